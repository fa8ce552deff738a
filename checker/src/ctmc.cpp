#include "semo/checker/ctmc.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <cvode/cvode.h>
#include <fmt/format.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace semo::checker {
namespace {

void validate(const RateMatrix& q, const std::vector<double>& initial, double t) {
  if (initial.size() != q.states) throw MarkovError("the initial distribution has the wrong size");
  if (!(t >= 0) || !std::isfinite(t)) throw MarkovError("the time must be finite and not negative");
  for (const RateMatrix::Rate& r : q.rates) {
    if (r.from >= q.states || r.to >= q.states || r.from == r.to || !(r.rate > 0) || !std::isfinite(r.rate)) {
      throw MarkovError("a rate must be positive and finite, between two different states");
    }
  }
}

std::vector<double> exitRates(const RateMatrix& q) {
  std::vector<double> out(q.states, 0.0);
  for (const RateMatrix::Rate& r : q.rates) out[r.from] += r.rate;
  return out;
}

}  // namespace

Transient transientByUniformisation(const RateMatrix& q, const std::vector<double>& initial, double t, double epsilon) {
  validate(q, initial, t);
  const std::vector<double> exit = exitRates(q);
  const double lambda = std::max(1e-300, *std::max_element(exit.begin(), exit.end(), [](double a, double b) { return a < b; }));
  const double qt = lambda * t;
  // Poisson weights around the mode, unnormalised (the mode's is 1: no underflow of e^{-qt} for a
  // large qt), out to where the weights left out on each side add up to at most epsilon / 2 of the
  // mode's (each tail is bounded by a geometric series), hence of the total; then normalised.
  const auto mode = static_cast<std::size_t>(std::floor(qt));
  std::vector<double> left{1.0}, right;
  for (std::size_t k = mode; k > 0; --k) {
    const double ratio = static_cast<double>(k) / qt;  // w(k - 1) = w(k) k / qt, and k / qt < 1 below the mode
    if (left.back() * ratio / (1.0 - ratio) <= epsilon / 2) break;
    left.push_back(left.back() * ratio);
  }
  for (double w = 1.0, k = static_cast<double>(mode) + 1;; ++k) {
    const double ratio = qt / k;  // w(k) = w(k - 1) qt / k, below 1 above the mode
    if (ratio < 1 && w * ratio / (1.0 - ratio) <= epsilon / 2) break;
    w *= ratio;
    right.push_back(w);
    if (right.size() > 100'000'000) throw MarkovError("uniformisation needs more than 10^8 terms: q t is too large");
  }
  const std::size_t first = mode + 1 - left.size();
  std::vector<double> weight(left.rbegin(), left.rend());
  weight.insert(weight.end(), right.begin(), right.end());
  double total = 0;
  for (double w : weight) total += w;
  // pi0 P^k for k = 0 .. first + weights, summed with their weights.
  std::vector<double> v = initial, next(q.states), out(q.states, 0.0);
  for (std::size_t k = 0; k < first + weight.size(); ++k) {
    if (k >= first) {
      const double w = weight[k - first] / total;
      for (std::size_t s = 0; s < q.states; ++s) out[s] += w * v[s];
    }
    for (std::size_t s = 0; s < q.states; ++s) next[s] = v[s] * (1.0 - exit[s] / lambda);
    for (const RateMatrix::Rate& r : q.rates) next[r.to] += v[r.from] * r.rate / lambda;
    std::swap(v, next);
  }
  Transient result;
  result.distribution = std::move(out);
  result.terms = weight.size();
  result.method = fmt::format("uniformisation at rate {:g}: {} Poisson terms ({} to {}), the weight left out at most {:g}", lambda, weight.size(), first,
                              first + weight.size() - 1, epsilon);
  return result;
}

Transient transientByCvode(const RateMatrix& q, const std::vector<double>& initial, double t) {
  validate(q, initial, t);
  struct Solver {
    SUNContext context = nullptr;
    N_Vector y = nullptr;
    SUNMatrix matrix = nullptr;
    SUNLinearSolver linear = nullptr;
    void* cvode = nullptr;
    ~Solver() {
      if (cvode != nullptr) CVodeFree(&cvode);
      if (linear != nullptr) SUNLinSolFree(linear);
      if (matrix != nullptr) SUNMatDestroy(matrix);
      if (y != nullptr) N_VDestroy(y);
      if (context != nullptr) SUNContext_Free(&context);
    }
  } s;
  auto check = [](int code, const char* what) {
    if (code < 0) throw MarkovError(fmt::format("CVODE: {} failed ({})", what, code));
  };
  const auto n = static_cast<sunindextype>(q.states);
  check(SUNContext_Create(nullptr, &s.context), "SUNContext_Create");
  s.y = N_VNew_Serial(n, s.context);
  if (s.y == nullptr) throw MarkovError("CVODE: cannot allocate the state vector");
  for (sunindextype i = 0; i < n; ++i) NV_Ith_S(s.y, i) = initial[static_cast<std::size_t>(i)];
  s.cvode = CVodeCreate(CV_BDF, s.context);
  if (s.cvode == nullptr) throw MarkovError("CVODE: CVodeCreate failed");
  // pi' = pi Q: what flows out of each state and into the others.
  auto rhs = [](sunrealtype, N_Vector y, N_Vector dy, void* data) -> int {
    const auto* rates = static_cast<const RateMatrix*>(data);
    N_VConst(0.0, dy);
    for (const RateMatrix::Rate& r : rates->rates) {
      const double flow = NV_Ith_S(y, static_cast<sunindextype>(r.from)) * r.rate;
      NV_Ith_S(dy, static_cast<sunindextype>(r.from)) -= flow;
      NV_Ith_S(dy, static_cast<sunindextype>(r.to)) += flow;
    }
    return 0;
  };
  check(CVodeInit(s.cvode, rhs, 0.0, s.y), "CVodeInit");
  check(CVodeSStolerances(s.cvode, 1e-10, 1e-12), "CVodeSStolerances");
  check(CVodeSetUserData(s.cvode, const_cast<RateMatrix*>(&q)), "CVodeSetUserData");
  check(CVodeSetMaxNumSteps(s.cvode, 1'000'000), "CVodeSetMaxNumSteps");
  s.matrix = SUNDenseMatrix(n, n, s.context);
  s.linear = SUNLinSol_Dense(s.y, s.matrix, s.context);
  if (s.matrix == nullptr || s.linear == nullptr) throw MarkovError("CVODE: cannot allocate the linear solver");
  check(CVodeSetLinearSolver(s.cvode, s.linear, s.matrix), "CVodeSetLinearSolver");
  Transient out;
  if (t > 0) {
    sunrealtype reached = 0;
    check(CVodeSetStopTime(s.cvode, t), "CVodeSetStopTime");
    check(CVode(s.cvode, t, s.y, &reached, CV_NORMAL), "CVode");
  }
  for (sunindextype i = 0; i < n; ++i) out.distribution.push_back(NV_Ith_S(s.y, i));
  out.method = "CVODE (BDF, dense Newton; relative tolerance 1e-10, absolute 1e-12)";
  return out;
}

}  // namespace semo::checker
