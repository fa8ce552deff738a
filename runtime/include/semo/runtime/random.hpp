#pragma once
// Seeded random streams for the simulator: xoshiro256** seeded through SplitMix64. One stream per
// purpose (latency, loss, ...), derived from the run's seed and a stable hash of the purpose, so that
// adding a use of randomness somewhere does not shift the draws everywhere else. No allocation.
#include <cstdint>
#include <string_view>

namespace semo::runtime {

class RandomStream {
 public:
  explicit RandomStream(std::uint64_t seed);
  // A stream for (purpose, index), independent of every other purpose and index of the same seed.
  static RandomStream derive(std::uint64_t seed, std::string_view purpose, std::uint64_t index);
  std::uint64_t next();
  double uniform();             // [0, 1), 53 bits
  bool bernoulli(double p);     // always one draw, so that streams stay aligned whatever p is
  std::uint64_t below(std::uint64_t n);  // [0, n), unbiased; n > 0

  // The raw state, for tests against the reference sequence.
  static RandomStream fromState(std::uint64_t s0, std::uint64_t s1, std::uint64_t s2, std::uint64_t s3);

 private:
  RandomStream() = default;
  std::uint64_t s_[4] = {0, 0, 0, 0};
};

}  // namespace semo::runtime
