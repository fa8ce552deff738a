// xoshiro256** (Blackman and Vigna, 2018) with SplitMix64 seeding, from the published description.
#include "semo/runtime/random.hpp"

namespace semo::runtime {
namespace {

__extension__ using U128 = unsigned __int128;  // GCC's 128-bit product, for Lemire's method

std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

std::uint64_t splitmix(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

RandomStream::RandomStream(std::uint64_t seed) {
  for (std::uint64_t& s : s_) s = splitmix(seed);
}

RandomStream RandomStream::fromState(std::uint64_t s0, std::uint64_t s1, std::uint64_t s2, std::uint64_t s3) {
  RandomStream r;
  r.s_[0] = s0, r.s_[1] = s1, r.s_[2] = s2, r.s_[3] = s3;
  return r;
}

RandomStream RandomStream::derive(std::uint64_t seed, std::string_view purpose, std::uint64_t index) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a of the purpose
  for (unsigned char c : purpose) h = (h ^ c) * 0x100000001b3ULL;
  std::uint64_t mix = seed;
  std::uint64_t a = splitmix(mix) ^ h;
  std::uint64_t b = splitmix(a) ^ index;
  return RandomStream(splitmix(b));
}

std::uint64_t RandomStream::next() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double RandomStream::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

bool RandomStream::bernoulli(double p) {
  const double u = uniform();
  return p > 0 && (p >= 1 || u < p);
}

std::uint64_t RandomStream::below(std::uint64_t n) {
  // Lemire's multiply-and-reject: unbiased without a division in the common case.
  U128 m = static_cast<U128>(next()) * n;
  auto low = static_cast<std::uint64_t>(m);
  if (low < n) {
    const std::uint64_t threshold = -n % n;
    while (low < threshold) {
      m = static_cast<U128>(next()) * n;
      low = static_cast<std::uint64_t>(m);
    }
  }
  return static_cast<std::uint64_t>(m >> 64);
}

}  // namespace semo::runtime
