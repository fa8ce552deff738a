// checkLasso (lasso_check.hpp): a lasso replayed on the compiled model and judged on its own.
#include "semo/checker/lasso_check.hpp"

#include <algorithm>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/fairness.hpp"

namespace semo::checker {

LassoCheck checkLasso(const ir::Model& model, const Trace& lasso, const ir::Property& property) {
  LassoCheck out;
  const CompiledModel cm(model);
  std::vector<std::vector<Value>> states{cm.initialValues()};
  if (!lasso.initial.empty() && lasso.initial != states[0]) {
    out.why = "the trace does not start in the model's initial state";
    return out;
  }
  if (lasso.loopStart > lasso.steps.size()) {
    out.why = "not a lasso: no loop start";
    return out;
  }
  std::vector<Value> next(states[0].size());
  for (std::size_t i = 0; i < lasso.steps.size(); ++i) {
    const Step& s = lasso.steps[i];
    const std::vector<Value>& here = states.back();
    if (s.rule >= cm.rules().size() || s.branch >= cm.rules()[s.rule].branches.size()) {
      out.why = "step " + std::to_string(i + 1) + ": no such rule or outcome";
      return out;
    }
    const CompiledRule& rule = cm.rules()[s.rule];
    if (!rule.guard.holds(here.data())) {
      out.why = "step " + std::to_string(i + 1) + ": rule '" + model.rules[s.rule].name + "' is not enabled";
      return out;
    }
    if (!cm.step(rule.branches[s.branch], here.data(), next.data())) {
      out.why = "step " + std::to_string(i + 1) + ": an update leaves its range";
      return out;
    }
    std::vector<Value> expected = here;
    for (const Change& c : s.changes) expected[c.var] = c.after;
    if (!s.changes.empty() && expected != next) {
      out.why = "step " + std::to_string(i + 1) + ": the rule does not change what the trace says";
      return out;
    }
    states.push_back(next);
  }
  const std::size_t l = lasso.loopStart;
  const bool stays = l == lasso.steps.size();
  if (!stays && states.back() != states[l]) {
    out.why = "the loop does not come back to the state it starts in";
    return out;
  }
  out.valid = true;

  // Fairness on the loop: the states it visits (or the one the run stays in) and the rules it takes.
  const Fairness fairness = Fairness::of(model);
  const Sensing sensing = Sensing::in(model);
  std::vector<char> taken(fairness.groups(), 0);
  std::vector<std::int8_t> decided(sensing.points, 0);  // bit 1: false, bit 2: true
  for (std::size_t i = l; i < lasso.steps.size(); ++i) {
    const std::size_t r = lasso.steps[i].rule;
    if (fairness.groupOf[r] != Fairness::kNone) taken[fairness.groupOf[r]] = 1;
    if (!property.settled) continue;
    for (const Sensing::Decision& d : sensing.of[r]) {
      decided[d.point] = static_cast<std::int8_t>(decided[d.point] | (d.holds ? 2 : 1));
      if (decided[d.point] == 3 && std::find(out.unsettled.begin(), out.unsettled.end(), r) == out.unsettled.end()) {
        out.unsettled.push_back(static_cast<std::uint32_t>(r));
      }
    }
  }
  const std::size_t loopEnd = stays ? states.size() : states.size() - 1;  // the last state repeats the first
  const std::size_t visited = loopEnd - l;
  for (std::uint32_t g = 0; g < fairness.groups(); ++g) {
    if (taken[g]) continue;
    std::size_t on = 0;
    for (std::size_t i = l; i < loopEnd; ++i) {
      bool any = false;
      for (std::uint32_t r : fairness.members[g]) any = any || cm.rules()[r].guard.holds(states[i].data());
      on += any ? 1 : 0;
    }
    const bool unfair = fairness.strong[g] ? on > 0 : on == visited;
    if (unfair) out.unfairGroups.push_back(g);
  }

  // The property on the word: the prefix, then the loop for ever (a run that stays repeats its last state).
  const std::size_t n = stays ? states.size() : states.size() - 1;
  const std::size_t loopAt = stays ? states.size() - 1 : l;
  std::vector<std::pair<const ir::Expr*, Program>> programs;
  auto atom = [&](const ir::Expr& e, std::size_t i) {
    for (auto& [expr, program] : programs) {
      if (expr == &e) return program.eval(states[i].data()) != 0;
    }
    programs.emplace_back(&e, Program(e));
    return programs.back().second.eval(states[i].data()) != 0;
  };
  out.violates = !ltlOnLasso(property.formula, n, loopAt, atom);
  return out;
}

}  // namespace semo::checker
