#include "smt_ic3.hpp"

#include <z3_spacer.h>

namespace semo::checker::detail {

namespace {

z3::expr_vector boundVariables(z3::context& ctx, SmtEncoding& enc) {
  z3::expr_vector all(ctx);
  for (std::size_t k = 0; k < 2; ++k) {
    for (const z3::expr& v : enc.state(k)) all.push_back(v);
  }
  all.push_back(enc.action(0));
  return all;
}

z3::expr reachAt(const z3::func_decl& reach, SmtEncoding& enc, std::size_t k) {
  z3::expr_vector args(reach.ctx());
  for (const z3::expr& v : enc.state(k)) args.push_back(v);
  return reach(args);
}

void addRule(z3::fixedpoint& fp, z3::context& ctx, const z3::expr_vector& bound, const z3::expr& body, const z3::expr& head,
             const char* name) {
  z3::expr rule = z3::forall(bound, z3::implies(body, head));
  fp.add_rule(rule, ctx.str_symbol(name));
}

std::uint32_t stepsAlongTrace(z3::context& ctx, z3::fixedpoint& fp) {
  // The rule names from the error back to the initial state, separated by ';'.
  std::string names = z3::symbol(ctx, Z3_fixedpoint_get_rule_names_along_trace(ctx, fp)).str();
  std::uint32_t steps = 0;
  for (std::size_t at = names.find("step"); at != std::string::npos; at = names.find("step", at + 1)) ++steps;
  return steps;
}

// The invariant Spacer found for Reach, as a formula over step k of the encoding.
z3::expr invariantAt(z3::fixedpoint& fp, z3::func_decl& reach, SmtEncoding& enc, std::size_t k) {
  z3::expr cover = fp.get_cover_delta(-1, reach);
  z3::expr_vector to(reach.ctx());
  for (const z3::expr& v : enc.state(k)) to.push_back(v);
  return cover.substitute(to);  // de Bruijn variable i is the i-th argument
}

bool unsatisfiable(z3::context& ctx, const z3::expr& formula, unsigned timeoutMs) {
  z3::solver s(ctx);
  if (timeoutMs != 0) {
    z3::params p(ctx);
    p.set("timeout", timeoutMs);
    s.set(p);
  }
  s.add(formula);
  return s.check() == z3::unsat;
}

}  // namespace

Ic3Outcome proveWithIc3(z3::context& ctx, SmtEncoding& enc, const z3::expr& error, unsigned timeoutMs) {
  Ic3Outcome out;
  z3::fixedpoint fp(ctx);
  z3::params params(ctx);
  params.set("engine", "spacer");
  if (timeoutMs != 0) params.set("timeout", timeoutMs);
  fp.set(params);
  z3::sort_vector sorts(ctx);
  for (std::size_t v = 0; v < enc.state(0).size(); ++v) sorts.push_back(ctx.int_sort());
  z3::func_decl reach = ctx.function("Reach", sorts, ctx.bool_sort());
  z3::func_decl errorHead = ctx.function("Error", 0, nullptr, ctx.bool_sort());
  fp.register_relation(reach);
  fp.register_relation(errorHead);
  const z3::expr_vector bound = boundVariables(ctx, enc);
  const z3::expr step = enc.transitionByCases(0) && enc.inRange(1);
  addRule(fp, ctx, bound, enc.initial(0), reachAt(reach, enc, 0), "init");
  addRule(fp, ctx, bound, reachAt(reach, enc, 0) && step, reachAt(reach, enc, 1), "step");
  addRule(fp, ctx, bound, reachAt(reach, enc, 0) && error, errorHead(), "error");
  z3::expr query = errorHead();
  z3::check_result r = z3::unknown;
  try {
    r = fp.query(query);
  } catch (const z3::exception& e) {
    out.note = std::string("IC3 stopped: ") + e.msg();
    return out;
  }
  if (r == z3::sat) {
    out.kind = Ic3Outcome::Kind::Violated;
    out.depth = stepsAlongTrace(ctx, fp);
    return out;
  }
  if (r == z3::unknown) {
    out.note = "IC3 gave up: " + fp.reason_unknown();
    return out;
  }
  // Spacer's answer is not taken on trust: the invariant must hold initially, be kept by every step
  // within the ranges, and exclude the error.
  z3::expr inv0 = invariantAt(fp, reach, enc, 0), inv1 = invariantAt(fp, reach, enc, 1);
  bool initiation = unsatisfiable(ctx, enc.initial(0) && !inv0, timeoutMs);
  // The compact form of the same step relation: the solver decides it many times faster.
  bool consecution = initiation && unsatisfiable(ctx, inv0 && enc.transition(0) && enc.inRange(1) && !inv1, timeoutMs);
  bool safe = consecution && unsatisfiable(ctx, inv0 && error, timeoutMs);
  if (!safe) {
    out.note = std::string("IC3's invariant did not pass the independent check (") +
               (!initiation ? "initiation" : !consecution ? "consecution" : "it does not exclude the error") + ")";
    return out;
  }
  out.kind = Ic3Outcome::Kind::Proven;
  out.conjuncts = inv0.is_and() ? inv0.num_args() : 1;
  return out;
}

}  // namespace semo::checker::detail
