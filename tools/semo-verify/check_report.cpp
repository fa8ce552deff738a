// A Report (checker/verify.hpp) as `check` prints it: text for people, JSON for tools (specs/trace.md).
#include <algorithm>
#include <regex>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/checker/trace.hpp"

namespace semo::cli {

namespace {

using checker::PropertyVerdict;
using Kind = PropertyVerdict::Kind;

std::string joined(const std::vector<std::string>& parts, const char* separator = ", ") {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : separator) + p;
  return out;
}

std::string fairnessLine(const ir::Model& m) {
  std::size_t weak = 0, strong = 0;
  for (const ir::Rule& r : m.rules) {
    if (r.stronglyFair) ++strong;
    else if (r.weaklyFair) ++weak;
  }
  std::string out = std::to_string(weak) + " rules weakly fair (robot steps, deliveries: enabled for ever, taken eventually)";
  if (strong > 0) out += ", " + std::to_string(strong) + " strongly fair (deliveries under fair loss)";
  return out;
}

void verdictLines(std::string& out, const checker::Report& r, Kind kind) {
  for (const PropertyVerdict& p : r.properties) {
    if (p.kind != kind) continue;
    out += "  " + std::string(checker::verdictName(p.verdict)) + "  " + p.name + (p.coverage.empty() ? "" : "  (" + p.coverage + ")") + "\n";
  }
}

void formationLines(std::string& out, const checker::Report& r) {
  if (!r.formation.empty()) out += "group formation, for every crash set within the budget (Z3):\n";
  for (std::size_t b = 0; b < r.formation.size(); ++b) {
    const checker::FormationVerdict& v = r.formation[b];
    out += "  " + std::string(v.holds() ? "proven" : "VIOLATED") + "  " + v.block + " at " + r.formationOrigins[b];
    if (v.holds()) {
      out += "  (" + checker::formationCoverage(v) + ")";
    } else if (v.breakingSet.empty()) {
      out += "  (cannot be formed even with every robot alive: " + joined(v.unmetArms) + " cannot all get a robot of their own)";
    } else {
      out += "  (smallest crash set that breaks it: " + joined(v.breakingSet) + "; then " +
             (v.unmetArms.size() == 1 ? "no live robot is left for " + v.unmetArms[0] : joined(v.unmetArms) + " cannot all get a robot of their own") + ")";
    }
    out += "\n";
  }
}

// The counterexamples, after every verdict.
void counterexamples(std::string& out, const checker::Report& r, const ir::Model& model) {
  for (const PropertyVerdict& p : r.properties) {
    if (p.counterexample) out += "\n" + checker::traceToText(model, *p.counterexample);
  }
  if (r.safety.rangeError) out += "\nmodel error: " + r.safety.limitReached + "\n" + checker::traceToText(model, *r.safety.rangeError);
}

}  // namespace

std::string durationText(double seconds) {
  const double ms = seconds * 1000;
  if (ms < 999.5) return fmt::format("{:.3g} ms", ms);
  if (seconds < 59.95) return fmt::format("{:.3g} s", seconds);
  const double minutes = seconds / 60;
  return minutes < 999.5 ? fmt::format("{:.3g} min", minutes) : fmt::format("{:.0f} min", minutes);
}

std::string reportText(const checker::Report& r, const ir::Model& model, const std::string& input, bool bmcOnly) {
  std::string out = "model:       " + input + " (" + std::to_string(model.variables.size()) + " variables, " + std::to_string(model.rules.size()) + " rules)\n";
  out += "assumptions: " + (r.assumptions.empty() ? std::string("none stated") : joined(r.assumptions, "; ")) + "\n";
  const checker::SearchResult& s = r.safety;
  if (r.engine == checker::Engine::Smt) {
    out += "engine:      smt (Z3): bounded model checking to depth " + std::to_string(r.smt->bmcDepth) +
           (bmcOnly ? " only (--bmc-only)" : ", then k-induction and IC3") + ", " + durationText(s.seconds) + "\n";
    if (!r.engineReason.empty()) out += "             (chosen: " + r.engineReason + ")\n";
    if (r.smt->lemmasProven > 0) {
      out += "             (the definitions of " + std::to_string(r.smt->lemmasProven) + " team counts proven, then assumed)\n";
    }
    formationLines(out, r);
    verdictLines(out, r, Kind::Safety);
    verdictLines(out, r, Kind::Liveness);
    if (!r.smt->note.empty()) out += "note:        " + r.smt->note + "\n";
    counterexamples(out, r, model);
    return out;
  }
  if (r.engine == checker::Engine::Counting) {
    const checker::CountingResult& c = *r.counting;
    out += "engine:      counting: the robots of one team counted per local state (0, 1, " + std::to_string(c.threshold) + " or more)";
    out += r.engineReason.empty() ? "\n" : " (chosen: " + r.engineReason + ")\n";
    if (c.applicable) {
      out += "explored:    " + std::to_string(c.robots) + " robots, " + std::to_string(c.localStates) + " local states of one robot, " +
             std::to_string(c.states) + " abstract states, " + std::to_string(c.transitions) + " transitions (complete), " + durationText(c.seconds) + "\n";
    } else {
      out += "explored:    nothing: the counter abstraction does not apply (" + c.why + ")\n";
    }
    verdictLines(out, r, Kind::Safety);
    if (!r.livenessSkipped.empty()) out += "liveness:    " + r.livenessSkipped + "\n";
    verdictLines(out, r, Kind::Liveness);
    return out;
  }
  if (!r.engineReason.empty()) out += "engine:      explicit (chosen: " + r.engineReason + ")\n";
  for (const std::string& c : s.symmetry) out += "symmetry:    interchangeable " + c + "\n";
  out += "explored:    " + std::to_string(s.states) + " states, " + std::to_string(s.transitions) + " transitions, depth " +
         std::to_string(s.depth) + " (" + (s.complete ? "complete" : "PARTIAL: " + s.limitReached) + "), " + durationText(s.seconds) + "\n";
  verdictLines(out, r, Kind::Safety);
  if (!model.properties.empty()) {
    const checker::LivenessResult& live = r.liveness;
    out += "liveness:    ";
    if (!r.livenessSkipped.empty()) {
      out += r.livenessSkipped + "\n";
    } else {
      out += std::to_string(live.states) + " product states, " + std::to_string(live.transitions) + " transitions";
      if (live.reducedProperties > 0) {
        out += " (up to symmetry for " + std::to_string(live.reducedProperties) + " of " + std::to_string(live.properties.size()) + " properties)";
      }
      out += " (" + (live.complete ? std::string("complete") : "PARTIAL: " + live.limitReached) + "), " + durationText(live.seconds) + "\n";
      out += "fairness:    " + fairnessLine(model) + "\n";
    }
    verdictLines(out, r, Kind::Liveness);
  } else {
    verdictLines(out, r, Kind::Liveness);  // a named LTL check with nothing to check: vacuous
  }
  counterexamples(out, r, model);
  return out;
}

namespace {

// A partial result says what would decide more: the options the unknown verdicts name as what
// stopped them, a budget to raise or a switch to leave out. Empty when they name none.
std::string toDecideMore(const checker::Report& r) {
  static const std::regex option(R"(--[a-z][a-z-]+)");
  const std::set<std::string> budgets = {"--max-states", "--max-memory", "--max-depth",  "--slice-states",
                                         "--symbolic-seconds", "--cone-seconds", "--smt-timeout"};
  const std::set<std::string> switches = {"--safety-only", "--bmc-only", "--no-symbolic", "--no-walks", "--no-slicing"};
  std::vector<std::string> more, without;
  auto scan = [&](const std::string& text) {
    for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it) {
      const std::string o = it->str();
      std::vector<std::string>& into = budgets.count(o) != 0 ? more : without;
      if ((budgets.count(o) != 0 || switches.count(o) != 0) && std::find(into.begin(), into.end(), o) == into.end()) into.push_back(o);
    }
  };
  for (const PropertyVerdict& p : r.properties) {
    if (p.verdict == checker::Verdict::Unknown) scan(p.coverage);
  }
  scan(r.safety.limitReached);
  scan(r.livenessSkipped);
  if (more.empty() && without.empty()) return {};
  std::string out = "to decide:   ";
  if (!more.empty()) out += "more " + joined(more, ", more ");
  if (!without.empty()) out += std::string(more.empty() ? "" : "; ") + "without " + joined(without, ", without ");
  return out + " (each unknown verdict above says what stopped it)\n";
}

}  // namespace

std::string resultLine(const checker::Report& r) {
  std::size_t proven = 0, violated = 0;
  std::vector<std::string> unknown;
  for (const PropertyVerdict& p : r.properties) {
    if (p.kind == Kind::GroupFormation && !r.formation.empty()) continue;  // counted from r.formation below
    if (p.verdict == checker::Verdict::Proven) ++proven;
    else if (p.verdict == checker::Verdict::Violated) ++violated;
    else unknown.push_back(p.name);
  }
  for (const checker::FormationVerdict& v : r.formation) (v.holds() ? proven : violated) += 1;
  std::string out = "result: " + std::to_string(proven) + " proven, " + std::to_string(violated) + " violated, " +
                    std::to_string(unknown.size()) + " unknown";
  if (!unknown.empty()) {
    constexpr std::size_t kNamed = 3;
    std::vector<std::string> named(unknown.begin(), unknown.begin() + static_cast<std::ptrdiff_t>(std::min(kNamed, unknown.size())));
    if (unknown.size() > kNamed) named.push_back(std::to_string(unknown.size() - kNamed) + " more");
    out += " (" + joined(named) + ")";
  }
  const char* meaning = r.exitCode == 0 ? "every property proven" : r.exitCode == 1 ? "violated" : "partial";
  if (r.exitCode == 3 && unknown.empty() && !r.safety.limitReached.empty()) meaning = "partial: the search stopped at a limit";
  const std::string hint = r.exitCode == 3 ? toDecideMore(r) : std::string();
  return hint + out + " \u2014 exit " + std::to_string(r.exitCode) + " (" + meaning + ")\n";
}

nlohmann::json reportJson(const checker::Report& r, const ir::Model& model, const ModelInput& in) {
  using nlohmann::json;
  // Every counterexample names the model it belongs to, so that it can be read back on its own.
  auto traceJson = [&](const checker::Trace& t) {
    json j = json::parse(checker::traceToJson(model, t));
    j["modelFingerprint"] = r.modelFingerprint;
    return j;
  };
  const checker::SearchResult& s = r.safety;
  json props = json::array();
  const bool smt = r.engine == checker::Engine::Smt;
  const bool counting = r.engine == checker::Engine::Counting;
  std::size_t invariant = 0, ltl = 0;
  for (const PropertyVerdict& p : r.properties) {
    if (p.kind == Kind::GroupFormation) continue;  // in "groupFormation"
    json jp = {{"name", p.name}, {"verdict", checker::verdictName(p.verdict)}, {"origin", p.origin},
               {"type", p.kind == Kind::Safety ? "safety" : "liveness"}};
    if (p.kind == Kind::Safety && smt && p.vacuous.empty()) {
      const std::size_t j = invariant;
      if (r.smt->inductionDepth[j] != 0) jp["inductionDepth"] = r.smt->inductionDepth[j];
      if (p.proof == checker::ProofKind::Exhausted) jp["proof"] = "exhausted";
      if (p.proof == checker::ProofKind::KInduction) jp["proof"] = "k-induction";
      if (p.proof == checker::ProofKind::Ic3) {
        jp["proof"] = "ic3";
        jp["invariantConjuncts"] = p.conjuncts;
      }
      if (r.smt->deepCounterexample[j] != 0) jp["beyondBmcDepth"] = true;
    }
    if (p.kind == Kind::Liveness) {
      if (smt || counting) jp["note"] = p.coverage;
      else if (ltl < r.liveness.notes.size() && !r.liveness.notes[ltl].empty()) jp["note"] = r.liveness.notes[ltl];
      if (ltl < r.liveness.methods.size() && r.livenessSkipped.empty()) {
        const checker::LivenessMethod& m = r.liveness.methods[ltl];
        json search = {{"on", m.roundRobin ? "round-robin" : m.sliced ? "slice" : "whole product"}, {"productStates", m.states}, {"seconds", m.seconds}};
        if (m.sliced) {
          search["variables"] = m.keptVariables;
          search["ofVariables"] = model.variables.size();
          search["refinements"] = m.refinements;
        }
        if (m.symbolic) {
          search["on"] = "slice, symbolically";
          search["symbolicProductStates"] = m.symbolicStates;
        }
        if (m.walked) {
          search["on"] = "random walks";
          search["walks"] = m.walks;
        }
        if (m.onCone) {
          search["on"] = "exact cone, symbolically";
          search["symbolicProductStates"] = m.symbolicStates;
          if (!m.assumedInvariants.empty()) search["assumedInvariants"] = m.assumedInvariants;
        }
        if (m.hunted) {
          search["on"] = "cone without crashes, symbolically";
          search["symbolicProductStates"] = m.symbolicStates;
        }
        if (!m.slicingGaveUp.empty()) search["slicingGaveUp"] = m.slicingGaveUp;
        jp["search"] = search;
      }
      ++ltl;
    } else {
      ++invariant;
    }
    if (p.proof == checker::ProofKind::Counting) jp["proof"] = "counting";
    if (p.everyTeamFrom > 0) jp["everyTeamSizeFrom"] = p.everyTeamFrom;
    if (counting && p.verdict != checker::Verdict::Proven && p.vacuous.empty()) jp["note"] = p.coverage;
    if (p.counterexample) jp["counterexample"] = traceJson(*p.counterexample);
    if (!p.vacuous.empty()) jp["vacuous"] = p.vacuous;
    props.push_back(jp);
  }
  json root = {{"schemaVersion", 1}, {"tool", std::string("semo-verify ") + kToolVersion},
               {"input", in.input}, {"assumptions", r.assumptions}, {"complete", s.complete}, {"seconds", s.seconds},
               {"properties", props}, {"exitCode", r.exitCode}, {"modelFingerprint", r.modelFingerprint}};
  addModelInput(root, in);  // what `replay` needs to build the same model again
  if (!r.engineReason.empty()) root["engineChoice"] = r.engineReason;
  if (s.rangeError) root["modelError"] = traceJson(*s.rangeError);
  if (smt) {
    root["engine"] = "smt";
    root["bmcDepth"] = r.smt->bmcDepth;
    root["lemmasProven"] = r.smt->lemmasProven;
    json formation = json::array();
    for (std::size_t b = 0; b < r.formation.size(); ++b) {
      const checker::FormationVerdict& v = r.formation[b];
      formation.push_back({{"block", v.block}, {"origin", r.formationOrigins[b]}, {"budget", v.budget}, {"tolerated", v.tolerated},
                           {"verdict", v.holds() ? "proven" : "VIOLATED"}, {"breakingSet", v.breakingSet}, {"unmetArms", v.unmetArms}});
    }
    root["groupFormation"] = formation;
    if (!r.smt->note.empty()) root["note"] = r.smt->note;
    return root;
  }
  if (counting) {
    const checker::CountingResult& c = *r.counting;
    root["engine"] = "counting";
    root["states"] = s.states;
    root["transitions"] = s.transitions;
    root["counting"] = {{"applicable", c.applicable}, {"robots", c.robots}, {"localStates", c.localStates}, {"threshold", c.threshold}};
    if (!s.limitReached.empty()) root["limit"] = s.limitReached;
    return root;
  }
  root["engine"] = "explicit";
  root["states"] = s.states;
  root["transitions"] = s.transitions;
  root["depth"] = s.depth;
  root["bytesPerState"] = s.bytesPerState;
  root["symmetry"] = s.symmetry;
  if (!s.limitReached.empty()) root["limit"] = s.limitReached;
  if (s.depthBounded) root["boundedDepth"] = s.depth;
  if (!model.properties.empty()) {
    const checker::LivenessResult& live = r.liveness;
    root["liveness"] = {{"productStates", live.states}, {"productTransitions", live.transitions}, {"complete", live.complete},
                        {"seconds", live.seconds}, {"propertiesUpToSymmetry", live.reducedProperties}};
    if (!live.limitReached.empty()) root["liveness"]["limit"] = live.limitReached;
  }
  return root;
}

}  // namespace semo::cli
