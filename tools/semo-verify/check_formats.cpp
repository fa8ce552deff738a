// `check --junit FILE` and `--sarif FILE`, `lint --sarif FILE`: the verdicts in the formats CI
// systems read. JUnit: one test case per property (a violation a failure with its counterexample,
// unknown skipped). SARIF 2.1.0: violations as errors and unknowns as warnings at the property's
// place in the mission, a counterexample as a code flow through the mission lines of its steps;
// lint's diagnostics as results at their positions.
#include <tinyxml2.h>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/checker/trace.hpp"

namespace semo::cli {

namespace {

using checker::PropertyVerdict;
using nlohmann::json;

std::size_t countVerdicts(const checker::Report& r, checker::Verdict v) {
  std::size_t n = 0;
  for (const PropertyVerdict& p : r.properties) n += p.verdict == v ? 1 : 0;
  return n;
}

// A SARIF location from "file:line:col" (none when the text has no position).
std::optional<json> location(const std::string& originText, const std::string& message = {}) {
  const ir::Origin o = ir::Origin::parse(originText);
  if (o.file.empty() || o.line == 0) return std::nullopt;
  json region = {{"startLine", o.line}};
  if (o.column > 0) region["startColumn"] = o.column;
  json out = {{"physicalLocation", {{"artifactLocation", {{"uri", o.file}}}, {"region", region}}}};
  if (!message.empty()) out["message"] = {{"text", message}};
  return out;
}

json sarifLog(json results, json rules) {
  return {{"$schema", "https://json.schemastore.org/sarif-2.1.0.json"},
          {"version", "2.1.0"},
          {"runs", json::array({{{"tool", {{"driver", {{"name", "semo-verify"}, {"version", kToolVersion}, {"rules", std::move(rules)}}}}},
                                 {"results", std::move(results)}}})}};
}

}  // namespace

std::string junitXml(const checker::Report& r, const ir::Model& model, const std::string& input) {
  tinyxml2::XMLPrinter out;  // escapes what it writes
  out.PushHeader(false, true);
  const std::size_t tests = r.properties.size(), failures = countVerdicts(r, checker::Verdict::Violated),
                    skipped = countVerdicts(r, checker::Verdict::Unknown);
  out.OpenElement("testsuites");
  out.PushAttribute("name", "semo-verify check");
  out.PushAttribute("tests", static_cast<std::uint64_t>(tests));
  out.PushAttribute("failures", static_cast<std::uint64_t>(failures));
  out.PushAttribute("skipped", static_cast<std::uint64_t>(skipped));
  out.OpenElement("testsuite");
  out.PushAttribute("name", input.c_str());
  out.PushAttribute("tests", static_cast<std::uint64_t>(tests));
  out.PushAttribute("failures", static_cast<std::uint64_t>(failures));
  out.PushAttribute("skipped", static_cast<std::uint64_t>(skipped));
  out.OpenElement("properties");
  for (const std::string& a : r.assumptions) {
    out.OpenElement("property");
    out.PushAttribute("name", "assumption");
    out.PushAttribute("value", a.c_str());
    out.CloseElement();
  }
  out.CloseElement();
  for (const PropertyVerdict& p : r.properties) {
    out.OpenElement("testcase");
    out.PushAttribute("classname", input.c_str());
    out.PushAttribute("name", p.name.c_str());
    if (p.verdict == checker::Verdict::Violated) {
      out.OpenElement("failure");
      out.PushAttribute("message", ("VIOLATED" + (p.coverage.empty() ? std::string() : ": " + p.coverage)).c_str());
      out.PushAttribute("type", "counterexample");
      if (p.counterexample) out.PushText(checker::traceToText(model, *p.counterexample).c_str());
      out.CloseElement();
    } else if (p.verdict == checker::Verdict::Unknown) {
      out.OpenElement("skipped");
      out.PushAttribute("message", ("unknown: " + p.coverage).c_str());
      out.CloseElement();
    } else {
      out.OpenElement("system-out");
      out.PushText(("proven: " + p.coverage).c_str());
      out.CloseElement();
    }
    out.CloseElement();
  }
  out.CloseElement();
  out.CloseElement();
  return out.CStr();
}

std::string checkSarif(const checker::Report& r, const ir::Model& model) {
  json results = json::array();
  json rules = json::array({{{"id", "violated"}, {"shortDescription", {{"text", "A property of the mission is violated"}}}},
                            {{"id", "unknown"}, {"shortDescription", {{"text", "A property of the mission was not decided"}}}}});
  for (const PropertyVerdict& p : r.properties) {
    if (p.verdict == checker::Verdict::Proven) continue;
    const bool violated = p.verdict == checker::Verdict::Violated;
    json result = {{"ruleId", violated ? "violated" : "unknown"},
                   {"level", violated ? "error" : "warning"},
                   {"message", {{"text", p.name + (violated ? " is violated" : " is unknown") + (p.coverage.empty() ? "" : " (" + p.coverage + ")")}}}};
    json where = json::array();
    if (auto at = location(p.origin)) where.push_back(*at);
    if (p.counterexample) {
      // The counterexample as a code flow: each step at its mission line, the step's label.
      json steps = json::array();
      for (const checker::Step& s : p.counterexample->steps) {
        const ir::Rule& rule = model.rules[s.rule];
        const std::string robot = rule.robot >= 0 && static_cast<std::size_t>(rule.robot) < model.robots.size()
                                      ? model.robots[static_cast<std::size_t>(rule.robot)]
                                      : std::string("-");
        if (auto at = location(rule.origin.text(), "[" + robot + "] " + rule.label)) {
          steps.push_back({{"location", *at}});
          if (where.empty()) where.push_back(*at);  // a property without a place: its first step's
        }
      }
      if (!steps.empty()) result["codeFlows"] = json::array({{{"threadFlows", json::array({{{"locations", steps}}})}}});
    }
    if (!where.empty()) result["locations"] = where;
    results.push_back(std::move(result));
  }
  return sarifLog(std::move(results), std::move(rules)).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string diagnosticsSarif(const SourceManager& sources, const DiagnosticEngine& diags) {
  json results = json::array();
  for (const Diagnostic& d : diags.diagnostics()) {
    json result = {{"ruleId", d.severity == Severity::Error ? "error" : d.severity == Severity::Warning ? "warning" : "note"},
                   {"level", d.severity == Severity::Error ? "error" : d.severity == Severity::Warning ? "warning" : "note"},
                   {"message", {{"text", d.message}}}};
    if (d.range.begin.hasPosition()) {
      json region = {{"startLine", d.range.begin.line}, {"startColumn", d.range.begin.column},
                     {"endColumn", d.range.begin.column + std::max<std::uint32_t>(1, d.range.length)}};
      result["locations"] = json::array({{{"physicalLocation", {{"artifactLocation", {{"uri", sources.path(d.range.begin.file)}}}, {"region", region}}}}});
    }
    results.push_back(std::move(result));
  }
  json rules = json::array({{{"id", "error"}}, {{"id", "warning"}}, {{"id", "note"}}});
  return sarifLog(std::move(results), std::move(rules)).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace semo::cli
