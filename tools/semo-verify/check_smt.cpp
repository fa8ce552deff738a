// `check --engine smt`: bounded model checking and k-induction with Z3 (checker/smt_search.hpp).
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/checker/smt_search.hpp"

namespace semo::cli {

int runCheckSmt(const CheckOptions& options, const ir::Model& model) {
  checker::SmtOptions smt;
  if (options.maxDepth != UINT32_MAX) smt.maxDepth = options.maxDepth;
  checker::SmtResult out = checker::checkSafetySmt(model, smt);
  const checker::SearchResult& r = out.search;
  bool violated = r.rangeError.has_value();
  bool undecided = false;
  for (const checker::PropertyResult& p : r.properties) {
    violated = violated || p.verdict == checker::Verdict::Violated;
    undecided = undecided || p.verdict == checker::Verdict::Unknown;
  }
  int code = violated ? kViolated : undecided ? kLimit : kOk;
  const std::string how = "bounded model checking to depth " + std::to_string(out.bmcDepth) + ", then k-induction";

  if (options.json) {
    nlohmann::json props = nlohmann::json::array();
    for (std::size_t j = 0; j < r.properties.size(); ++j) {
      const checker::PropertyResult& p = r.properties[j];
      nlohmann::json jp = {{"name", p.name}, {"verdict", checker::verdictName(p.verdict)}, {"origin", p.origin}, {"type", "safety"}};
      if (out.inductionDepth[j] != 0) jp["inductionDepth"] = out.inductionDepth[j];
      if (p.counterexample) jp["counterexample"] = nlohmann::json::parse(checker::traceToJson(model, *p.counterexample));
      props.push_back(jp);
    }
    nlohmann::json root = {{"input", options.model.input}, {"engine", "smt"},           {"assumptions", model.assumptions},
                           {"bmcDepth", out.bmcDepth},      {"complete", r.complete}, {"seconds", r.seconds},
                           {"properties", props},           {"exitCode", code}};
    if (r.rangeError) root["modelError"] = nlohmann::json::parse(checker::traceToJson(model, *r.rangeError));
    if (!out.note.empty()) root["note"] = out.note;
    std::cout << root.dump(2) << "\n";
    return code;
  }
  std::string assumptions;
  for (const std::string& a : model.assumptions) assumptions += (assumptions.empty() ? "" : "; ") + a;
  std::cout << "model:       " << options.model.input << " (" << model.variables.size() << " variables, " << model.rules.size()
            << " rules)\n";
  std::cout << "assumptions: " << (assumptions.empty() ? "none stated" : assumptions) << "\n";
  std::cout << "engine:      smt (Z3): " << how << ", " << r.seconds << " s\n";
  for (std::size_t j = 0; j < r.properties.size(); ++j) {
    const checker::PropertyResult& p = r.properties[j];
    std::cout << "  " << checker::verdictName(p.verdict) << "  " << p.name;
    if (p.verdict == checker::Verdict::Proven && out.inductionDepth[j] != 0) {
      std::cout << "  (proven by k-induction at k = " << out.inductionDepth[j] << ", under the assumptions above)";
    } else if (p.verdict == checker::Verdict::Proven) {
      std::cout << "  (no path is longer than " << out.bmcDepth << " steps: every reachable state checked, under the assumptions above)";
    } else if (p.verdict == checker::Verdict::Unknown && !r.rangeError) {
      std::cout << "  (holds on every path of up to " << out.bmcDepth << " steps; not proven for longer ones: no induction up to k = "
                << out.bmcDepth + 1 << ")";
    } else if (p.counterexample) {
      std::size_t n = p.counterexample->steps.size();
      std::cout << "  (counterexample of " << n << (n == 1 ? " step" : " steps") << " below)";
    }
    std::cout << "\n";
  }
  if (!out.note.empty()) std::cout << "note:        " << out.note << "\n";
  for (const checker::PropertyResult& p : r.properties) {
    if (p.counterexample) std::cout << "\n" << checker::traceToText(model, *p.counterexample);
  }
  if (r.rangeError) std::cout << "\nmodel error: " << r.limitReached << "\n" << checker::traceToText(model, *r.rangeError);
  return code;
}

}  // namespace semo::cli
