// --prop: globs over property names, and the selection of a model's properties (verify.hpp).
#include <gtest/gtest.h>

#include "semo/checker/verify.hpp"

namespace semo::checker {
namespace {

TEST(PropertySelection, GlobsTakeStarAndQuestionMarkAndReadBracketsLiterally) {
  EXPECT_TRUE(globMatches("unique_leader[*]", "unique_leader[ReportPapers]"));
  EXPECT_FALSE(globMatches("unique_leader[*]", "unique_leader"));
  EXPECT_TRUE(globMatches("*", ""));
  EXPECT_TRUE(globMatches("a*b*c", "aXXbYYbc"));
  EXPECT_FALSE(globMatches("a*b*c", "aXXbYYbd"));
  EXPECT_TRUE(globMatches("leader_?eelection[W*]", "leader_reelection[WatchLight]"));
  EXPECT_FALSE(globMatches("leader_?eelection[W*]", "leader_reelection[ReportPapers]"));
  EXPECT_TRUE(globMatches("group_formation[March group (Legs, ...)]", "group_formation[March group (Legs, ...)]"));
  EXPECT_FALSE(globMatches("[a]", "a")) << "brackets are not character classes";
  // Many stars against a long name that fails at the end stay fast (at most glob size x name size).
  std::string stars(200, '*');
  stars += 'z';
  EXPECT_FALSE(globMatches(stars, std::string(5000, 'a')));
}

TEST(PropertySelection, KeepsTheChosenPropertiesAndDropsDeadlockFreedomUnlessChosen) {
  ir::Model m;
  m.variables.push_back({"x", 0, 1, 0, false, ir::kNoRobot, {}, {}});
  m.invariants.push_back({"unique_leader[A]", "", ir::Expr::constant(1)});
  m.invariants.push_back({"unique_leader[B]", "", ir::Expr::constant(1)});
  m.invariants.push_back({"safe", "", ir::Expr::constant(1)});
  m.properties.push_back({"mode_agreement[T]", "", {}, true});
  m.validEnd = ir::Expr::constant(1);
  ir::Model copy = m;
  const std::vector<std::string> kept = selectProperties(copy, {"unique_leader", "mode_agreement[*]"});
  EXPECT_EQ(kept, (std::vector<std::string>{"unique_leader[A]", "unique_leader[B]", "mode_agreement[T]"}));
  EXPECT_EQ(copy.invariants.size(), 2u);
  EXPECT_EQ(copy.properties.size(), 1u);
  EXPECT_FALSE(copy.validEnd.has_value());
  copy = m;
  EXPECT_EQ(selectProperties(copy, {"deadlock_freedom"}), std::vector<std::string>{"deadlock_freedom"});
  EXPECT_TRUE(copy.validEnd.has_value());
  EXPECT_TRUE(copy.invariants.empty());
  // `!` leaves out: alone, everything but what it matches; with other globs, what they choose but it.
  copy = m;
  EXPECT_EQ(selectProperties(copy, {"!mode_agreement"}),
            (std::vector<std::string>{"unique_leader[A]", "unique_leader[B]", "safe", "deadlock_freedom"}));
  EXPECT_TRUE(copy.properties.empty());
  EXPECT_TRUE(copy.validEnd.has_value());
  copy = m;
  EXPECT_EQ(selectProperties(copy, {"unique_leader", "!*[B]"}), std::vector<std::string>{"unique_leader[A]"});
  EXPECT_TRUE(propertySelected({"!unique_leader[*]"}, {"unique_leader", "unique_leader[*]", "unique_leader[]"}) == false);
  EXPECT_TRUE(propertySelected({"!unique_leader"}, {"mode_agreement"}));
  EXPECT_FALSE(propertySelected({"safe", "!mode_agreement"}, {"unique_leader[A]"}));
  copy = m;
  try {
    selectProperties(copy, {"!*"});
    FAIL() << "a selection that leaves nothing is an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--prop leaves out every property of the model; its properties: unique_leader[A]"), std::string::npos)
        << e.what();
  }
  copy = m;
  try {
    selectProperties(copy, {"!nosuch"});
    FAIL() << "a `!` glob that matches nothing is an error too";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'!nosuch' matches no property"), std::string::npos) << e.what();
  }
  copy = m;
  try {
    selectProperties(copy, {"safe", "nosuch*"});
    FAIL() << "a glob that matches nothing is an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'nosuch*' matches no property"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("unique_leader[A], unique_leader[B], safe, deadlock_freedom, mode_agreement[T]"), std::string::npos);
  }
  EXPECT_EQ(copy.invariants.size(), 3u) << "nothing is removed when the selection is refused";
}

}  // namespace
}  // namespace semo::checker
