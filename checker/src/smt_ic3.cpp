#include "smt_ic3.hpp"

#include <z3_spacer.h>

namespace semo::checker::detail {

namespace {

z3::expr applied(const z3::func_decl& relation, const z3::expr_vector& args) { return relation(args); }

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

// The invariant Spacer found for Reach, as a formula over `vars`.
z3::expr invariantOver(z3::fixedpoint& fp, z3::func_decl& reach, const z3::expr_vector& vars) {
  z3::expr cover = fp.get_cover_delta(-1, reach);
  return cover.substitute(vars);  // de Bruijn variable i is the i-th argument
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

Ic3Outcome proveWithIc3(z3::context& ctx, const TransitionSystem& sys, unsigned timeoutMs) {
  Ic3Outcome out;
  z3::fixedpoint fp(ctx);
  z3::params params(ctx);
  params.set("engine", "spacer");
  if (timeoutMs != 0) params.set("timeout", timeoutMs);
  fp.set(params);
  z3::sort_vector sorts(ctx);
  for (const z3::expr& v : sys.current) sorts.push_back(v.get_sort());
  z3::func_decl reach = ctx.function("Reach", sorts, ctx.bool_sort());
  z3::func_decl errorHead = ctx.function("Error", 0, nullptr, ctx.bool_sort());
  fp.register_relation(reach);
  fp.register_relation(errorHead);
  z3::expr_vector bound(ctx);
  for (const z3::expr& v : sys.current) bound.push_back(v);
  for (const z3::expr& v : sys.next) bound.push_back(v);
  for (const z3::expr& v : sys.inputs) bound.push_back(v);
  addRule(fp, ctx, bound, sys.initial, applied(reach, sys.current), "init");
  addRule(fp, ctx, bound, applied(reach, sys.current) && sys.step, applied(reach, sys.next), "step");
  addRule(fp, ctx, bound, applied(reach, sys.current) && sys.error, errorHead(), "error");
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
  // Spacer's answer is not taken on trust: the invariant must hold initially, be kept by every
  // step, and exclude the error.
  z3::expr inv0 = invariantOver(fp, reach, sys.current), inv1 = invariantOver(fp, reach, sys.next);
  bool initiation = unsatisfiable(ctx, sys.initial && !inv0, timeoutMs);
  bool consecution = initiation && unsatisfiable(ctx, inv0 && sys.checkStep && !inv1, timeoutMs);
  bool safe = consecution && unsatisfiable(ctx, inv0 && sys.error, timeoutMs);
  if (!safe) {
    out.note = std::string("IC3's invariant did not pass the independent check (") +
               (!initiation ? "initiation" : !consecution ? "consecution" : "it does not exclude the error") + ")";
    return out;
  }
  out.kind = Ic3Outcome::Kind::Proven;
  out.conjuncts = inv0.is_and() ? inv0.num_args() : 1;
  out.invariant = inv0;
  return out;
}

Ic3Outcome proveWithIc3(z3::context& ctx, SmtEncoding& enc, const z3::expr& error, unsigned timeoutMs, const z3::expr& assumed) {
  z3::expr_vector inputs(ctx);
  inputs.push_back(enc.action(0));
  // The compact form of the same step relation for the check: the solver decides it many times
  // faster; the form by cases is the one Spacer projects best.
  TransitionSystem sys{enc.state(0), enc.state(1), inputs, enc.initial(0), assumed && enc.transitionByCases(0) && enc.inRange(1),
                       assumed && enc.transition(0) && enc.inRange(1), assumed && error};
  return proveWithIc3(ctx, sys, timeoutMs);
}

}  // namespace semo::checker::detail
