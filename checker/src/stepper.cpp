#include "semo/checker/stepper.hpp"

#include <stdexcept>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/trace.hpp"

namespace semo::checker {

struct Stepper::Impl {
  ir::Model model;
  CompiledModel cm;  // points into `model`: Impl never moves (it lives behind a unique_ptr)
  explicit Impl(const ir::Model& m) : model(m), cm(model) {}
};

Stepper::Stepper(const ir::Model& model) : impl_(std::make_unique<const Impl>(model)) {}
Stepper::~Stepper() = default;
Stepper::Stepper(Stepper&&) noexcept = default;
Stepper& Stepper::operator=(Stepper&&) noexcept = default;

const ir::Model& Stepper::model() const { return impl_->model; }

std::size_t Stepper::branches(std::size_t rule) const { return impl_->model.rules.at(rule).branches.size(); }

void Stepper::checkState(const State& s) const {
  if (s.size() != impl_->model.variables.size()) {
    throw std::invalid_argument("stepper: a state of " + std::to_string(s.size()) + " values for a model of " +
                                std::to_string(impl_->model.variables.size()) + " variables");
  }
}

Stepper::State Stepper::initial() const { return impl_->cm.initialValues(); }

bool Stepper::enabled(const State& s, std::size_t rule) const {
  checkState(s);
  return impl_->cm.rules().at(rule).guard.holds(s.data());
}

std::vector<std::size_t> Stepper::enabledRules(const State& s) const {
  checkState(s);
  // Every guard is tested: CompiledModel::candidateRules would skip most of them, but it indexes
  // by value and so needs every value within its range, which a state given here need not have.
  std::vector<std::size_t> out;
  const std::vector<CompiledRule>& rules = impl_->cm.rules();
  for (std::size_t r = 0; r < rules.size(); ++r) {
    if (rules[r].guard.holds(s.data())) out.push_back(r);
  }
  return out;
}

Stepper::Outcome Stepper::apply(const State& s, Choice choice) const {
  checkState(s);
  const ir::Model& m = impl_->model;
  const CompiledRule& rule = impl_->cm.rules().at(choice.rule);
  const ir::Rule& irRule = m.rules[choice.rule];
  if (choice.branch >= rule.branches.size()) {
    throw std::out_of_range("stepper: rule '" + irRule.name + "' has " + std::to_string(rule.branches.size()) +
                            " outcomes, not " + std::to_string(choice.branch + 1));
  }
  Outcome out;
  if (!rule.guard.holds(s.data())) {
    out.message = "rule '" + irRule.name + "' is not enabled";
    return out;
  }
  out.enabled = true;
  out.state.resize(s.size());
  impl_->cm.step(rule.branches[choice.branch], s.data(), out.state.data());
  for (const CompiledAssignment& a : rule.branches[choice.branch].assignments) {
    if (impl_->cm.inRange(a.var, out.state[a.var])) continue;
    out.outOfRange.push_back(a.var);
    const ir::Variable& v = m.variables[a.var];
    out.message += (out.message.empty() ? "rule '" + irRule.name + "' sets " : ", and ") + v.name + " to " +
                   std::to_string(out.state[a.var]) + ", outside its range " + std::to_string(v.min) + ".." + std::to_string(v.max);
  }
  return out;
}

std::optional<Stepper::State> Stepper::successor(const State& s, Choice choice, std::string* why) const {
  Outcome o = apply(s, choice);
  if (o.enabled && o.outOfRange.empty()) return std::move(o.state);
  if (why != nullptr) *why = o.message;
  return std::nullopt;
}

std::optional<Stepper::State> Stepper::successor(const State& s, std::size_t rule, std::string* why) const {
  const ir::Rule& r = impl_->model.rules.at(rule);
  if (r.branches.size() != 1) {
    checkState(s);
    if (why != nullptr) {
      *why = "rule '" + r.name + "' has " + std::to_string(r.branches.size()) + " outcomes: choose one (Stepper::Choice)";
    }
    return std::nullopt;
  }
  return successor(s, Choice{rule, 0}, why);
}

std::vector<std::pair<Stepper::Choice, Stepper::State>> Stepper::successors(const State& s) const {
  std::vector<std::pair<Choice, State>> out;
  for (std::size_t r : enabledRules(s)) {
    for (std::size_t b = 0; b < branches(r); ++b) {
      Outcome o = apply(s, {r, b});
      if (o.outOfRange.empty()) out.emplace_back(Choice{r, b}, std::move(o.state));
    }
  }
  return out;
}

std::optional<Stepper::Choice> Stepper::findChoice(const State& from, const State& to) const {
  checkState(to);
  for (std::size_t r : enabledRules(from)) {
    for (std::size_t b = 0; b < branches(r); ++b) {
      Outcome o = apply(from, {r, b});
      if (o.outOfRange.empty() && o.state == to) return Choice{r, b};
    }
  }
  return std::nullopt;
}

std::optional<std::size_t> Stepper::findRule(const State& from, const State& to) const {
  if (auto c = findChoice(from, to)) return c->rule;
  return std::nullopt;
}

bool Stepper::invariantHolds(const State& s, std::size_t property) const {
  checkState(s);
  return impl_->cm.invariants().at(property).eval(s.data()) != 0;
}

bool Stepper::validEnd(const State& s) const {
  checkState(s);
  const Program* end = impl_->cm.validEnd();
  return end == nullptr || end->eval(s.data()) != 0;
}

bool Stepper::deadlocked(const State& s) const {
  checkState(s);
  if (impl_->cm.validEnd() == nullptr || validEnd(s)) return false;
  for (const CompiledRule& r : impl_->cm.rules()) {
    if (r.guard.holds(s.data())) return false;
  }
  return true;
}

namespace {

std::string shown(const ir::Variable& v, std::int32_t value) {
  std::string text = valueText(v, value);
  if (value < v.min || value > v.max) text += " (outside " + std::to_string(v.min) + ".." + std::to_string(v.max) + ")";
  return text;
}

}  // namespace

std::string Stepper::describe(const State& s) const {
  checkState(s);
  std::string out;
  for (std::size_t v = 0; v < s.size(); ++v) {
    const ir::Variable& var = impl_->model.variables[v];
    out += (out.empty() ? "" : ", ") + var.name + "=" + shown(var, s[v]);
  }
  return out;
}

std::string Stepper::describeDifference(const State& a, const State& b) const {
  checkState(a);
  checkState(b);
  std::string out;
  for (std::size_t v = 0; v < a.size(); ++v) {
    if (a[v] == b[v]) continue;
    const ir::Variable& var = impl_->model.variables[v];
    out += (out.empty() ? "" : ", ") + var.name + ": " + shown(var, a[v]) + " -> " + shown(var, b[v]);
  }
  return out;
}

}  // namespace semo::checker
