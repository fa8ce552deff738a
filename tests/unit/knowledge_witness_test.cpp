// Knowledge facts named in traces (checker/trace.hpp): the model counts a robot's
// facts; a trace shows one assignment of named facts that fits every count, or none at all.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "ir_support.hpp"
#include "semo/checker/trace.hpp"
#include "semo/semantics/ir_text.hpp"

namespace semo::checker {
namespace {

// Two robots sharing one knowledge item of three facts: each finds facts, b learns from a (the
// guard reads a's count, as the translation's gossip does), a may crash (its count starts over).
const char* kModel = R"(semo-ir 1
robots a b;
var a.knows.papers : 0..3 @robot(a) @facts("red yellow blue");
var b.knows.papers : 0..3 @robot(b) @facts("red yellow blue");
rule a.finds @robot(a) @kind(environment) : a.knows.papers < 3 -> a.knows.papers' = a.knows.papers + 1;
rule b.finds @robot(b) @kind(environment) : b.knows.papers < 3 -> b.knows.papers' = b.knows.papers + 1;
rule b.learns.2 @robot(b) @kind(delivery) : b.knows.papers < 2 && a.knows.papers <= 2 && 2 <= b.knows.papers + a.knows.papers -> b.knows.papers' = 2;
rule b.learns.3 @robot(b) @kind(delivery) : b.knows.papers < 3 && a.knows.papers <= 3 && 3 <= b.knows.papers + a.knows.papers -> b.knows.papers' = 3;
rule a.crash @robot(a) @kind(crash) : true -> a.knows.papers' = 0;
)";

enum : std::size_t { kAFinds, kBFinds, kBLearns2, kBLearns3, kACrash };
constexpr ir::VarId kA = 0, kB = 1;

Step step(std::size_t rule, ir::VarId var, std::int32_t before, std::int32_t after) { return {rule, 0, {{var, before, after}}}; }

Trace traceOf(std::vector<Step> steps) {
  Trace t;
  t.property = "p";
  t.kind = "invariant";
  t.initial = {0, 0};
  t.steps = std::move(steps);
  return t;
}

TEST(KnowledgeWitness, NamesFoundFactsNobodyHoldsFirstAndLearntOnesFromTheTeacher) {
  const ir::Model m = test::parseIr(kModel);
  ASSERT_EQ(m.variables.at(kA).facts, (std::vector<std::string>{"red", "yellow", "blue"}));
  const Trace t = traceOf({step(kAFinds, kA, 0, 1), step(kAFinds, kA, 1, 2), step(kBFinds, kB, 0, 1), step(kBLearns3, kB, 1, 3),
                           step(kACrash, kA, 2, 0)});
  const KnowledgeWitness w = knowledgeWitness(m, t);
  ASSERT_TRUE(w.named);
  using Names = std::vector<std::string>;
  EXPECT_EQ(w.held[0][0], (Names{"red"}));
  EXPECT_EQ(w.held[1][0], (Names{"red", "yellow"}));
  EXPECT_EQ(w.held[2][0], (Names{"blue"})) << "a fact nobody holds yet, so that b's gossip can teach a something";
  EXPECT_EQ(w.held[3][0], (Names{"red", "yellow", "blue"})) << "the two facts b lacked, from its teacher a";
  EXPECT_EQ(w.held[4][0], (Names{})) << "a crash starts the count over";

  const std::string text = traceToText(m, t);
  EXPECT_NE(text.find("the names are one assignment that fits the counts"), std::string::npos) << text;
  EXPECT_NE(text.find("b.knows.papers: 1 -> 3  (holds red, yellow, blue)"), std::string::npos) << text;
  EXPECT_NE(text.find("a.knows.papers: 2 -> 0  (holds none)"), std::string::npos) << text;
  const nlohmann::json j = nlohmann::json::parse(traceToJson(m, t));
  EXPECT_EQ(j["steps"][3]["changes"][0]["facts"], nlohmann::json({"red", "yellow", "blue"}));
}

TEST(KnowledgeWitness, NamesNothingWhenNoAssignmentFitsTheCounts) {
  // The model lets b, holding a's only fact, "learn" a second one from a (the counts do not say
  // the facts overlap); no assignment of named facts does that, so the trace names none.
  const ir::Model m = test::parseIr(kModel);
  const Trace t = traceOf({step(kAFinds, kA, 0, 1), step(kBFinds, kB, 0, 1), step(kAFinds, kA, 1, 2)});
  EXPECT_TRUE(knowledgeWitness(m, t).named) << "a fits: red, then b blue, then a yellow";
  const Trace overlapping = traceOf({step(kAFinds, kA, 0, 1), step(kBLearns2, kB, 0, 2)});
  const KnowledgeWitness w = knowledgeWitness(m, overlapping);
  EXPECT_FALSE(w.named);
  const std::string text = traceToText(m, overlapping);
  EXPECT_EQ(text.find("holds"), std::string::npos) << text;
  EXPECT_NE(text.find("b.knows.papers: 0 -> 2\n"), std::string::npos) << text;
  EXPECT_EQ(nlohmann::json::parse(traceToJson(m, overlapping))["steps"][1]["changes"][0].count("facts"), 0u);
}

TEST(KnowledgeWitness, FactsSurviveTheIrText) {
  const ir::Model m = test::parseIr(kModel);
  const std::string text = ir::toText(m);
  EXPECT_NE(text.find("@facts(\"red yellow blue\")"), std::string::npos) << text;
  EXPECT_EQ(test::parseIr(text).variables.at(kB).facts, m.variables.at(kB).facts);
}

}  // namespace
}  // namespace semo::checker
