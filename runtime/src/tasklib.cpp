// The simulated task library: one behaviour per service of specs/examples, registered by name.
// Behaviours are deliberately plain (drive to a point, turn, march, pause): they stand for the
// robots' real tasks so that a mission can run end to end, with motion the trace can show.
#include "semo/runtime/tasklib.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace semo::runtime {
namespace {

double wrap(double a) {
  while (a > std::numbers::pi) a -= 2 * std::numbers::pi;
  while (a < -std::numbers::pi) a += 2 * std::numbers::pi;
  return a;
}

// Steers towards `to`: turns on the spot when facing away, else drives with a proportional turn.
// Returns the distance left.
double steer(BehaviourContext& ctx, Vec2 to, double speedFactor = 1.0) {
  const Pose p = ctx.body->pose();
  const double dx = to.x - p.x, dy = to.y - p.y;
  const double distance = std::hypot(dx, dy);
  const double error = wrap(std::atan2(dy, dx) - p.theta);
  const double vmax = ctx.body->geometry().maxSpeed * speedFactor;
  const double speed = std::abs(error) > 0.6 ? 0.0 : std::min(vmax, distance / std::max(ctx.dt, 1e-3) * 0.5);
  ctx.body->command(speed, 3.0 * error);
  return distance;
}

// move(place), walk(place): drive to a named place of the world.
class GoTo final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override {
    const Place* place = ctx.args.empty() ? nullptr : ctx.world->place(ctx.args.front());
    known_ = place != nullptr;
    if (known_) target_ = place->at, *ctx.destination = place->at;
  }
  bool step(BehaviourContext& ctx) override {
    if (!known_ || steer(ctx, target_) < 0.1) {
      ctx.body->command(0, 0);
      return true;
    }
    return false;
  }

 private:
  Vec2 target_;
  bool known_ = false;
};

// A group service's search (searchPaper): drives to the nearest place where a fact it does not hold
// can be found; stands still once it knows every fact within its world.
class Search final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override { ctx.body->command(0, 0); }
  bool step(BehaviourContext& ctx) override {
    const Pose p = ctx.body->pose();
    const FactSite* nearest = nullptr;
    double best = 1e300;
    for (const FactSite* site : ctx.unknownFacts) {
      const double d = std::hypot(site->at.x - p.x, site->at.y - p.y);
      if (d < best) best = d, nearest = site;
    }
    if (nearest == nullptr) ctx.body->command(0, 0);
    else steer(ctx, nearest->at, 0.8);
    return false;
  }
};

// marchInLine: walks straight ahead at a steady pace; stops when its front touches an obstacle
// (it has walked into it).
class March final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override { ctx.body->command(0.6 * ctx.body->geometry().maxSpeed, 0); }
  bool step(BehaviourContext& ctx) override {
    const Pose p = ctx.body->pose();
    const Vec2 front{p.x + 0.1 * std::cos(p.theta), p.y + 0.1 * std::sin(p.theta)};
    const bool blocked = std::any_of(ctx.world->obstacles.begin(), ctx.world->obstacles.end(),
                                     [&](const Obstacle& o) { return o.shape.contains(front); });
    ctx.body->command(blocked ? 0.0 : 0.6 * ctx.body->geometry().maxSpeed, 0);
    return false;
  }
};

// turnBack: turns on the spot by half a turn.
class TurnBack final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override { target_ = wrap(ctx.body->pose().theta + std::numbers::pi); }
  bool step(BehaviourContext& ctx) override {
    const double error = wrap(target_ - ctx.body->pose().theta);
    if (std::abs(error) < 0.02) {
      ctx.body->command(0, 0);
      return true;
    }
    ctx.body->command(0, std::clamp(3.0 * error, -ctx.body->geometry().maxTurnRate, ctx.body->geometry().maxTurnRate));
    return false;
  }

 private:
  double target_ = 0;
};

// hide: drives towards the nearest obstacle (cover) for at most `limit` seconds.
class Hide final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override { since_ = ctx.now; }
  bool step(BehaviourContext& ctx) override {
    const Pose p = ctx.body->pose();
    const Obstacle* cover = nullptr;
    double best = 1e300;
    for (const Obstacle& o : ctx.world->obstacles) {
      const double d = o.shape.distance({p.x, p.y});
      if (d < best) best = d, cover = &o;
    }
    if (cover == nullptr || best < 0.3 || ctx.now - since_ >= 3.0) {
      ctx.body->command(0, 0);
      return true;
    }
    const Vec2 c = cover->shape.kind == Shape::Kind::Circle ? cover->shape.center : cover->shape.points.front();
    steer(ctx, c, 0.5);
    return false;
  }

 private:
  double since_ = 0;
};

// A call that takes a fixed time with a fixed command (flash a LED, back off, follow the joystick).
class Timed final : public Behaviour {
 public:
  Timed(double seconds, double speed, double turn) : seconds_(seconds), speed_(speed), turn_(turn) {}
  void start(BehaviourContext& ctx) override {
    since_ = ctx.now;
    ctx.body->command(speed_, turn_);
  }
  bool step(BehaviourContext& ctx) override {
    if (ctx.now - since_ + 1e-9 < seconds_) return false;
    ctx.body->command(0, 0);
    return true;
  }

 private:
  double seconds_, speed_, turn_;
  double since_ = 0;
};

}  // namespace

TaskLibrary TaskLibrary::standard() {
  TaskLibrary lib;
  lib.add("move", [] { return std::make_unique<GoTo>(); });
  lib.add("walk", [] { return std::make_unique<GoTo>(); });
  lib.add("searchPaper", [] { return std::make_unique<Search>(); });
  lib.add("marchInLine", [] { return std::make_unique<March>(); });
  lib.add("turnBack", [] { return std::make_unique<TurnBack>(); });
  lib.add("hide", [] { return std::make_unique<Hide>(); });
  lib.add("flashLed", [] { return std::make_unique<Timed>(0.5, 0, 0); });
  lib.add("teleoperate", [] { return std::make_unique<Timed>(1.0, 0.1, 0.3); });
  lib.add("backOff", [] { return std::make_unique<Timed>(1.0, -0.1, 0); });
  lib.add("stop", [] { return std::make_unique<Timed>(0, 0, 0); });
  lib.add("displayReport", [] { return std::make_unique<Timed>(0, 0, 0); });
  return lib;
}

void TaskLibrary::add(const std::string& service, Factory factory) { factories_[service] = std::move(factory); }

bool TaskLibrary::has(std::string_view service) const { return factories_.find(service) != factories_.end(); }

std::unique_ptr<Behaviour> TaskLibrary::make(std::string_view service) const {
  auto it = factories_.find(service);
  if (it != factories_.end()) return it->second();
  return std::make_unique<Timed>(0.1, 0, 0);
}

}  // namespace semo::runtime
