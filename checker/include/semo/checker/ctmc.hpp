#pragma once
// Continuous time: the transient distribution of a continuous-time Markov chain, pi(t) with
// pi' = pi Q, by uniformisation (Jensen's method: pi(t) = sum_k Poisson(k; q t) pi0 P^k with
// P = I + Q / q), and the same by integrating the differential equations with SUNDIALS CVODE (BDF,
// dense Newton), which the tests use to cross-check the first. specs/quantitative.md.
#include <cstddef>
#include <vector>

#include "semo/checker/markov.hpp"

namespace semo::checker {

struct RateMatrix {
  std::size_t states = 0;
  struct Rate {
    std::size_t from, to;
    double rate;  // > 0, from != to
  };
  std::vector<Rate> rates;  // the diagonal is minus each row's sum
};

struct Transient {
  std::vector<double> distribution;
  std::size_t terms = 0;  // uniformisation: Poisson terms summed (0 for CVODE)
  std::string method;
};

// pi(t) from pi0, the Poisson series cut where the weights left out add up to at most `epsilon`.
Transient transientByUniformisation(const RateMatrix& q, const std::vector<double>& initial, double t, double epsilon = 1e-12);
// The same by CVODE (relative tolerance 1e-10, absolute 1e-12); for cross-checks of small chains.
Transient transientByCvode(const RateMatrix& q, const std::vector<double>& initial, double t);

}  // namespace semo::checker
