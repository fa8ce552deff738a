// Model fingerprints (checker/fingerprint.hpp): SHA-256 itself, and the fingerprint of a
// translation: the same for the same mission, different for a different one.
#include <gtest/gtest.h>

#include "ir_support.hpp"
#include "mission_support.hpp"
#include "semo/checker/fingerprint.hpp"

namespace semo::checker {
namespace {

TEST(Fingerprint, Sha256OfKnownVectors) {
  // FIPS 180-2, appendix B.
  EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256Hex(std::string(1'000'000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  EXPECT_EQ(sha256Hex(std::string_view("a\0b", 3)).size(), 64u) << "NUL bytes are hashed, not a terminator";
  EXPECT_NE(sha256Hex(std::string_view("a\0b", 3)), sha256Hex("a"));
}

TEST(Fingerprint, StableAcrossTwoTranslationsOfTheSameMission) {
  const test::ShippedMission flood{"specs/defects/flood.semo", "specs/defects/strategy.xml"};
  std::optional<ir::Model> a = test::translateShipped(flood), b = test::translateShipped(flood);
  ASSERT_TRUE(a && b);
  const std::string fa = modelFingerprint(*a);
  EXPECT_EQ(fa, modelFingerprint(*b));
  EXPECT_EQ(fa.rfind("sha256:", 0), 0u);
  EXPECT_EQ(fa.size(), 7u + 64u);
  EXPECT_EQ(fa, "sha256:" + sha256Hex(ir::toText(*a)));
}

TEST(Fingerprint, DiffersForDifferentMissions) {
  std::optional<ir::Model> defect = test::translateShipped({"specs/defects/flood.semo", "specs/defects/strategy.xml"});
  std::optional<ir::Model> twin = test::translateShipped({"specs/defects/flood_fixed.semo", "specs/defects/strategy.xml"});
  std::optional<ir::Model> other = test::translateShipped({"specs/examples/patrol/patrol.semo", "specs/examples/patrol/strategy.xml"});
  ASSERT_TRUE(defect && twin && other);
  EXPECT_NE(modelFingerprint(*defect), modelFingerprint(*twin));
  EXPECT_NE(modelFingerprint(*defect), modelFingerprint(*other));
  EXPECT_NE(modelFingerprint(*twin), modelFingerprint(*other));
}

TEST(Fingerprint, AnyChangeToTheModelChangesIt) {
  ir::Model m = test::parseIr("semo-ir 1;\nvar x : 0..3 = 0;\nrule inc : x < 3 -> x' = x + 1;\ninvariant ok : x <= 3;\n");
  const std::string before = modelFingerprint(m);
  ir::Model changed = m;
  changed.variables[0].init = 1;
  EXPECT_NE(modelFingerprint(changed), before);
  changed = m;
  changed.rules[0].guard = ir::Expr::binary(ir::Op::Lt, ir::Expr::var(0), ir::Expr::constant(2));
  EXPECT_NE(modelFingerprint(changed), before);
  changed = m;
  changed.assumptions.push_back("nothing is lost");
  EXPECT_NE(modelFingerprint(changed), before);
}

}  // namespace
}  // namespace semo::checker
