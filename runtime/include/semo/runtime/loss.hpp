#pragma once
// How the simulated network loses messages (the simulator's --loss and --loss-model): independent
// losses, bursts of a fixed length, or a two-state Gilbert-Elliott channel per link. Each link keeps
// its own state; every decision draws from the stream it is given, so runs are reproducible.
#include <optional>
#include <string>
#include <string_view>

#include "semo/runtime/random.hpp"

namespace semo::runtime {

struct LossModel {
  enum class Kind { Bernoulli, Burst, GilbertElliott };
  Kind kind = Kind::Bernoulli;
  double p = 0;                 // Bernoulli, Burst: probability that a message starts a loss
  int burst = 1;                // Burst: every loss is followed by burst - 1 more on the same link
  double goodToBad = 0, badToGood = 1;  // GilbertElliott: per message; every message is lost in Bad

  // "bernoulli", "burst:N" or "gilbert:G2B,B2G"; nullopt with `error` set otherwise.
  static std::optional<LossModel> parse(std::string_view text, std::string& error);
  [[nodiscard]] std::string describe() const;
};

class LinkLoss {
 public:
  explicit LinkLoss(const LossModel& model) : model_(model) {}
  // Decides one message.
  bool lose(RandomStream& random);
  // A message sent 1 + retransmissions times: lost only if every copy is.
  bool loseWithRetransmissions(RandomStream& random, int retransmissions);
  [[nodiscard]] int lostInARow() const { return lostInARow_; }

 private:
  LossModel model_;
  int burstLeft_ = 0;
  bool bad_ = false;
  int lostInARow_ = 0;
};

}  // namespace semo::runtime
