#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "semo/frontend/robot_catalog.hpp"

namespace semo {
namespace {

const std::string kRobots = SEMO_SOURCE_DIR "/specs/robots/";

std::vector<std::string> names(const RobotType& t) {
  std::vector<std::string> out;
  for (const Capability& c : t.capabilities) out.push_back(c.name);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(RobotCatalog, TurtlebotBurgerCapabilitiesAndWheels) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  auto type = loadRobotType(sources, kRobots + "turtlebot3_burger.urdf", {}, diags);
  ASSERT_TRUE(type.has_value()) << diags.format(diags.diagnostics().front());
  EXPECT_EQ(type->name, "TurtlebotBurger");
  EXPECT_EQ(names(*type), (std::vector<std::string>{"DifferentialDrive", "Imu", "LaserDistanceSensor", "Led",
                                                     "LightSensor", "Wheels"}));
  ASSERT_TRUE(type->wheels.has_value());
  EXPECT_EQ(type->wheels->wheelCount, 2);
  EXPECT_NEAR(type->wheels->radius, 0.033, 1e-6);
  EXPECT_NEAR(type->wheels->separation, 0.160, 1e-6);
}

TEST(RobotCatalog, EveryShippedRobotLoads) {
  const std::pair<const char*, std::vector<std::string>> expected[] = {
      {"irobot_create.urdf", {"Bumper", "CliffSensor", "DifferentialDrive", "Wheels"}},
      {"ev3_robot.urdf", {"ColorSensor", "DifferentialDrive", "ProximitySensor", "Wheels"}},
      {"quadruped.urdf", {"Camera", "Legs", "ProximitySensor"}}};
  for (const auto& [file, caps] : expected) {
    SourceManager sources;
    DiagnosticEngine diags(sources);
    auto type = loadRobotType(sources, kRobots + file, {}, diags);
    ASSERT_TRUE(type.has_value()) << file;
    std::vector<std::string> got = names(*type);
    for (const std::string& c : caps) {
      EXPECT_NE(std::find(got.begin(), got.end(), c), got.end()) << file << " lacks " << c;
    }
    EXPECT_FALSE(diags.hasErrors());
  }
}

TEST(RobotCatalog, UrdfdomErrorsPointAtTheCulprit) {
  std::string path = testing::TempDir() + "/bad_joint.urdf";
  {
    std::ofstream out(path);
    out << "<robot name=\"R\">\n  <link name=\"base\"/>\n"
           "  <joint name=\"j\" type=\"fixed\">\n    <parent link=\"base\"/>\n    <child link=\"ghost\"/>\n  </joint>\n</robot>\n";
  }
  SourceManager sources;
  DiagnosticEngine diags(sources);
  EXPECT_FALSE(loadRobotType(sources, path, {}, diags).has_value());
  ASSERT_TRUE(diags.hasErrors());
  const Diagnostic& d = diags.diagnostics().front();
  EXPECT_NE(d.message.find("invalid URDF"), std::string::npos);
  EXPECT_EQ(d.range.begin.line, 3u);  // the <joint> named in urdfdom's message
  EXPECT_EQ(d.range.begin.column, 3u);
}

TEST(RobotCatalog, StrategyAdditionsAndTypeCheck) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  strategy::Strategy s;
  s.folder = SEMO_SOURCE_DIR "/specs";
  s.robots.push_back({"robots/ev3_robot.urdf", std::nullopt, {{"Speaker", "", {}}}, {}});
  s.robots.push_back({"robots/irobot_create.urdf", std::string("Roomba"), {}, {}});
  RobotCatalog catalog = buildCatalog(s, std::nullopt, sources, diags);
  ASSERT_EQ(catalog.types().size(), 1u);
  EXPECT_TRUE(catalog.find("Ev3Robot")->has("Speaker"));
  ASSERT_EQ(diags.errorCount(), 1u);
  EXPECT_NE(diags.diagnostics().front().message.find("does not match the URDF robot name 'iRobotCreate'"), std::string::npos);
}

TEST(RobotCatalog, RobotsFolderWithoutRobotEntries) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  RobotCatalog catalog = buildCatalog({}, std::string(SEMO_SOURCE_DIR "/specs/robots"), sources, diags);
  EXPECT_EQ(catalog.types().size(), 4u);
  EXPECT_NE(catalog.find("QuadrupedRobot"), nullptr);
}

}  // namespace
}  // namespace semo
