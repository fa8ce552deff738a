#include "semo/runtime/loss.hpp"

#include <charconv>
#include <fmt/format.h>

namespace semo::runtime {
namespace {

bool number(std::string_view text, double& out) {
  const auto r = std::from_chars(text.data(), text.data() + text.size(), out);
  return r.ec == std::errc() && r.ptr == text.data() + text.size();
}

}  // namespace

std::optional<LossModel> LossModel::parse(std::string_view text, std::string& error) {
  LossModel m;
  const std::string expected = "--loss-model: expected bernoulli, burst:N or gilbert:P,R, got '" + std::string(text) + "'";
  if (text == "bernoulli") return m;
  if (text.rfind("burst:", 0) == 0) {
    double n = 0;
    if (!number(text.substr(6), n) || n < 1 || n > 1000 || n != static_cast<int>(n)) {
      error = expected + " (N: a whole number of messages from 1 to 1000)";
      return std::nullopt;
    }
    m.kind = Kind::Burst;
    m.burst = static_cast<int>(n);
    return m;
  }
  if (text.rfind("gilbert:", 0) == 0) {
    const std::string_view rest = text.substr(8);
    const auto comma = rest.find(',');
    double g = 0, b = 0;
    if (comma == std::string_view::npos || !number(rest.substr(0, comma), g) || !number(rest.substr(comma + 1), b) || g < 0 || g > 1 ||
        b <= 0 || b > 1) {
      error = expected + " (P: chance to turn bad, in [0, 1]; R: chance to recover, in (0, 1])";
      return std::nullopt;
    }
    m.kind = Kind::GilbertElliott;
    m.goodToBad = g;
    m.badToGood = b;
    return m;
  }
  error = expected;
  return std::nullopt;
}

std::string LossModel::describe() const {
  switch (kind) {
    case Kind::Bernoulli: return "independent";
    case Kind::Burst: return fmt::format("in bursts of {}", burst);
    case Kind::GilbertElliott: return fmt::format("Gilbert-Elliott (bad {:g}, recover {:g})", goodToBad, badToGood);
  }
  return {};
}

bool LinkLoss::lose(RandomStream& random) {
  bool lost = false;
  switch (model_.kind) {
    case LossModel::Kind::Bernoulli: lost = random.bernoulli(model_.p); break;
    case LossModel::Kind::Burst:
      if (burstLeft_ > 0) {
        --burstLeft_;
        lost = true;
      } else if (random.bernoulli(model_.p)) {
        burstLeft_ = model_.burst - 1;
        lost = true;
      }
      break;
    case LossModel::Kind::GilbertElliott:
      bad_ = bad_ ? !random.bernoulli(model_.badToGood) : random.bernoulli(model_.goodToBad);
      lost = bad_;
      break;
  }
  lostInARow_ = lost ? lostInARow_ + 1 : 0;
  return lost;
}

bool LinkLoss::loseWithRetransmissions(RandomStream& random, int retransmissions) {
  for (int copy = 0; copy <= retransmissions; ++copy) {
    if (!lose(random)) return false;
  }
  return true;
}

}  // namespace semo::runtime
