// The trace reader (checker/trace_reader.hpp): counterexamples the engines find, written as
// `check --json` writes them, read back and replayed to the same steps; and what it refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "ir_support.hpp"
#include "mission_support.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/checker/fingerprint.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/checker/smt_search.hpp"
#include "semo/checker/trace_reader.hpp"

namespace semo::checker {
namespace {

using nlohmann::json;

struct Read {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  std::optional<ReplayedTrace> trace;
  [[nodiscard]] std::string errors() const {
    std::string out;
    for (const Diagnostic& d : diags.diagnostics()) out += diags.format(d);
    return out;
  }
};

std::unique_ptr<Read> read(const std::string& text, const ir::Model& model, const TraceReadOptions& options = {}) {
  auto r = std::make_unique<Read>();
  FileId file = r->sources.add("trace.json", text);
  r->trace = readTrace(r->sources, file, model, r->diags, options);
  EXPECT_EQ(r->trace.has_value(), !r->diags.hasErrors()) << r->errors();
  return r;
}

// A counterexample as check --json writes it: the trace, with the model's fingerprint.
json counterexample(const ir::Model& m, const Trace& t) {
  json j = json::parse(traceToJson(m, t));
  j["modelFingerprint"] = modelFingerprint(m);
  return j;
}

// The output of check --json, as far as the reader looks at it.
json checkOutput(const ir::Model& m, const SearchResult& r) {
  json props = json::array();
  for (const PropertyResult& p : r.properties) {
    json jp = {{"name", p.name}, {"verdict", verdictName(p.verdict)}, {"type", "safety"}};
    if (p.counterexample) jp["counterexample"] = counterexample(m, *p.counterexample);
    props.push_back(jp);
  }
  json root = {{"input", "test"}, {"properties", props}, {"modelFingerprint", modelFingerprint(m)}};
  if (r.rangeError) root["modelError"] = counterexample(m, *r.rangeError);
  return root;
}

void expectSameSteps(const Trace& t, const ReplayedTrace& back) {
  ASSERT_EQ(back.rules.size(), t.steps.size());
  for (std::size_t k = 0; k < t.steps.size(); ++k) {
    EXPECT_EQ(back.rules[k], t.steps[k].rule) << "step " << k + 1;
    EXPECT_EQ(back.branches[k], t.steps[k].branch) << "step " << k + 1;
  }
  ASSERT_EQ(back.states.size(), t.steps.size() + 1);
  EXPECT_EQ(back.states.front(), t.initial);
  EXPECT_EQ(back.property, t.property);
  EXPECT_EQ(traceKindName(back.kind), t.kind);
  // And back to the checker's form, change for change.
  Trace again = back.toTrace();
  ASSERT_EQ(again.steps.size(), t.steps.size());
  for (std::size_t k = 0; k < t.steps.size(); ++k) {
    ASSERT_EQ(again.steps[k].changes.size(), t.steps[k].changes.size());
    for (std::size_t c = 0; c < t.steps[k].changes.size(); ++c) {
      EXPECT_EQ(again.steps[k].changes[c].var, t.steps[k].changes[c].var);
      EXPECT_EQ(again.steps[k].changes[c].after, t.steps[k].changes[c].after);
    }
  }
  EXPECT_EQ(again.loopStart, t.loopStart);
}

class TraceRoundTrip : public testing::TestWithParam<test::ShippedMission> {};

TEST_P(TraceRoundTrip, EveryCounterexampleReadsBackToTheSameRules) {
  std::optional<ir::Model> m = test::translateShipped(GetParam());
  ASSERT_TRUE(m.has_value());
  SearchResult r = checkSafety(*m, {});
  std::size_t found = 0;
  for (const PropertyResult& p : r.properties) {
    if (!p.counterexample) continue;
    SCOPED_TRACE(p.name);
    ++found;
    // A counterexample on its own.
    auto single = read(counterexample(*m, *p.counterexample).dump(2), *m);
    ASSERT_TRUE(single->trace.has_value()) << single->errors();
    expectSameSteps(*p.counterexample, *single->trace);
    EXPECT_EQ(single->trace->fingerprint, modelFingerprint(*m));
    // Chosen by name in the whole output.
    TraceReadOptions options;
    options.property = p.name;
    auto whole = read(checkOutput(*m, r).dump(2), *m, options);
    ASSERT_TRUE(whole->trace.has_value()) << whole->errors();
    expectSameSteps(*p.counterexample, *whole->trace);
  }
  EXPECT_GT(found, 0u);
}

INSTANTIATE_TEST_SUITE_P(Defects, TraceRoundTrip,
                         testing::Values(test::ShippedMission{"specs/defects/flood.semo", "specs/defects/strategy.xml"},
                                         test::ShippedMission{"specs/defects/double_receive.semo", "specs/defects/strategy.xml"},
                                         test::ShippedMission{"specs/defects/early_clear.semo", "specs/defects/strategy.xml"},
                                         test::ShippedMission{"specs/defects/leader_timeout.semo", "specs/defects/leader_timeout_short.xml"},
                                         test::ShippedMission{"specs/defects/lost_report.semo", "specs/defects/strategy.xml"}),
                         [](const testing::TestParamInfo<test::ShippedMission>& info) {
                           std::string n = info.param.mission;
                           return n.substr(n.rfind('/') + 1, n.find('.') - n.rfind('/') - 1);
                         });

TEST(TraceReader, TheSmtEnginesCounterexamplesReadBackToo) {
  for (const test::ShippedMission& mission : {test::ShippedMission{"specs/defects/flood.semo", "specs/defects/strategy.xml"},
                                              test::ShippedMission{"specs/defects/circular_wait.semo", "specs/defects/strategy.xml"}}) {
    SCOPED_TRACE(mission.mission);
    std::optional<ir::Model> m = test::translateShipped(mission);
    ASSERT_TRUE(m.has_value());
    SmtOptions options;
    options.induction = options.ic3 = false;
    SmtResult r = checkSafetySmt(*m, options);
    std::size_t found = 0;
    for (const PropertyResult& p : r.search.properties) {
      if (!p.counterexample) continue;
      ++found;
      auto back = read(counterexample(*m, *p.counterexample).dump(), *m);
      ASSERT_TRUE(back->trace.has_value()) << back->errors();
      expectSameSteps(*p.counterexample, *back->trace);
    }
    EXPECT_GT(found, 0u);
  }
}

TEST(TraceReader, DefaultIsTheFirstViolatedProperty) {
  std::optional<ir::Model> m = test::translateShipped({"specs/defects/early_clear.semo", "specs/defects/strategy.xml"});
  ASSERT_TRUE(m.has_value());
  SearchResult r = checkSafety(*m, {});
  const PropertyResult* first = nullptr;
  for (const PropertyResult& p : r.properties) {
    if (p.counterexample && first == nullptr) first = &p;
  }
  ASSERT_NE(first, nullptr);
  auto back = read(checkOutput(*m, r).dump(2), *m);
  ASSERT_TRUE(back->trace.has_value()) << back->errors();
  EXPECT_EQ(back->trace->property, first->name);
}

TEST(TraceReader, ALassoReadsBackWithItsLoop) {
  std::optional<ir::Model> m = test::translateShipped({"specs/defects/liveness/lost_recall.semo", "specs/defects/liveness/strategy.xml"});
  ASSERT_TRUE(m.has_value());
  LivenessResult live = checkLiveness(*m, {});
  std::size_t lassos = 0;
  for (const PropertyResult& p : live.properties) {
    if (!p.counterexample) continue;
    ++lassos;
    auto back = read(counterexample(*m, *p.counterexample).dump(), *m);
    ASSERT_TRUE(back->trace.has_value()) << back->errors();
    EXPECT_EQ(back->trace->kind, ReplayedTrace::Kind::Lasso);
    EXPECT_EQ(back->trace->loopStart, p.counterexample->loopStart);
    expectSameSteps(*p.counterexample, *back->trace);
  }
  EXPECT_GT(lassos, 0u);
}

const char* kCounter = R"(semo-ir 1;
var c : 0..3 = 0;
var d : 0..1 = 0;
rule inc : c < 3 -> c' = c + 1;
rule jump : c == 1 -> c' = c + 3;
rule flip : true -> d' = 1 - d;
invariant small : c < 2;
)";

TEST(TraceReader, AModelErrorReadsBackWithTheValueOutOfRange) {
  ir::Model m = test::parseIr(kCounter);
  SearchResult r = checkSafety(m, {});
  ASSERT_TRUE(r.rangeError.has_value());
  TraceReadOptions options;
  options.property = "modelError";
  // The invariant is violated too (c == 2): ask for the model error by name.
  auto back = read(checkOutput(m, r).dump(), m, options);
  ASSERT_TRUE(back->trace.has_value()) << back->errors();
  EXPECT_EQ(back->trace->kind, ReplayedTrace::Kind::ModelError);
  EXPECT_EQ(back->trace->states.back()[0], 4);
  expectSameSteps(*r.rangeError, *back->trace);
}

// A trace of kCounter written by hand.
json handTrace() {
  return json::parse(R"({"property": "small", "kind": "invariant", "initial": {"c": 0, "d": 0},
    "steps": [{"rule": "inc", "changes": [{"var": "c", "from": 0, "to": 1}]},
              {"rule": "flip", "changes": [{"var": "d", "from": 0, "to": 1}]},
              {"rule": "inc", "changes": [{"var": "c", "from": 1, "to": 2}]}]})");
}

TEST(TraceReader, AHandWrittenTraceWithoutBranchesOrFingerprint) {
  ir::Model m = test::parseIr(kCounter);
  auto back = read(handTrace().dump(2), m);
  ASSERT_TRUE(back->trace.has_value()) << back->errors();
  EXPECT_EQ(back->trace->rules, (std::vector<std::size_t>{0, 2, 0}));
  EXPECT_EQ(back->trace->states.back(), (Stepper::State{2, 1}));
  EXPECT_EQ(back->trace->fingerprint, "");
}

TEST(TraceReader, AStepThatIsNotEnabledIsAnErrorAtItsRule) {
  ir::Model m = test::parseIr(kCounter);
  // jump needs c == 1; a fourth step after c became 2.
  json t = handTrace();
  t["steps"].push_back(json::parse(R"({"rule": "jump", "changes": [{"var": "c", "from": 2, "to": 3}]})"));
  const std::string text = t.dump(2);
  auto back = read(text, m);
  ASSERT_FALSE(back->trace.has_value());
  ASSERT_EQ(back->diags.diagnostics().size(), 1u);
  const Diagnostic& d = back->diags.diagnostics().front();
  EXPECT_EQ(d.message, "step 4: rule 'jump' is not enabled in the state reached; the trace has it change c: 2 -> 3 (rule 'inc' would)");
  // At the rule's name, with the line and a caret.
  const std::size_t at = text.find("\"jump\"");
  const std::string before = text.substr(0, at);
  EXPECT_EQ(d.range.begin.line, static_cast<std::uint32_t>(1 + std::count(before.begin(), before.end(), '\n')));
  EXPECT_EQ(d.range.begin.column, static_cast<std::uint32_t>(at - before.rfind('\n')));
  EXPECT_NE(back->errors().find("trace.json:" + std::to_string(d.range.begin.line) + ":"), std::string::npos) << back->errors();
  EXPECT_NE(back->errors().find("^"), std::string::npos) << back->errors();
}

TEST(TraceReader, AStepLeadingElsewhereNamesTheDifference) {
  ir::Model m = test::parseIr(kCounter);
  json t = handTrace();
  t["steps"][2]["changes"][0]["to"] = 3;
  auto back = read(t.dump(), m);
  ASSERT_FALSE(back->trace.has_value());
  EXPECT_NE(back->errors().find("step 3: rule 'inc' does not lead to the state the trace records: c becomes 2, the trace says 3"), std::string::npos)
      << back->errors();
}

TEST(TraceReader, TheEndMustBeWhatTheKindSays) {
  ir::Model m = test::parseIr(kCounter);
  json t = handTrace();
  t["steps"].erase(2);
  auto back = read(t.dump(), m);
  ASSERT_FALSE(back->trace.has_value());
  EXPECT_NE(back->errors().find("invariant 'small' holds in the state the trace ends in"), std::string::npos) << back->errors();
  t = handTrace();
  t["property"] = "smal";
  back = read(t.dump(), m);
  EXPECT_NE(back->errors().find("the model has no invariant 'smal'; did you mean 'small'?"), std::string::npos) << back->errors();
}

TEST(TraceReader, AnotherModelsFingerprintIsAnErrorNamingBoth) {
  ir::Model m = test::parseIr(kCounter);
  json t = handTrace();
  t["modelFingerprint"] = "sha256:" + std::string(64, '0');
  auto back = read(t.dump(), m);
  ASSERT_FALSE(back->trace.has_value());
  EXPECT_NE(back->errors().find("its fingerprint is sha256:000"), std::string::npos) << back->errors();
  EXPECT_NE(back->errors().find("the model's is " + modelFingerprint(m)), std::string::npos) << back->errors();
  TraceReadOptions options;
  options.checkFingerprint = false;
  back = read(t.dump(), m, options);
  EXPECT_TRUE(back->trace.has_value()) << back->errors();
}

TEST(TraceReader, ChoosingAPropertyByName) {
  ir::Model m = test::parseIr(kCounter);
  json root = {{"properties", json::array({{{"name", "fine"}, {"verdict", "proven"}}, {{"name", "small"}, {"verdict", "VIOLATED"}, {"counterexample", handTrace()}}})}};
  EXPECT_TRUE(read(root.dump(), m)->trace.has_value());
  TraceReadOptions options;
  options.property = "fine";
  auto back = read(root.dump(), m, options);
  EXPECT_NE(back->errors().find("property 'fine' has no counterexample (its verdict is 'proven')"), std::string::npos) << back->errors();
  options.property = "smll";
  back = read(root.dump(), m, options);
  EXPECT_NE(back->errors().find("no property named 'smll' in this file; did you mean 'small'?"), std::string::npos) << back->errors();
  root["properties"].erase(1);
  back = read(root.dump(), m);
  EXPECT_NE(back->errors().find("no counterexample in this file"), std::string::npos) << back->errors();
}

TEST(TraceReader, GarbageIsRefusedWithAPosition) {
  ir::Model m = test::parseIr(kCounter);
  for (const std::string& text : {std::string(""), std::string("{"), std::string("[]"), std::string("17"), std::string("{\"steps\": 3}"),
                                  std::string("{\"properties\": {}}"), std::string(1000, '[') + std::string(1000, ']'),
                                  std::string("{\"a\":\0}", 7), std::string("{\"steps\": [], \"property\": \"small\", \"kind\": \"invariant\", \"initial\": {\"c\": 99999999999}}")}) {
    auto back = read(text, m);
    EXPECT_FALSE(back->trace.has_value()) << text;
    ASSERT_FALSE(back->diags.diagnostics().empty()) << text;
    EXPECT_TRUE(back->diags.diagnostics().front().range.begin.hasPosition()) << text;
  }
  auto deep = read(std::string(100, '[') + std::string(100, ']'), m);
  EXPECT_NE(deep->errors().find("nested more than 64 levels"), std::string::npos) << deep->errors();
}

}  // namespace
}  // namespace semo::checker
