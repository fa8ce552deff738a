// A robot's body integrated with CVODE, compared with the closed forms of the unicycle under a
// constant command: a straight line, and an arc of radius v/ω.
#include <gtest/gtest.h>

#include <cmath>

#include "semo/runtime/kinematics.hpp"

namespace semo::runtime {
namespace {

double angleDifference(double a, double b) { return std::remainder(a - b, 2 * M_PI); }

DriveGeometry unicycle(double maxSpeed = 1, double maxTurnRate = 2) {
  DriveGeometry g;
  g.maxSpeed = maxSpeed;
  g.maxTurnRate = maxTurnRate;
  return g;
}

TEST(Kinematics, StandsStillWithoutACommand) {
  Body b({1, 2, 0.5}, unicycle(), 3);
  EXPECT_EQ(b.time(), 3);
  b.advanceTo(100);
  EXPECT_EQ(b.time(), 100);
  EXPECT_EQ(b.pose().x, 1);
  EXPECT_EQ(b.pose().y, 2);
  EXPECT_EQ(b.pose().theta, 0.5);
  b.advanceTo(50);  // the past is ignored
  EXPECT_EQ(b.time(), 100);
}

TEST(Kinematics, StraightLine) {
  const double heading = 0.3;
  Body b({0, 0, heading}, unicycle());
  b.command(0.25, 0);
  for (int s = 1; s <= 60; ++s) {
    b.advanceTo(s);
    EXPECT_NEAR(b.pose().x, 0.25 * s * std::cos(heading), 1e-8);
    EXPECT_NEAR(b.pose().y, 0.25 * s * std::sin(heading), 1e-8);
    EXPECT_NEAR(b.pose().theta, heading, 1e-12);
  }
  EXPECT_EQ(b.time(), 60);
}

TEST(Kinematics, ConstantTurnFollowsTheArc) {
  const double x0 = 1, y0 = -2, th0 = 0.7, v = 0.3, w = 0.4;
  Body b({x0, y0, th0}, unicycle());
  b.command(v, w);
  for (double t = 0.5; t <= 60; t += 0.5) {
    b.advanceTo(t);
    const Pose p = b.pose();
    EXPECT_NEAR(p.x, x0 + v / w * (std::sin(th0 + w * t) - std::sin(th0)), 1e-6) << "t = " << t;
    EXPECT_NEAR(p.y, y0 - v / w * (std::cos(th0 + w * t) - std::cos(th0)), 1e-6) << "t = " << t;
    EXPECT_NEAR(angleDifference(p.theta, th0 + w * t), 0, 1e-6) << "t = " << t;
    EXPECT_GT(p.theta, -M_PI - 1e-12);
    EXPECT_LE(p.theta, M_PI + 1e-12);
  }
}

TEST(Kinematics, TurnOnTheSpot) {
  Body b({0, 0, 0}, unicycle());
  b.command(0, -1);
  b.advanceTo(M_PI / 2);
  EXPECT_NEAR(b.pose().x, 0, 1e-12);
  EXPECT_NEAR(b.pose().theta, -M_PI / 2, 1e-8);
}

TEST(Kinematics, CommandsAreClipped) {
  Body b({0, 0, 0}, unicycle(0.3, 1.5));
  b.command(2, -7);
  EXPECT_EQ(b.speed(), 0.3);
  EXPECT_EQ(b.turnRate(), -1.5);
  b.command(-1, 0.5);
  EXPECT_EQ(b.speed(), -0.3);
  EXPECT_EQ(b.turnRate(), 0.5);
  b.command(NAN, INFINITY);
  EXPECT_EQ(b.speed(), 0);
  EXPECT_EQ(b.turnRate(), 0);
  b.command(-1, 0);
  b.advanceTo(10);
  EXPECT_NEAR(b.pose().x, -3, 1e-8);  // backwards at the limit
}

TEST(Kinematics, WheeledRobotsConvertWheelSpeeds) {
  DriveGeometry g;
  g.wheeled = true;
  g.wheelRadius = 0.028;  // an EV3's wheel
  g.wheelSeparation = 0.12;
  g.maxSpeed = 0.5;
  g.maxTurnRate = 3;
  Body b({0, 0, 0}, g);
  b.wheelSpeeds(5, 5);
  EXPECT_NEAR(b.speed(), 0.14, 1e-15);
  EXPECT_EQ(b.turnRate(), 0);
  b.wheelSpeeds(2, 6);
  EXPECT_NEAR(b.speed(), 0.028 * 4, 1e-15);
  EXPECT_NEAR(b.turnRate(), 0.028 * 4 / 0.12, 1e-15);
  b.wheelSpeeds(-100, 100);  // clipped after the conversion
  EXPECT_EQ(b.speed(), 0);
  EXPECT_EQ(b.turnRate(), 3);

  Body legged({0, 0, 0}, unicycle());
  legged.wheelSpeeds(5, 5);
  EXPECT_EQ(legged.speed(), 0);
}

TEST(Kinematics, ManyCommandChanges) {
  // A square driven as 4 x (straight 2 s, quarter turn 1 s), 25 times: back at the start each lap.
  Body b({0, 0, 0}, unicycle(1, M_PI / 2));
  double t = 0;
  for (int lap = 0; lap < 25; ++lap) {
    for (int side = 0; side < 4; ++side) {
      b.command(0.5, 0);
      b.advanceTo(t += 2);
      b.command(0, M_PI / 2);
      b.advanceTo(t += 1);
    }
    EXPECT_NEAR(b.pose().x, 0, 1e-6) << "lap " << lap;
    EXPECT_NEAR(b.pose().y, 0, 1e-6) << "lap " << lap;
    EXPECT_NEAR(angleDifference(b.pose().theta, 0), 0, 1e-6) << "lap " << lap;
  }
  EXPECT_EQ(b.time(), 300);
  // Stopping and resuming keeps the pose.
  b.command(0, 0);
  b.advanceTo(400);
  const Pose still = b.pose();
  b.command(1, 0);
  b.advanceTo(401);
  EXPECT_NEAR(b.pose().x - still.x, 1, 1e-8);
}

TEST(Kinematics, MovesWithItsState) {
  Body a({0, 0, 0}, unicycle());
  a.command(1, 0);
  a.advanceTo(1);
  Body b = std::move(a);
  b.advanceTo(2);
  EXPECT_NEAR(b.pose().x, 2, 1e-8);
  EXPECT_EQ(b.geometry().maxSpeed, 1);
}

}  // namespace
}  // namespace semo::runtime
