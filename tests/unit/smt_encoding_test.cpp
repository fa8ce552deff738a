// The IR as Z3 formulas (checker/src/smt_encoding.hpp) on tiny models whose reachable states are
// worked out by hand, and the two forms of the step relation (compact, for BMC and induction; one
// case per rule outcome, for IC3) shown to be the same relation on every shipped model.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "../../checker/src/smt_encoding.hpp"
#include "ir_support.hpp"

namespace semo::checker {
namespace {

using detail::SmtEncoding;

// The states (x, y) reachable within `depth` steps, as the encoding sees them: one query per
// candidate state and path length.
std::set<std::pair<int, int>> reachable(const ir::Model& m, std::size_t depth) {
  std::set<std::pair<int, int>> out;
  z3::context ctx;
  SmtEncoding enc(ctx, m);
  const ir::Variable& x = m.variables[0];
  const ir::Variable& y = m.variables[1];
  for (int a = x.min; a <= x.max; ++a) {
    for (int b = y.min; b <= y.max; ++b) {
      z3::solver s(ctx);
      s.add(enc.initial(0));
      for (std::size_t k = 0; k <= depth; ++k) {
        if (k > 0) s.add(enc.transition(k - 1));
        s.push();
        s.add(enc.state(k)[0] == a && enc.state(k)[1] == b);
        bool found = s.check() == z3::sat;
        s.pop();
        if (found) {
          out.insert({a, b});
          break;
        }
        if (s.check() == z3::unsat) break;  // no path is this long
      }
    }
  }
  return out;
}

TEST(SmtEncoding, ReachableStatesOfATinyModelAsWorkedOutByHand) {
  // x climbs to 3, y follows while below x, and at y == 2 x is halved (truncating): from (2,2) and
  // (3,2) to (1,2), then to (0,2). So every y <= x (10 states) and (1,2), (0,2): 12 states; (3,3)
  // is a dead end, the rest of the 16 is unreachable.
  ir::Model m = test::parseIr("semo-ir 1;\nvar x : 0..3 = 0;\nvar y : 0..3 = 0;\n"
                              "rule up : x < 3 -> x' = x + 1;\n"
                              "rule follow : x > y -> y' = y + 1;\n"
                              "rule halve : y == 2 -> x' = x / 2;\n");
  std::set<std::pair<int, int>> expected;
  for (int a = 0; a <= 3; ++a) {
    for (int b = 0; b <= a; ++b) expected.insert({a, b});
  }
  expected.insert({1, 2});
  expected.insert({0, 2});
  EXPECT_EQ(reachable(m, 16), expected);
  // Within two steps: (0,0), (1,0), (2,0), (1,1) only.
  EXPECT_EQ(reachable(m, 2), (std::set<std::pair<int, int>>{{0, 0}, {1, 0}, {2, 0}, {1, 1}}));
}

TEST(SmtEncoding, ChoicesAndSignedArithmetic) {
  // One rule with two outcomes, x + 2 or x - 2, and y the remainder by 3 as C computes it (-2 % 3 is
  // -2, where Z3's own mod would give 1). From 0: (2, 2) or (-2, -2); the guard stops both there.
  ir::Model m = test::parseIr("semo-ir 1;\nvar x : -4..3 = 0;\nvar y : -2..2 = 0;\n"
                              "rule move : x >= -1 && x <= 1 ->\n"
                              "    0.5 : x' = x + 2, y' = (x + 2) % 3\n"
                              "  + 0.5 : x' = x - 2, y' = (x - 2) % 3;\n");
  EXPECT_EQ(reachable(m, 5), (std::set<std::pair<int, int>>{{0, 0}, {2, 2}, {-2, -2}}));
}

TEST(SmtEncoding, BothFormsOfTheStepRelationAreTheSame) {
  std::size_t models = test::forEachShippedModel([&](const std::string&, const std::string& text) {
    ir::Model m = test::parseIr(text);
    z3::context ctx;
    SmtEncoding enc(ctx, m);
    z3::expr_vector action(ctx);
    action.push_back(enc.action(0));
    // A step of one form that the other does not allow: none, either way.
    z3::solver compactOnly(ctx), casesOnly(ctx);
    compactOnly.add(enc.transition(0) && !enc.transitionByCases(0));
    casesOnly.add(enc.transitionByCases(0) && !z3::exists(action, enc.transition(0)));
    EXPECT_EQ(compactOnly.check(), z3::unsat);
    EXPECT_EQ(casesOnly.check(), z3::unsat);
  });
  EXPECT_GE(models, 5u);
}

}  // namespace
}  // namespace semo::checker
