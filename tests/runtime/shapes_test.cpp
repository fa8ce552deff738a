// Shapes of the world: inside tests (even-odd rule for polygons, concave ones included) and the
// distance from a point to a shape, which the obstacle sensors use.
#include <gtest/gtest.h>

#include <cmath>

#include "semo/runtime/world.hpp"

namespace semo::runtime {
namespace {

Shape circle(Vec2 c, double r) {
  Shape s;
  s.kind = Shape::Kind::Circle;
  s.center = c;
  s.radius = r;
  return s;
}

Shape polygon(std::vector<Vec2> points) {
  Shape s;
  s.kind = Shape::Kind::Polygon;
  s.points = std::move(points);
  return s;
}

TEST(Shape, Circle) {
  const Shape c = circle({1, 1}, 2);
  EXPECT_TRUE(c.contains({1, 1}));
  EXPECT_TRUE(c.contains({3, 1}));  // on the border
  EXPECT_FALSE(c.contains({3.01, 1}));
  EXPECT_EQ(c.distance({2, 1}), 0);
  EXPECT_NEAR(c.distance({1, 5}), 2, 1e-15);
  EXPECT_NEAR(c.distance({4, 5}), 3, 1e-15);  // 5 from the centre
}

TEST(Shape, ConvexPolygon) {
  const Shape square = polygon({{0, 0}, {2, 0}, {2, 2}, {0, 2}});
  EXPECT_TRUE(square.contains({1, 1}));
  EXPECT_TRUE(square.contains({0, 1}));  // on an edge
  EXPECT_TRUE(square.contains({2, 2}));  // a corner
  EXPECT_FALSE(square.contains({2.5, 1}));
  EXPECT_FALSE(square.contains({-1, -1}));
  EXPECT_EQ(square.distance({1, 1}), 0);
  EXPECT_NEAR(square.distance({3, 1}), 1, 1e-15);
  EXPECT_NEAR(square.distance({3, 3}), std::sqrt(2.0), 1e-15);  // nearest: the corner
  EXPECT_NEAR(square.distance({1, -0.5}), 0.5, 1e-15);
}

TEST(Shape, ConcavePolygon) {
  // A U open at the top: the notch (1..2 x 1..3) is outside.
  const Shape u = polygon({{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}});
  EXPECT_TRUE(u.contains({0.5, 2.5}));
  EXPECT_TRUE(u.contains({2.5, 2.5}));
  EXPECT_TRUE(u.contains({1.5, 0.5}));
  EXPECT_FALSE(u.contains({1.5, 2}));
  EXPECT_NEAR(u.distance({1.5, 2}), 0.5, 1e-15);  // to either arm
  // A ray from (1.5, 1) runs along the notch's floor (through two vertices): still counted right.
  EXPECT_TRUE(u.contains({0.5, 1}));
  EXPECT_FALSE(u.contains({3.5, 1}));
}

TEST(Shape, SelfIntersectingPolygonUsesEvenOdd) {
  // A pentagram drawn in one stroke: its centre pentagon is crossed twice, so it is outside.
  std::vector<Vec2> star;
  for (int k = 0; k < 5; ++k) {
    const double a = M_PI / 2 + k * 4 * M_PI / 5;
    star.push_back({std::cos(a), std::sin(a)});
  }
  const Shape s = polygon(star);
  EXPECT_FALSE(s.contains({0, 0}));
  EXPECT_TRUE(s.contains({0, 0.7}));  // inside the top point
}

TEST(Shape, DegeneratePolygonsFromCode) {
  EXPECT_FALSE(polygon({}).contains({0, 0}));
  EXPECT_TRUE(std::isinf(polygon({}).distance({0, 0})));
  EXPECT_NEAR(polygon({{0, 0}, {2, 0}}).distance({1, 1}), 1, 1e-15);
}

TEST(World, LooksEntriesUpByName) {
  World w;
  w.places.push_back({"base camp", {1, 2}, {}});
  w.starts.push_back({"ev3_0", {0, 0}, 1.0, {}});
  ValueSource v;
  v.name = "Team.light";
  w.values.push_back(v);
  ASSERT_NE(w.place("base camp"), nullptr);
  EXPECT_EQ(w.place("base camp")->at.y, 2);
  EXPECT_EQ(w.place("base"), nullptr);
  EXPECT_EQ(w.start("ev3_0")->heading, 1.0);
  EXPECT_EQ(w.start("ev3_1"), nullptr);
  EXPECT_NE(w.value("Team.light"), nullptr);
  EXPECT_EQ(w.value("Team.dark"), nullptr);
}

}  // namespace
}  // namespace semo::runtime
