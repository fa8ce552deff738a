// The liveness engine with symmetry reduction decides exactly what it decides without: on random
// models of interchangeable robots (the same rule templates per robot, random fairness), and on
// hand-made ones where fairness to one particular robot is what makes a property hold.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "semo/checker/liveness_search.hpp"
#include "semo/checker/symmetry.hpp"
#include "ir_support.hpp"
#include "random_model.hpp"

namespace semo::checker {
namespace {

// The whole product's verdicts (the engine under test here); slicing must agree with them.
std::vector<Verdict> verdicts(const ir::Model& m, bool symmetry, std::uint32_t* reduced = nullptr, bool slicing = false) {
  SearchLimits limits;
  limits.symmetry = symmetry;
  LivenessOptions options;
  options.slicing = slicing;
  LivenessResult r = checkLiveness(m, limits, options);
  EXPECT_TRUE(r.complete) << r.limitReached;
  std::vector<Verdict> out;
  for (std::size_t k = 0; k < r.properties.size(); ++k) {
    out.push_back(r.properties[k].verdict);
    // A violation always comes with a concrete lasso, also when it was found up to symmetry.
    if (r.properties[k].verdict == Verdict::Violated) {
      EXPECT_TRUE(r.properties[k].counterexample.has_value()) << r.notes[k];
    }
  }
  if (reduced != nullptr) *reduced = r.reducedProperties;
  if (!slicing) {
    EXPECT_EQ(verdicts(m, symmetry, nullptr, true), out) << "slicing disagrees";
  }
  return out;
}

std::string robotsLine(int robots) {
  std::string line = "robots";
  for (int i = 0; i < robots; ++i) line += " r" + std::to_string(i);
  return line + ";\n";
}

// Every robot counts x up to 2, one step at a time while it holds the token `busy`; it may also take
// the token without counting (spin). Whether every robot gets to 2 depends on fairness to each
// robot's own step, which is enabled again and again but not for ever (others hold the token).
TEST(LivenessSymmetry, FairnessIsPerRobotNotPerOrbit) {
  for (int robots = 2; robots <= 4; ++robots) {
    auto model = [&](const std::string& stepFairness) {
      std::string text = "semo-ir 1;\n" + robotsLine(robots) + "var busy : bool = false;\n"
                         "rule release @fair : busy -> busy' = false;\n";
      std::string all, any;
      for (int i = 0; i < robots; ++i) {
        std::string r = "r" + std::to_string(i);
        text += "var " + r + ".x : 0..2 = 0 @robot(" + r + ");\n";
        text += "rule " + r + "_step @robot(" + r + ") " + stepFairness + " : !busy && " + r + ".x < 2 -> busy' = true, " + r +
                ".x' = " + r + ".x + 1;\n";
        text += "rule " + r + "_spin @robot(" + r + ") @fair : !busy -> busy' = true;\n";
        all += (all.empty() ? "" : " && ") + r + ".x == 2";
        any += (any.empty() ? "" : " || ") + r + ".x == 2";
      }
      return test::parseIr(text + "property all : eventually {" + all + "};\nproperty any : eventually {" + any +
                           "};\nproperty again : always eventually {!busy};\n");
    };
    ir::Model weak = model("@fair"), strong = model("@strongly_fair");
    ASSERT_FALSE(Symmetry::find(weak).empty());
    std::uint32_t reduced = 0;
    std::vector<Verdict> quotient = verdicts(weak, true, &reduced);
    EXPECT_EQ(reduced, 3u);
    // Weak: the robots may spin for ever. Strong: each robot's step is taken whenever it recurs.
    EXPECT_EQ(quotient, (std::vector<Verdict>{Verdict::Violated, Verdict::Violated, Verdict::Proven})) << robots << " robots";
    EXPECT_EQ(verdicts(weak, false), quotient) << robots << " robots";
    EXPECT_EQ(verdicts(strong, true), (std::vector<Verdict>{Verdict::Proven, Verdict::Proven, Verdict::Proven})) << robots;
    EXPECT_EQ(verdicts(strong, false), (std::vector<Verdict>{Verdict::Proven, Verdict::Proven, Verdict::Proven})) << robots;
  }
}

// A token passed between robots; the holder may work once. The quotient has one state per
// "who worked", and passing the token permutes the robots along its cycles: fairness must follow
// each robot through those permutations.
TEST(LivenessSymmetry, FairnessFollowsRobotsAroundPermutingCycles) {
  for (int robots = 2; robots <= 3; ++robots) {
    auto model = [&](const std::string& workFairness) {
      std::string vars, rules, all, none;
      for (int i = 0; i < robots; ++i) {
        std::string r = "r" + std::to_string(i);
        vars += "var " + r + ".token : bool = false @robot(" + r + ");\nvar " + r + ".worked : bool = false @robot(" + r + ");\n";
        none += (none.empty() ? "" : " && ") + ("!" + r + ".token");
        all += (all.empty() ? "" : " && ") + r + ".worked";
      }
      for (int i = 0; i < robots; ++i) {
        std::string r = "r" + std::to_string(i);
        rules += "rule " + r + "_grab @robot(" + r + ") @fair : " + none + " -> " + r + ".token' = true;\n";
        rules += "rule " + r + "_work @robot(" + r + ") " + workFairness + " : " + r + ".token && !" + r + ".worked -> " + r +
                 ".worked' = true;\n";
        for (int j = 0; j < robots; ++j) {
          if (j == i) continue;
          std::string q = "r" + std::to_string(j);
          rules += "rule " + r + "_pass_" + q + " @robot(" + r + ") @fair : " + r + ".token -> " + r + ".token' = false, " + q +
                   ".token' = true;\n";
        }
      }
      return test::parseIr("semo-ir 1;\n" + robotsLine(robots) + vars + rules + "property all : eventually {" + all + "};\n");
    };
    ir::Model weak = model("@fair"), strong = model("@strongly_fair");
    std::uint32_t reduced = 0;
    EXPECT_EQ(verdicts(weak, true, &reduced), std::vector<Verdict>{Verdict::Violated}) << robots << " robots";
    EXPECT_EQ(reduced, 1u);
    EXPECT_EQ(verdicts(weak, false), std::vector<Verdict>{Verdict::Violated}) << robots << " robots";
    // Strongly fair work: two robots both work; of three, two may pass the token between them
    // for ever (passing is only weakly fair, and each pass is enabled only while its robot holds it).
    Verdict expected = robots == 2 ? Verdict::Proven : Verdict::Violated;
    EXPECT_EQ(verdicts(strong, true), std::vector<Verdict>{expected}) << robots << " robots";
    EXPECT_EQ(verdicts(strong, false), std::vector<Verdict>{expected}) << robots << " robots";
  }
}

// The representative of a state may list the robots in another order than the state: fairness must
// rename the rules of such a state back. Here r1 waits at x = 1 (where its `finish` stays enabled)
// while r0 goes round 0 -> 2 -> 0, which the quotient sees as two states with the robots swapped
// in the second: the cycle is unfair to r1, so every fair run finishes.
TEST(LivenessSymmetry, FairnessFollowsRobotsThroughReorderedStates) {
  std::string text = "semo-ir 1;\nrobots r0 r1;\nvar r0.x : 0..3 = 0 @robot(r0);\nvar r1.x : 0..3 = 0 @robot(r1);\n";
  for (int i = 0; i < 2; ++i) {
    std::string r = "r" + std::to_string(i), other = "r" + std::to_string(1 - i);
    text += "rule " + r + "_ready @robot(" + r + ") @fair : " + r + ".x == 0 -> " + r + ".x' = 1;\n";
    text += "rule " + r + "_out @robot(" + r + ") @fair : " + r + ".x == 0 && " + other + ".x == 1 -> " + r + ".x' = 2;\n";
    text += "rule " + r + "_back @robot(" + r + ") @fair : " + r + ".x == 2 -> " + r + ".x' = 0;\n";
    text += "rule " + r + "_finish @robot(" + r + ") @fair : " + r + ".x == 1 -> " + r + ".x' = 3;\n";
  }
  ir::Model m = test::parseIr(text + "property done : eventually {r0.x == 3 || r1.x == 3};\n");
  std::uint32_t reduced = 0;
  EXPECT_EQ(verdicts(m, true, &reduced), std::vector<Verdict>{Verdict::Proven});
  EXPECT_EQ(reduced, 1u);
  EXPECT_EQ(verdicts(m, false), std::vector<Verdict>{Verdict::Proven});
}

// Random models: per robot the same rule templates (random guards over its own x, a shared g, and
// another robot's x), with random fairness; symmetric properties. Verdicts must agree.
class RandomSymmetricModel {
 public:
  explicit RandomSymmetricModel(std::uint32_t seed) : rng_(seed) {}

  std::string text() {
    int robots = pick(2, 3);
    std::ostringstream out;
    out << "semo-ir 1;\n" << robotsLine(robots) << "var g : 0..2 = 0;\n";
    for (int i = 0; i < robots; ++i) out << "var r" << i << ".x : 0..2 = 0 @robot(r" << i << ");\n";
    int templates = pick(3, 6);
    for (int t = 0; t < templates; ++t) {
      bool pairwise = pick(0, 2) == 0;
      int fairness = pick(0, 2);
      int guardX = pick(0, 2), guardG = pick(-1, 2), setX = pick(0, 2), setG = pick(-1, 2), otherX = pick(0, 2);
      int setOther = pick(-1, 2);  // a pairwise rule may hand something to the other robot
      bool environment = pick(0, 4) == 0;  // an unfair environment step on g
      for (int i = 0; i < robots; ++i) {
        for (int j = 0; j < robots; ++j) {
          if (pairwise == (i == j)) continue;  // own rules: i == j; pairwise: i != j
          std::string r = "r" + std::to_string(i), name = "t" + std::to_string(t) + "_" + r + (pairwise ? "_r" + std::to_string(j) : "");
          std::string attrs = environment ? " @kind(environment)" : fairness == 1 ? " @fair" : fairness == 2 ? " @strongly_fair" : "";
          out << "rule " << name << " @robot(" << r << ")" << attrs << " : " << r << ".x == " << guardX;
          if (guardG >= 0) out << " && g == " << guardG;
          if (pairwise) out << " && r" << j << ".x == " << otherX;
          out << " -> " << r << ".x' = " << setX;
          if (setG >= 0) out << ", g' = " << setG;
          if (pairwise && setOther >= 0) out << ", r" << j << ".x' = " << setOther;
          out << ";\n";
        }
      }
    }
    // Symmetric atoms: "every robot", "some robot", or about g only.
    auto atom = [&] {
      int value = pick(0, 2), kind = pick(0, 2);
      if (kind == 2) return "{g == " + std::to_string(value) + "}";
      std::string joined;
      for (int i = 0; i < robots; ++i) {
        joined += (joined.empty() ? "" : kind == 0 ? " && " : " || ") + ("r" + std::to_string(i) + ".x == " + std::to_string(value));
      }
      return "{" + joined + "}";
    };
    const char* shapes[] = {"eventually A", "always eventually A", "always (A => eventually B)", "eventually always A",
                            "A until B", "always (A => next B)"};
    for (int p = 0; p < 3; ++p) {
      std::string f = shapes[pick(0, 5)];
      for (std::size_t at = f.find('A'); at != std::string::npos; at = f.find('A')) f.replace(at, 1, atom());
      for (std::size_t at = f.find('B'); at != std::string::npos; at = f.find('B')) f.replace(at, 1, atom());
      out << "property p" << p << " : " << f << ";\n";
    }
    return out.str();
  }

 private:
  int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  std::mt19937 rng_;
};

TEST(LivenessSymmetry, RandomModelsAgreeWithAndWithoutSymmetry) {
  int proven = 0, violated = 0, reducedModels = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(600); ++seed) {
    std::string text = RandomSymmetricModel(seed).text();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    ir::Model m = test::parseIr(text);
    std::uint32_t reduced = 0;
    std::vector<Verdict> quotient = verdicts(m, true, &reduced), concrete = verdicts(m, false);
    ASSERT_EQ(quotient, concrete);
    reducedModels += reduced > 0 ? 1 : 0;
    for (Verdict v : concrete) (v == Verdict::Proven ? proven : violated) += 1;
  }
  // The sample must exercise both verdicts and the reduction itself.
  EXPECT_GT(proven, test::atLeast(100));
  EXPECT_GT(violated, test::atLeast(100));
  EXPECT_GT(reducedModels, test::atLeast(300));
}

}  // namespace
}  // namespace semo::checker
