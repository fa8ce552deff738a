// The IR in the PRISM language (checker/prism_export.hpp): what PRISM or Storm would read.
#include <gtest/gtest.h>

#include <string>

#include "semo/checker/prism_export.hpp"
#include "semo/frontend/diagnostics.hpp"
#include "semo/semantics/ir_text.hpp"
#include "ir_support.hpp"

namespace semo::checker {
namespace {

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

TEST(PrismExport, AChainWithExactProbabilitiesLabelsAndQuestions) {
  const PrismModel p = toPrism(test::parseIr("semo-ir 1;\nvar b.knows : bool = false;\nrule a.broadcast : !b.knows -> 4/5 : b.knows' = true + 1/5 : skip;\n"
                                     "property known : eventually {b.knows};\n"),
                               true);
  EXPECT_TRUE(has(p.model, "\ndtmc\n")) << p.model;
  EXPECT_TRUE(has(p.model, "  b_knows : bool init false;  // b.knows\n")) << p.model;
  EXPECT_TRUE(has(p.model, "  // a.broadcast\n  [] !b_knows -> 4/5 : (b_knows' = true)\n     + 1/5 : true;\n")) << p.model;
  EXPECT_TRUE(has(p.model, "label \"known\" = b_knows;")) << p.model;
  EXPECT_TRUE(has(p.model, "rewards \"steps\"\n  true : 1;\nendrewards")) << p.model;
  EXPECT_TRUE(has(p.properties, "P=? [ F \"known\" ];\nR{\"steps\"}=? [ F \"known\" ];")) << p.properties;
}

TEST(PrismExport, AnMdpAsksForTheMinimumAndMaximumAndInvariantsAsReachability) {
  const PrismModel p = toPrism(test::parseIr("semo-ir 1;\nvar x : 0..2 = 0;\nrule a : x == 0 -> x' = 1;\nrule b : x == 0 -> x' = 2;\n"
                                     "invariant small : x <= 1;\nproperty one : eventually {x == 1};\n"),
                               false);
  EXPECT_TRUE(has(p.model, "\nmdp\n"));
  EXPECT_TRUE(has(p.model, "  x : [0..2] init 0;\n"));
  EXPECT_TRUE(has(p.properties, "Pmin=? [ F \"one\" ];")) << p.properties;
  EXPECT_TRUE(has(p.properties, "R{\"steps\"}max=? [ F \"one\" ];")) << p.properties;
  EXPECT_TRUE(has(p.model, "label \"small\" = (x <= 1);")) << p.model;
  EXPECT_TRUE(has(p.properties, "Pmax=? [ F !\"small\" ];")) << p.properties;
}

TEST(PrismExport, NamesAreMadeValidAndDistinctAndTypesAgree) {
  const PrismModel p = toPrism(test::parseIr("semo-ir 1;\nvar a.b[2] : 0..3;\nvar a_b_1 : 0..3;\nvar init : bool;\nvar \"9 lives\" : 0..1;\n"
                                     "rule r : init -> a.b[1]' = a_b_1 / 2, init' = a.b[1] % 3 == 1;\n"),
                               true);
  EXPECT_TRUE(has(p.model, "  a_b_1 : [0..3] init 0;  // a.b[1]\n")) << p.model;
  EXPECT_TRUE(has(p.model, "  a_b_1_2 : [0..3] init 0;  // a_b_1\n")) << p.model;
  EXPECT_TRUE(has(p.model, "  v_init : bool init false;  // init\n")) << p.model;
  EXPECT_TRUE(has(p.model, "  v_9_lives : [0..1] init 0;  // 9 lives\n")) << p.model;
  // Integer division and remainder as the IR means them (toward zero, x / 0 = 0).
  EXPECT_TRUE(has(p.model, "(a_b_1' = (2 = 0 ? 0 : (a_b_1_2 / 2 >= 0 ? floor(a_b_1_2 / 2) : ceil(a_b_1_2 / 2))))")) << p.model;
  EXPECT_TRUE(has(p.model, "(v_init' = ((3 = 0 ? 0 : a_b_1 - 3 * (a_b_1 / 3 >= 0 ? floor(a_b_1 / 3) : ceil(a_b_1 / 3))) = 1))")) << p.model;
}

}  // namespace
}  // namespace semo::checker
