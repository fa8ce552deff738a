// `check --engine smt`: bounded model checking and k-induction with Z3 (checker/smt_search.hpp).
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/checker/fingerprint.hpp"
#include "semo/checker/group_formation.hpp"
#include "semo/checker/smt_search.hpp"
#include "semo/semantics/load.hpp"

namespace semo::cli {

namespace {

struct Formation {
  std::vector<checker::FormationVerdict> verdicts;
  std::vector<std::string> origins;
};

// Group formation for every crash set, for a mission (an IR file has no groups to form). The mission
// was loaded once already without errors; --crash overrides the verify block's budget, as for check.
Formation formation(const CheckOptions& options) {
  Formation out;
  if (!options.model.strategy || options.model.input.ends_with(".ir")) return out;
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::optional<model::MissionModel> m = loadMission({options.model.input, *options.model.strategy, options.model.robotsDir}, sources, diags);
  if (!m) return out;
  if (options.model.crash) {
    for (std::size_t t = 0; t < m->teams.size() && t < m->assumptions.crashBudget.size(); ++t) {
      m->assumptions.crashBudget[t] = std::min<std::int64_t>(*options.model.crash, static_cast<std::int64_t>(m->teams[t].robots.size()));
    }
  }
  out.verdicts = checker::checkGroupFormation(*m);
  for (const checker::FormationVerdict& v : out.verdicts) {
    const SourceRange& at = m->groupBlocks[v.blockIndex].at;
    out.origins.push_back(at.begin.valid() ? sources.path(at.begin.file) + ":" + std::to_string(at.begin.line) + ":" +
                                                 std::to_string(at.begin.column)
                                           : "");
  }
  return out;
}

const char* proofName(checker::SmtProof p) {
  switch (p) {
    case checker::SmtProof::Exhausted: return "exhausted";
    case checker::SmtProof::Induction: return "k-induction";
    case checker::SmtProof::Ic3: return "ic3";
    default: return "none";
  }
}

std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : ", ") + p;
  return out;
}

}  // namespace

int runCheckSmt(const CheckOptions& options, const ir::Model& model) {
  checker::SmtOptions smt;
  if (options.maxDepth != UINT32_MAX) smt.maxDepth = options.maxDepth;
  smt.induction = smt.ic3 = !options.bmcOnly;
  smt.timeoutMs = options.smtTimeoutS * 1000u;
  checker::SmtResult out = checker::checkSafetySmt(model, smt);
  const checker::SearchResult& r = out.search;
  Formation groups = formation(options);
  bool violated = r.rangeError.has_value();
  for (const checker::FormationVerdict& v : groups.verdicts) violated = violated || !v.holds();
  bool undecided = false;
  for (const checker::PropertyResult& p : r.properties) {
    violated = violated || p.verdict == checker::Verdict::Violated;
    undecided = undecided || p.verdict == checker::Verdict::Unknown;
  }
  // The smt engine decides safety only: LTL properties stay unknown, so the check is not complete.
  undecided = undecided || !model.properties.empty();
  int code = violated ? kViolated : undecided ? kLimit : kOk;
  const std::string how = "bounded model checking to depth " + std::to_string(out.bmcDepth) +
                          (options.bmcOnly ? " only (--bmc-only)" : ", then k-induction and IC3");

  if (options.json) {
    // Every counterexample names the model it belongs to, so that it can be read back on its own.
    const std::string fingerprint = checker::modelFingerprint(model);
    auto traceJson = [&](const checker::Trace& t) {
      nlohmann::json j = nlohmann::json::parse(checker::traceToJson(model, t));
      j["modelFingerprint"] = fingerprint;
      return j;
    };
    nlohmann::json props = nlohmann::json::array();
    for (std::size_t j = 0; j < r.properties.size(); ++j) {
      const checker::PropertyResult& p = r.properties[j];
      nlohmann::json jp = {{"name", p.name}, {"verdict", checker::verdictName(p.verdict)}, {"origin", p.origin}, {"type", "safety"}};
      if (out.inductionDepth[j] != 0) jp["inductionDepth"] = out.inductionDepth[j];
      if (out.proof[j] != checker::SmtProof::None) jp["proof"] = proofName(out.proof[j]);
      if (out.proof[j] == checker::SmtProof::Ic3) jp["invariantConjuncts"] = out.invariantConjuncts[j];
      if (out.deepCounterexample[j] != 0) jp["beyondBmcDepth"] = true;
      if (p.counterexample) jp["counterexample"] = traceJson(*p.counterexample);
      props.push_back(jp);
    }
    for (const ir::Property& p : model.properties) {
      props.push_back({{"name", p.name}, {"verdict", "unknown"}, {"origin", p.origin}, {"type", "liveness"},
                       {"note", "not checked: the smt engine decides safety properties only"}});
    }
    nlohmann::json root = {{"input", options.model.input}, {"engine", "smt"},           {"assumptions", model.assumptions},
                           {"bmcDepth", out.bmcDepth},      {"complete", r.complete}, {"seconds", r.seconds},
                           {"properties", props},           {"exitCode", code}};
    root["modelFingerprint"] = fingerprint;
    addModelInput(root, options.model);  // what `replay` needs to build the same model again
    nlohmann::json formationJson = nlohmann::json::array();
    for (std::size_t b = 0; b < groups.verdicts.size(); ++b) {
      const checker::FormationVerdict& v = groups.verdicts[b];
      formationJson.push_back({{"block", v.block}, {"origin", groups.origins[b]}, {"budget", v.budget}, {"tolerated", v.tolerated},
                               {"verdict", v.holds() ? "proven" : "VIOLATED"}, {"breakingSet", v.breakingSet}, {"unmetArms", v.unmetArms}});
    }
    root["groupFormation"] = formationJson;
    if (r.rangeError) root["modelError"] = traceJson(*r.rangeError);
    if (!out.note.empty()) root["note"] = out.note;
    if (!options.engineReason.empty()) root["engineChoice"] = options.engineReason;
    std::cout << root.dump(2) << "\n";
    return code;
  }
  std::string assumptions;
  for (const std::string& a : model.assumptions) assumptions += (assumptions.empty() ? "" : "; ") + a;
  std::cout << "model:       " << options.model.input << " (" << model.variables.size() << " variables, " << model.rules.size()
            << " rules)\n";
  std::cout << "assumptions: " << (assumptions.empty() ? "none stated" : assumptions) << "\n";
  std::cout << "engine:      smt (Z3): " << how << ", " << r.seconds << " s\n";
  if (!options.engineReason.empty()) std::cout << "             (--engine auto: " << options.engineReason << ")\n";
  if (!groups.verdicts.empty()) std::cout << "group formation, for every crash set within the budget (Z3):\n";
  for (std::size_t b = 0; b < groups.verdicts.size(); ++b) {
    const checker::FormationVerdict& v = groups.verdicts[b];
    std::cout << "  " << (v.holds() ? "proven" : "VIOLATED") << "  " << v.block << " at " << groups.origins[b];
    if (v.holds()) {
      std::cout << "  (every crash set of up to " << v.budget << " robots leaves it formable; it tolerates " << v.tolerated << ")";
    } else if (v.breakingSet.empty()) {
      std::cout << "  (cannot be formed even with every robot alive: " << joined(v.unmetArms) << " cannot all get a robot of their own)";
    } else {
      std::cout << "  (smallest crash set that breaks it: " << joined(v.breakingSet) << "; then "
                << (v.unmetArms.size() == 1 ? "no live robot is left for " + v.unmetArms[0]
                                            : joined(v.unmetArms) + " cannot all get a robot of their own")
                << ")";
    }
    std::cout << "\n";
  }
  for (std::size_t j = 0; j < r.properties.size(); ++j) {
    const checker::PropertyResult& p = r.properties[j];
    std::cout << "  " << checker::verdictName(p.verdict) << "  " << p.name;
    if (out.proof[j] == checker::SmtProof::Induction) {
      std::cout << "  (proven by k-induction at k = " << out.inductionDepth[j] << ", under the assumptions above)";
    } else if (out.proof[j] == checker::SmtProof::Ic3) {
      std::cout << "  (proven by induction with a strengthening invariant of " << out.invariantConjuncts[j]
                << (out.invariantConjuncts[j] == 1 ? " conjunct" : " conjuncts")
                << " found by IC3 and checked independently, under the assumptions above)";
    } else if (p.verdict == checker::Verdict::Proven) {
      std::cout << "  (no path is longer than " << out.bmcDepth << " steps: every reachable state checked, under the assumptions above)";
    } else if (p.verdict == checker::Verdict::Unknown && !r.rangeError) {
      std::cout << "  (holds on every path of up to " << out.bmcDepth << " steps; not proven for longer ones"
                << (options.bmcOnly ? ")" : ": no induction up to k = " + std::to_string(std::min(out.bmcDepth + 1, smt.maxInduction)) + ", IC3 undecided)");
    } else if (p.counterexample) {
      std::size_t n = p.counterexample->steps.size();
      std::cout << "  (counterexample of " << n << (n == 1 ? " step" : " steps") << " below"
                << (out.deepCounterexample[j] != 0 ? ", found by IC3 beyond depth " + std::to_string(out.bmcDepth) + "; a shorter one may exist" : "")
                << ")";
    }
    std::cout << "\n";
  }
  for (const ir::Property& p : model.properties) {
    std::cout << "  unknown  " << p.name << "  (not checked: the smt engine decides safety properties only)\n";
  }
  if (!out.note.empty()) std::cout << "note:        " << out.note << "\n";
  for (const checker::PropertyResult& p : r.properties) {
    if (p.counterexample) std::cout << "\n" << checker::traceToText(model, *p.counterexample);
  }
  if (r.rangeError) std::cout << "\nmodel error: " << r.limitReached << "\n" << checker::traceToText(model, *r.rangeError);
  return code;
}

}  // namespace semo::cli
