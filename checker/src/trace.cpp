#include "semo/checker/trace.hpp"

#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "semo/checker/stepper.hpp"

namespace semo::checker {

std::string valueText(const ir::Variable& v, std::int32_t value) {
  if (v.isBool && (value == 0 || value == 1)) return value != 0 ? "true" : "false";
  auto index = static_cast<std::size_t>(static_cast<std::int64_t>(value) - v.min);
  if (value >= v.min && index < v.valueNames.size()) return v.valueNames[index];
  return std::to_string(value);
}

namespace {

std::string robotName(const ir::Model& m, const ir::Rule& r) {
  return r.robot == ir::kNoRobot ? "-" : m.robots.at(static_cast<std::size_t>(r.robot));
}

// A lasso's fair steps that are enabled somewhere on the loop but never taken there: weak fairness
// does not force them (each is disabled somewhere on the loop), which is often the answer to "why
// does this never happen?". One line per fairness group, with the steps before which it is enabled.
std::string enabledButNotTaken(const ir::Model& m, const Trace& t) {
  if (t.loopStart >= t.steps.size()) return {};
  const Stepper stepper(m);
  std::vector<std::int32_t> state = t.initial;
  for (std::size_t i = 0; i < t.loopStart; ++i) {
    for (const Change& c : t.steps[i].changes) state[c.var] = c.after;
  }
  auto groupOf = [&](std::size_t r) { return m.rules[r].fairGroup.empty() ? m.rules[r].name : m.rules[r].fairGroup; };
  std::map<std::string, std::vector<std::size_t>> enabledBefore;  // group -> loop steps (1-based) before which it is enabled
  std::map<std::string, std::size_t> firstRule;
  std::map<std::string, bool> taken;
  for (std::size_t i = t.loopStart; i < t.steps.size(); ++i) {
    for (std::size_t r : stepper.enabledRules(state)) {
      if (!m.rules[r].weaklyFair && !m.rules[r].stronglyFair) continue;
      std::vector<std::size_t>& at = enabledBefore[groupOf(r)];
      if (at.empty() || at.back() != i + 1) at.push_back(i + 1);
      firstRule.emplace(groupOf(r), r);
    }
    taken[groupOf(t.steps[i].rule)] = true;
    for (const Change& c : t.steps[i].changes) state[c.var] = c.after;
  }
  std::string out;
  for (const auto& [group, at] : enabledBefore) {
    if (taken[group]) continue;
    const ir::Rule& r = m.rules[firstRule[group]];
    std::string steps;
    for (std::size_t k = 0; k < at.size() && k < 6; ++k) steps += (k == 0 ? "" : ", ") + std::to_string(at[k]);
    if (at.size() > 6) steps += ", ...";
    out += "       [" + robotName(m, r) + "] " + (r.label.empty() ? r.name : r.label) + "  (enabled before step" + (at.size() == 1 ? " " : "s ") +
           steps + ")\n";
  }
  if (out.empty()) return {};
  return "  fair steps enabled on the loop but never taken (each is disabled somewhere on it, so fairness does not force it):\n" + out;
}

}  // namespace

// The facts a knowledge count holds after a change, as a trace shows them (knowledgeWitness, trace.hpp).
std::string heldText(const std::vector<std::string>& facts) {
  std::string out;
  for (const std::string& f : facts) out += (out.empty() ? "" : ", ") + f;
  return out.empty() ? "none" : out;
}

std::string traceToText(const ir::Model& m, const Trace& t) {
  std::ostringstream out;
  out << "counterexample for " << t.property << " (" << t.kind << "): " << t.steps.size() << " step"
      << (t.steps.size() == 1 ? "" : "s") << "\n";
  const KnowledgeWitness known = knowledgeWitness(m, t);
  if (known.named) out << "  (facts: the model counts a robot's facts; the names are one assignment that fits the counts)\n";
  for (std::size_t i = 0; i < t.steps.size(); ++i) {
    if (i == t.loopStart) out << "  -- loop starts here (the steps below repeat for ever) --\n";
    const Step& s = t.steps[i];
    const ir::Rule& r = m.rules.at(s.rule);
    out << "  " << (i + 1) << ". [" << robotName(m, r) << "] " << (r.label.empty() ? r.name : r.label);
    if (r.branches.size() > 1) out << " (outcome " << (s.branch + 1) << ")";
    if (r.kind != ir::RuleKind::Step) out << "  {" << ir::kindName(r.kind) << "}";
    if (!r.origin.empty()) out << "  at " << r.origin.text();
    out << "\n";
    for (std::size_t j = 0; j < s.changes.size(); ++j) {
      const Change& c = s.changes[j];
      const ir::Variable& v = m.variables.at(c.var);
      out << "       " << v.name << ": " << valueText(v, c.before) << " -> " << valueText(v, c.after);
      if (known.named && !v.facts.empty()) out << "  (holds " << heldText(known.held[i][j]) << ")";
      out << "\n";
    }
  }
  if (t.kind == "deadlock") {
    out << "  then no rule is enabled, and the state is not a valid end state; still running:\n";
    // Who is stuck where: every program counter that is not at its end, for live robots.
    std::vector<std::int32_t> final = t.initial;
    for (const Step& s : t.steps) {
      for (const Change& c : s.changes) final[c.var] = c.after;
    }
    for (ir::VarId v = 0; v < final.size(); ++v) {
      const ir::Variable& var = m.variables[v];
      if (var.name.find(".pc.") == std::string::npos || final[v] == var.min) continue;
      if (var.robot != ir::kNoRobot) {
        auto alive = m.find(m.robots[static_cast<std::size_t>(var.robot)] + ".alive");
        if (alive && final[*alive] == 0) continue;
      }
      out << "       " << var.name << " = " << valueText(var, final[v]) << "\n";
    }
  }
  if (t.kind == "lasso") {
    if (t.loopStart >= t.steps.size()) {
      out << "  then the run stays in this state for ever (no rule that must be taken in the end is enabled), and "
          << t.property << " does not hold\n";
    } else {
      out << "  then back to the state before step " << (t.loopStart + 1) << ": the loop repeats for ever, and "
          << t.property << " does not hold\n";
      out << enabledButNotTaken(m, t);
    }
  }
  if (t.kind == "invariant") out << "  then " << t.property << " does not hold\n";
  if (t.kind == "range") out << "  the last step assigns a value outside a variable's declared range (a modelling error)\n";
  return out.str();
}

std::string traceToJson(const ir::Model& m, const Trace& t) {
  using nlohmann::json;
  json initial = json::object(), initialText = json::object();
  for (ir::VarId v = 0; v < t.initial.size(); ++v) {
    initial[m.variables[v].name] = t.initial[v];
    initialText[m.variables[v].name] = valueText(m.variables[v], t.initial[v]);  // as "fromText"/"toText" show values
  }
  const KnowledgeWitness known = knowledgeWitness(m, t);
  json steps = json::array();
  for (std::size_t i = 0; i < t.steps.size(); ++i) {
    const Step& s = t.steps[i];
    const ir::Rule& r = m.rules.at(s.rule);
    json changes = json::array();
    for (std::size_t j = 0; j < s.changes.size(); ++j) {
      const Change& c = s.changes[j];
      const ir::Variable& v = m.variables.at(c.var);
      json change = {{"var", v.name}, {"from", c.before}, {"to", c.after},
                     {"fromText", valueText(v, c.before)}, {"toText", valueText(v, c.after)}};
      if (known.named && !v.facts.empty()) change["facts"] = known.held[i][j];
      changes.push_back(std::move(change));
    }
    json step = {{"step", i + 1}, {"rule", r.name}, {"kind", ir::kindName(r.kind)}, {"label", r.label},
                 {"origin", r.origin.text()}, {"branch", s.branch}, {"changes", changes}};
    step["robot"] = r.robot == ir::kNoRobot ? json(nullptr) : json(m.robots.at(static_cast<std::size_t>(r.robot)));
    steps.push_back(step);
  }
  json root = {{"property", t.property}, {"kind", t.kind}, {"initial", initial}, {"initialText", initialText}, {"steps", steps}};
  if (t.loopStart != SIZE_MAX) root["loopStart"] = t.loopStart + 1;
  return root.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace semo::checker
