// Shapes of the world (circles and simple polygons) and the world's lookups by name (world.hpp).
// The simulator asks these questions at every sample of every robot (is it inside a region, how far
// is the nearest obstacle), so they are plain loops without allocation.
#include <algorithm>
#include <cmath>

#include "semo/runtime/world.hpp"

namespace semo::runtime {

namespace {

// A point this close to a polygon's edge counts as inside: a robot touching a region's border is
// in it, whichever way the floating-point crossing test happens to round.
constexpr double kOnEdge = 1e-12;

double segmentDistance(Vec2 p, Vec2 a, Vec2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double length2 = dx * dx + dy * dy;
  double t = 0;
  if (length2 > 0) t = std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / length2, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

double edgeDistance(const std::vector<Vec2>& points, Vec2 p) {
  double best = INFINITY;
  for (std::size_t i = 0, n = points.size(); i < n; ++i) {
    best = std::min(best, segmentDistance(p, points[i], points[(i + 1) % n]));
  }
  return best;
}

// Even-odd rule: a horizontal ray from p crosses the boundary an odd number of times when p is
// inside. The half-open test on y (one end included, the other not) counts a vertex on the ray once.
bool evenOdd(const std::vector<Vec2>& points, Vec2 p) {
  bool inside = false;
  for (std::size_t i = 0, n = points.size(), j = n - 1; i < n; j = i++) {
    const Vec2 a = points[i], b = points[j];
    if ((a.y > p.y) != (b.y > p.y)) {
      const double crossX = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (p.x < crossX) inside = !inside;
    }
  }
  return inside;
}

}  // namespace

bool Shape::contains(Vec2 p) const {
  if (kind == Kind::Circle) return std::hypot(p.x - center.x, p.y - center.y) <= radius;
  if (points.size() < 3) return false;  // the reader never builds one; code might
  return evenOdd(points, p) || edgeDistance(points, p) <= kOnEdge;
}

double Shape::distance(Vec2 p) const {
  if (kind == Kind::Circle) return std::max(0.0, std::hypot(p.x - center.x, p.y - center.y) - radius);
  if (points.empty()) return INFINITY;
  if (points.size() >= 3 && evenOdd(points, p)) return 0;
  const double d = edgeDistance(points, p);
  return d <= kOnEdge ? 0 : d;
}

// Worlds are small (tens of entries): a linear search keeps the structs plain vectors in file order.
const Place* World::place(std::string_view name) const {
  for (const Place& p : places) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

const StartPose* World::start(std::string_view robot) const {
  for (const StartPose& s : starts) {
    if (s.robot == robot) return &s;
  }
  return nullptr;
}

const ValueSource* World::value(std::string_view name) const {
  for (const ValueSource& v : values) {
    if (v.name == name) return &v;
  }
  return nullptr;
}

}  // namespace semo::runtime
