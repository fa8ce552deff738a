// Continuous time (checker/ctmc.hpp): uniformisation against closed forms, and against SUNDIALS
// CVODE integrating pi' = pi Q.
#include <gtest/gtest.h>

#include <cmath>

#include "semo/checker/ctmc.hpp"

namespace semo::checker {
namespace {

// Two states, rate a from 0 to 1 and b back: pi_1(t) = a / (a + b) (1 - e^{-(a + b) t}).
TEST(Ctmc, TwoStatesMatchTheClosedForm) {
  const double a = 2.0, b = 0.5;
  const RateMatrix q{2, {{0, 1, a}, {1, 0, b}}};
  for (double t : {0.0, 0.1, 1.0, 3.0, 40.0}) {
    const double expected = a / (a + b) * (1 - std::exp(-(a + b) * t));
    const Transient u = transientByUniformisation(q, {1.0, 0.0}, t);
    EXPECT_NEAR(u.distribution[1], expected, 1e-10) << "t=" << t << " " << u.method;
    EXPECT_NEAR(u.distribution[0] + u.distribution[1], 1.0, 1e-12);
    EXPECT_NEAR(transientByCvode(q, {1.0, 0.0}, t).distribution[1], expected, 1e-8) << "t=" << t;
  }
}

// k phases of rate lambda in a row (Erlang): P(through all by t) = 1 - sum_{i<k} e^{-lt} (lt)^i / i!.
// The chain is stiff-free but long; q t = 500 tests the weights around a far mode.
TEST(Ctmc, AnErlangChainMatchesItsDistributionAndCvodeAgrees) {
  const std::size_t k = 12;
  const double lambda = 5.0;
  RateMatrix q{k + 1, {}};
  for (std::size_t i = 0; i < k; ++i) q.rates.push_back({i, i + 1, lambda});
  std::vector<double> start(k + 1, 0.0);
  start[0] = 1.0;
  for (double t : {0.5, 2.4, 5.0, 100.0}) {
    double below = 0, term = std::exp(-lambda * t);
    for (std::size_t i = 0; i < k; ++i) below += term, term *= lambda * t / static_cast<double>(i + 1);
    const Transient u = transientByUniformisation(q, start, t);
    EXPECT_NEAR(u.distribution[k], 1.0 - below, 1e-10) << "t=" << t << " " << u.method;
    const Transient c = transientByCvode(q, start, t);
    for (std::size_t s = 0; s <= k; ++s) EXPECT_NEAR(c.distribution[s], u.distribution[s], 1e-7) << "t=" << t << " state " << s;
  }
}

TEST(Ctmc, BadRatesAreErrors) {
  EXPECT_THROW((void)transientByUniformisation(RateMatrix{2, {{0, 0, 1.0}}}, {1, 0}, 1), MarkovError);
  EXPECT_THROW((void)transientByUniformisation(RateMatrix{2, {{0, 1, -1.0}}}, {1, 0}, 1), MarkovError);
  EXPECT_THROW((void)transientByCvode(RateMatrix{2, {{0, 1, 1.0}}}, {1}, 1), MarkovError);
}

}  // namespace
}  // namespace semo::checker
