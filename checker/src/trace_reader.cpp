#include "semo/checker/trace_reader.hpp"

#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string_view>
#include <unordered_map>

#include "semo/checker/fingerprint.hpp"
#include "semo/frontend/json_text.hpp"
#include "semo/runtime/json_positions.hpp"

namespace semo::checker {

const char* traceKindName(ReplayedTrace::Kind kind) {
  switch (kind) {
    case ReplayedTrace::Kind::Invariant: return "invariant";
    case ReplayedTrace::Kind::Deadlock: return "deadlock";
    case ReplayedTrace::Kind::ModelError: return "range";
    case ReplayedTrace::Kind::Lasso: return "lasso";
  }
  return "invariant";
}

Trace ReplayedTrace::toTrace() const {
  Trace t;
  t.property = property;
  t.kind = traceKindName(kind);
  if (!states.empty()) t.initial = states.front();
  for (std::size_t k = 0; k < rules.size() && k + 1 < states.size(); ++k) {
    Step step{rules[k], branches[k], {}};
    const Stepper::State &before = states[k], &after = states[k + 1];
    for (ir::VarId v = 0; v < before.size() && v < after.size(); ++v) {
      if (before[v] != after[v]) step.changes.push_back({v, before[v], after[v]});
    }
    t.steps.push_back(std::move(step));
  }
  t.loopStart = loopStart;
  return t;
}

namespace {

using nlohmann::json;

// check --json nests six deep (root, properties, property, counterexample, steps, step, changes,
// change): anything far deeper is not a trace, and is refused before the parser sees it.
constexpr std::size_t kMaxDepth = 64;

struct Invalid {};

std::string pointerKey(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
  return out;
}

std::string inQuotes(const std::string& s) { return "'" + s + "'"; }

std::string withSuggestion(std::string message, const std::string& name, const std::vector<std::string>& candidates) {
  std::string hint = suggestClosest(name, candidates);
  return hint.empty() ? message : message + "; " + hint;
}

class Reader {
 public:
  Reader(const SourceManager& sources, FileId file, const Stepper& stepper, DiagnosticEngine& diags, const TraceReadOptions& options)
      : text_(sources.text(file)), file_(file), stepper_(stepper), model_(stepper.model()), diags_(diags), options_(options),
        positions_(text_) {
    for (std::size_t r = 0; r < model_.rules.size(); ++r) {
      ruleIndex_.emplace(model_.rules[r].name, r);
      ruleNames_.push_back(model_.rules[r].name);
    }
    for (std::size_t v = 0; v < model_.variables.size(); ++v) {
      varIndex_.emplace(model_.variables[v].name, v);
      varNames_.push_back(model_.variables[v].name);
    }
  }

  std::optional<ReplayedTrace> read(const json& root) {
    try {
      readRoot(root);
    } catch (const Invalid&) {
      return std::nullopt;
    }
    return std::move(out_);
  }

 private:
  const std::string& text_;
  FileId file_;
  const Stepper& stepper_;
  const ir::Model& model_;
  DiagnosticEngine& diags_;
  const TraceReadOptions& options_;
  runtime::JsonPositions positions_;
  std::unordered_map<std::string, std::size_t> ruleIndex_, varIndex_;
  std::vector<std::string> ruleNames_, varNames_;
  ReplayedTrace out_;

  [[noreturn]] void fail(const std::string& pointer, const std::string& message) {
    diags_.error(jsonRangeAt(file_, text_, positions_.offsetOf(pointer)), message);
    throw Invalid{};
  }

  const json* optionalMember(const json& object, const std::string& pointer, const char* key) {
    if (!object.is_object()) fail(pointer, "expected an object here");
    auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }
  const json& member(const json& object, const std::string& pointer, const char* key, const char* what) {
    const json* m = optionalMember(object, pointer, key);
    if (m == nullptr) fail(pointer, std::string("missing \"") + key + "\" (" + what + ")");
    return *m;
  }
  std::string string(const json& value, const std::string& pointer, const char* key) {
    if (!value.is_string()) fail(pointer, std::string("\"") + key + "\" must be a string");
    return value.get<std::string>();
  }
  std::int64_t integer(const json& value, const std::string& pointer, const char* key, std::int64_t min, std::int64_t max) {
    if (!value.is_number_integer()) fail(pointer, std::string("\"") + key + "\" must be an integer");
    const std::string range = std::string("\"") + key + "\" must be between " + std::to_string(min) + " and " + std::to_string(max);
    if (value.is_number_unsigned() && value.get<std::uint64_t>() > static_cast<std::uint64_t>(max)) fail(pointer, range);
    const auto x = value.get<std::int64_t>();
    if (x < min || x > max) fail(pointer, range);
    return x;
  }
  std::int32_t value(const json& v, const std::string& pointer, const char* key) {
    return static_cast<std::int32_t>(integer(v, pointer, key, std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max()));
  }
  std::optional<std::string> optionalString(const json& object, const std::string& pointer, const char* key) {
    const json* m = optionalMember(object, pointer, key);
    if (m == nullptr) return std::nullopt;
    return string(*m, pointer + "/" + key, key);
  }

  // Chooses the counterexample, checks the fingerprint, replays.
  void readRoot(const json& root) {
    if (!root.is_object()) fail("", "expected an object: the output of 'semo-verify check --json', or one counterexample");
    std::string base;
    const json* trace = nullptr;
    std::optional<std::string> fingerprint = optionalString(root, "", "modelFingerprint");
    std::string fingerprintAt = "/modelFingerprint";
    if (root.contains("properties")) {
      const json& props = root.at("properties");
      if (!props.is_array()) fail("/properties", "\"properties\" must be an array");
      std::vector<std::string> names;
      for (std::size_t i = 0; i < props.size() && trace == nullptr; ++i) {
        const std::string at = "/properties/" + std::to_string(i);
        const json& p = props[i];
        if (!p.is_object()) fail(at, "a property must be an object");
        std::string name = optionalString(p, at, "name").value_or("");
        names.push_back(name);
        const bool has = p.contains("counterexample");
        if (options_.property.empty() ? has : name == options_.property) {
          if (!has) {
            std::string verdict = p.contains("verdict") && p.at("verdict").is_string() ? p.at("verdict").get<std::string>() : "not given";
            fail(at + "/name", "property " + inQuotes(name) + " has no counterexample (its verdict is " + inQuotes(verdict) + ")");
          }
          trace = &p.at("counterexample");
          base = at + "/counterexample";
        }
      }
      if (trace == nullptr && (options_.property.empty() || options_.property == "modelError") && root.contains("modelError")) {
        trace = &root.at("modelError");
        base = "/modelError";
      }
      if (trace == nullptr && !options_.property.empty()) {
        fail("/properties", withSuggestion("no property named " + inQuotes(options_.property) + " in this file", options_.property, names));
      }
      if (trace == nullptr) fail("/properties", "no counterexample in this file: no property is violated");
    } else if (root.contains("steps")) {
      trace = &root;
    } else {
      fail("", "neither the output of 'semo-verify check --json' (no \"properties\") nor a counterexample (no \"steps\")");
    }
    if (!trace->is_object()) fail(base, "a counterexample must be an object");
    if (base.empty() ? false : trace->contains("modelFingerprint")) {
      fingerprint = optionalString(*trace, base, "modelFingerprint");
      fingerprintAt = base + "/modelFingerprint";
    }
    out_.fingerprint = fingerprint.value_or("");
    if (options_.checkFingerprint && fingerprint) {
      const std::string mine = modelFingerprint(model_);
      if (*fingerprint != mine) {
        fail(fingerprintAt, "the trace is of another model: its fingerprint is " + *fingerprint + ", the model's is " + mine);
      }
    }
    replay(*trace, base);
  }

  void replay(const json& t, const std::string& base) {
    using Kind = ReplayedTrace::Kind;
    out_.property = string(member(t, base, "property", "the property it violates"), base + "/property", "property");
    const std::string kindText = string(member(t, base, "kind", "invariant, deadlock, range or lasso"), base + "/kind", "kind");
    if (kindText == "invariant") out_.kind = Kind::Invariant;
    else if (kindText == "deadlock") out_.kind = Kind::Deadlock;
    else if (kindText == "range") out_.kind = Kind::ModelError;
    else if (kindText == "lasso") out_.kind = Kind::Lasso;
    else fail(base + "/kind", "unknown trace kind " + inQuotes(kindText) + " (expected invariant, deadlock, range or lasso)");

    // What the trace claims to violate must be something the model has.
    std::size_t invariant = SIZE_MAX;
    if (out_.kind == Kind::Invariant) {
      std::vector<std::string> names;
      for (std::size_t i = 0; i < model_.invariants.size(); ++i) {
        if (model_.invariants[i].name == out_.property) invariant = i;
        names.push_back(model_.invariants[i].name);
      }
      if (invariant == SIZE_MAX) fail(base + "/property", withSuggestion("the model has no invariant " + inQuotes(out_.property), out_.property, names));
    } else if (out_.kind == Kind::Lasso) {
      std::vector<std::string> names;
      bool found = false;
      for (const ir::Property& p : model_.properties) {
        found = found || p.name == out_.property;
        names.push_back(p.name);
      }
      if (!found) fail(base + "/property", withSuggestion("the model has no property " + inQuotes(out_.property), out_.property, names));
    } else if (out_.kind == Kind::Deadlock && !model_.validEnd) {
      fail(base + "/kind", "a deadlock trace, but the model has no valid_end: it does not check deadlock freedom");
    }

    Stepper::State state = stepper_.initial();
    if (const json* initial = optionalMember(t, base, "initial")) {
      const std::string at = base + "/initial";
      if (!initial->is_object()) fail(at, "\"initial\" must be an object (variable name: value)");
      for (auto it = initial->begin(); it != initial->end(); ++it) {
        const std::string vp = at + "/" + pointerKey(it.key());
        auto var = varIndex_.find(it.key());
        if (var == varIndex_.end()) fail(vp, withSuggestion("unknown variable " + inQuotes(it.key()), it.key(), varNames_));
        const std::int32_t v = value(it.value(), vp, it.key().c_str());
        if (v != state[var->second]) {
          fail(vp, "the trace starts with " + it.key() + " = " + std::to_string(v) + ", but its initial value in the model is " +
                       std::to_string(state[var->second]));
        }
      }
    }
    out_.states.push_back(state);

    const json& steps = member(t, base, "steps", "an array of steps");
    if (!steps.is_array()) fail(base + "/steps", "\"steps\" must be an array");
    if (out_.kind == Kind::ModelError && steps.empty()) fail(base + "/steps", "a model error trace ends with the step that leaves a range: it cannot be empty");
    for (std::size_t k = 0; k < steps.size(); ++k) {
      state = replayStep(steps[k], base + "/steps/" + std::to_string(k), k, k + 1 == steps.size(), state);
      out_.states.push_back(state);
    }

    const json* loop = optionalMember(t, base, "loopStart");
    if (out_.kind == Kind::Lasso) {
      if (loop == nullptr) fail(base, "missing \"loopStart\" (a lasso says where its loop starts)");
      out_.loopStart = static_cast<std::size_t>(integer(*loop, base + "/loopStart", "loopStart", 1, static_cast<std::int64_t>(steps.size()) + 1)) - 1;
    } else if (loop != nullptr) {
      fail(base + "/loopStart", "\"loopStart\" belongs to lassos only; this trace's kind is " + inQuotes(kindText));
    }

    // The trace must end as its kind says.
    const Stepper::State& last = out_.states.back();
    switch (out_.kind) {
      case Kind::Invariant:
        if (stepper_.invariantHolds(last, invariant)) fail(base + "/property", "invariant " + inQuotes(out_.property) + " holds in the state the trace ends in");
        break;
      case Kind::Deadlock:
        if (!stepper_.deadlocked(last)) {
          std::vector<std::size_t> enabled = stepper_.enabledRules(last);
          fail(base + "/kind", "the trace ends in a state that is not a deadlock: " +
                                   (enabled.empty() ? std::string("it is a valid end state")
                                                    : "rule " + inQuotes(model_.rules[enabled.front()].name) + " is enabled there"));
        }
        break;
      case Kind::Lasso:
        if (out_.loopStart < steps.size() && out_.states[out_.loopStart] != last) {
          fail(base + "/loopStart", "the loop does not close: from the state before step " + std::to_string(out_.loopStart + 1) +
                                        " to the last one, " + stepper_.describeDifference(out_.states[out_.loopStart], last));
        }
        break;
      case Kind::ModelError: break;  // checked at the last step
    }
  }

  Stepper::State replayStep(const json& s, const std::string& at, std::size_t k, bool last, const Stepper::State& state) {
    const std::string number = "step " + std::to_string(k + 1);
    if (!s.is_object()) fail(at, number + " must be an object");
    const std::string name = string(member(s, at, "rule", "the IR rule it takes"), at + "/rule", "rule");
    auto it = ruleIndex_.find(name);
    if (it == ruleIndex_.end()) fail(at + "/rule", withSuggestion(number + ": unknown rule " + inQuotes(name), name, ruleNames_));
    const std::size_t rule = it->second;
    const std::size_t outcomes = stepper_.branches(rule);
    std::optional<std::size_t> branch;
    if (const json* b = optionalMember(s, at, "branch")) {
      if (outcomes == 0) fail(at + "/branch", number + ": rule " + inQuotes(name) + " has no outcome");
      branch = static_cast<std::size_t>(integer(*b, at + "/branch", "branch", 0, static_cast<std::int64_t>(outcomes) - 1));
    }

    // The changes the step records, read first; checked against the state reached once the rule
    // is known to be enabled there.
    struct Recorded {
      std::size_t var;
      std::int32_t from, to;
      std::string at;
    };
    std::optional<std::vector<Recorded>> changes;
    if (const json* list = optionalMember(s, at, "changes")) {
      if (!list->is_array()) fail(at + "/changes", "\"changes\" must be an array");
      changes.emplace();
      std::set<std::size_t> seen;
      for (std::size_t j = 0; j < list->size(); ++j) {
        const std::string cp = at + "/changes/" + std::to_string(j);
        const json& c = (*list)[j];
        const std::string varName = string(member(c, cp, "var", "the variable it changes"), cp + "/var", "var");
        auto var = varIndex_.find(varName);
        if (var == varIndex_.end()) fail(cp + "/var", withSuggestion(number + ": unknown variable " + inQuotes(varName), varName, varNames_));
        if (!seen.insert(var->second).second) fail(cp + "/var", number + " changes " + varName + " twice");
        const std::int32_t from = value(member(c, cp, "from", "the value before the step"), cp + "/from", "from");
        const std::int32_t to = value(member(c, cp, "to", "the value after the step"), cp + "/to", "to");
        changes->push_back({var->second, from, to, cp});
      }
    }

    if (!stepper_.enabled(state, rule)) {
      std::string message = number + ": rule " + inQuotes(name) + " is not enabled in the state reached";
      if (changes) {
        std::string said;
        Stepper::State target = state;
        for (const Recorded& c : *changes) {
          const ir::Variable& v = model_.variables[c.var];
          said += (said.empty() ? "" : ", ") + v.name + ": " + valueText(v, c.from) + " -> " + valueText(v, c.to);
          target[c.var] = c.to;
        }
        message += said.empty() ? "; the trace has it change nothing" : "; the trace has it change " + said;
        if (auto other = stepper_.findRule(state, target)) message += " (rule " + inQuotes(model_.rules[*other].name) + " would)";
      }
      fail(at + "/rule", message);
    }

    // The state the step records: the one reached, with its changes.
    std::optional<Stepper::State> recorded;
    if (changes) {
      recorded = state;
      for (const Recorded& c : *changes) {
        if (c.from != state[c.var]) {
          const ir::Variable& v = model_.variables[c.var];
          fail(c.at + "/from", number + " changes " + v.name + " from " + valueText(v, c.from) + ", but " + v.name + " is " +
                                   valueText(v, state[c.var]) + " in the state reached");
        }
        (*recorded)[c.var] = c.to;
      }
    }

    // The outcome the step takes: the one given, or the first that fits what the step records.
    const bool rangeStep = out_.kind == ReplayedTrace::Kind::ModelError && last;
    std::optional<Stepper::Outcome> chosen;
    std::size_t chosenBranch = 0;
    for (std::size_t b = branch.value_or(0); b < (branch ? *branch + 1 : outcomes) && !chosen; ++b) {
      Stepper::Outcome o = stepper_.apply(state, {rule, b});
      if (recorded ? o.state == *recorded : o.outOfRange.empty() != rangeStep) {
        chosen = std::move(o);
        chosenBranch = b;
      }
    }
    if (!chosen) {
      if (outcomes == 0) fail(at + "/rule", number + ": rule " + inQuotes(name) + " has no outcome");
      Stepper::Outcome o = stepper_.apply(state, {rule, branch.value_or(0)});
      if (!recorded) {
        fail(at + "/rule", rangeStep ? number + ": the trace is a model error ('range'), but rule " + inQuotes(name) + " keeps every variable in its range"
                                     : number + ": " + o.message + " (a model error)");
      }
      std::string differs;
      for (std::size_t v = 0; v < o.state.size(); ++v) {
        if (o.state[v] == (*recorded)[v]) continue;
        const ir::Variable& var = model_.variables[v];
        differs += (differs.empty() ? "" : ", ") + var.name + " becomes " + valueText(var, o.state[v]) + ", the trace says " +
                   valueText(var, (*recorded)[v]);
      }
      fail(at + "/changes", number + ": rule " + inQuotes(name) + (branch || outcomes == 1 ? "" : " (outcome 1 of " + std::to_string(outcomes) + ")") +
                                " does not lead to the state the trace records: " + differs);
    }
    if (!chosen->outOfRange.empty() && !rangeStep) {
      fail(at + "/rule", number + ": " + chosen->message + "; only the last step of a model error ('range') trace may leave a range");
    }
    if (chosen->outOfRange.empty() && rangeStep) {
      fail(at + "/rule", number + ": the trace is a model error ('range'), but rule " + inQuotes(name) + " keeps every variable in its range");
    }
    out_.rules.push_back(rule);
    out_.branches.push_back(chosenBranch);
    return std::move(chosen->state);
  }
};

}  // namespace

std::optional<ReplayedTrace> readTrace(const SourceManager& sources, FileId file, const Stepper& stepper, DiagnosticEngine& diags,
                                       const TraceReadOptions& options) {
  const std::string& text = sources.text(file);
  if (const auto nul = text.find('\0'); nul == std::string::npos) {
    if (auto deep = jsonNestedDeeperThan(text, kMaxDepth)) {
      diags.error(jsonRangeAt(file, text, *deep), "nested more than " + std::to_string(kMaxDepth) + " levels deep: not a trace");
      return std::nullopt;
    }
  }
  std::optional<json> root = parseJsonFile(sources, file, diags);
  if (!root) return std::nullopt;
  return Reader(sources, file, stepper, diags, options).read(*root);
}

std::optional<ReplayedTrace> readTrace(const SourceManager& sources, FileId file, const ir::Model& model, DiagnosticEngine& diags,
                                       const TraceReadOptions& options) {
  return readTrace(sources, file, Stepper(model), diags, options);
}

}  // namespace semo::checker
