// The simulated task library: one behaviour per service of specs/examples, registered by name.
// Behaviours are deliberately plain (drive to a point, turn, march, pause): they stand for the
// robots' real tasks so that a mission can run end to end, with motion the trace can show.
#include "semo/runtime/tasklib.hpp"

#include <algorithm>
#include <array>
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

// spreadOut (group service): each robot claims one sector. It heads for the nearest sector it does
// not know to be claimed (a fact site of the service's knowledge it does not hold) and, once it is
// within the site's radius (where it finds the fact: its claim), stays there, whatever it learns
// later: a robot never leaves its sector for another, so the team spreads over the area rather than
// gathering at the last free sector. Only when a teammate of lower index stands in the same sector
// (both reached it before either heard of the other's claim) does it yield and move on. One that
// learns on its way that its sector was claimed re-aims at the nearest one still free as far as it
// knows; one that knows every sector claimed stops where it is.
class SpreadOut final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override { ctx.body->command(0, 0); }
  bool step(BehaviourContext& ctx) override {
    const Pose p = ctx.body->pose();
    if (held_ != nullptr && sharedWithLowerIndex(ctx, *held_)) held_ = nullptr;
    const FactSite* nearest = nullptr;
    double best = 1e300;
    for (const FactSite* site : ctx.unknownFacts) {
      const double d = std::hypot(site->at.x - p.x, site->at.y - p.y);
      if (d <= site->radius && held_ == nullptr) held_ = site;
      if (d < best) best = d, nearest = site;
    }
    if (held_ != nullptr || nearest == nullptr) ctx.body->command(0, 0);
    else steer(ctx, nearest->at, 0.8);
    return false;
  }

 private:
  const FactSite* held_ = nullptr;  // the sector it reached first as far as it knew: it stays there

  static bool sharedWithLowerIndex(const BehaviourContext& ctx, const FactSite& site) {
    for (std::size_t r = 0; r < ctx.robot; ++r) {
      if (!(*ctx.alive)[r] || (*ctx.teams)[r] != (*ctx.teams)[ctx.robot]) continue;
      if (std::hypot((*ctx.poses)[r].x - site.at.x, (*ctx.poses)[r].y - site.at.y) <= site.radius + 0.05) return true;
    }
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

// `p` moved 0.3 m inside the world's arena where it has one: its walls stop a real robot, so a
// behaviour that aims at a point of its own making aims inside them.
Vec2 insideArena(const BehaviourContext& ctx, Vec2 p) {
  if (!ctx.world->arena) return p;
  const auto& [lo, hi] = *ctx.world->arena;
  return {std::clamp(p.x, std::min(lo.x + 0.3, hi.x), std::max(hi.x - 0.3, lo.x)), std::clamp(p.y, std::min(lo.y + 0.3, hi.y), std::max(hi.y - 0.3, lo.y))};
}

// pursue(team): drives after one robot of the named team (of any other team when no name is given):
// the nearest live one not already within reach (a robot within reach has just been caught). Over
// once it is reached or gone; when there is nobody to chase it waits a second first, so that the
// mission's restart of the pursuit is not a busy loop.
class Pursue final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override {
    since_ = ctx.now;
    const std::string_view own = (*ctx.teams)[ctx.robot];
    const Pose me = ctx.body->pose();
    double best = 1e300;
    target_ = -1;
    for (std::size_t r = 0; r < ctx.poses->size(); ++r) {
      const bool wanted = ctx.args.empty() ? (*ctx.teams)[r] != own : (*ctx.teams)[r] == ctx.args.front();
      if (r == ctx.robot || !(*ctx.alive)[r] || !wanted) continue;
      const double d = std::hypot((*ctx.poses)[r].x - me.x, (*ctx.poses)[r].y - me.y);
      if (d > kReach && d < best) best = d, target_ = static_cast<int>(r);
    }
  }
  bool step(BehaviourContext& ctx) override {
    const bool over = target_ < 0 ? ctx.now - since_ + 1e-9 >= 1.0
                                  : !(*ctx.alive)[target_] || steer(ctx, {(*ctx.poses)[target_].x, (*ctx.poses)[target_].y}) < kReach;
    if (over || target_ < 0) ctx.body->command(0, 0);
    return over;
  }

 private:
  static constexpr double kReach = 0.35;  // metres: caught
  int target_ = -1;
  double since_ = 0;
};

// runAway: drives away from the robots of the other teams (from its own when it is alone with them)
// for a few seconds, re-aiming every period as the pursuers move.
class RunAway final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override { since_ = ctx.now; }
  bool step(BehaviourContext& ctx) override {
    // Away from every robot of the other teams at once, each weighing 1/d^2 (the nearest counts
    // most): fleeing only the nearest flips direction whenever two chasers swap places. With no
    // other team in sight, away from its own team.
    const Pose me = ctx.body->pose();
    double ax = 0, ay = 0;
    for (const bool sameTeam : {false, true}) {
      for (std::size_t r = 0; r < ctx.poses->size(); ++r) {
        if (r == ctx.robot || !(*ctx.alive)[r] || (((*ctx.teams)[r] == (*ctx.teams)[ctx.robot]) != sameTeam)) continue;
        const double dx = me.x - (*ctx.poses)[r].x, dy = me.y - (*ctx.poses)[r].y;
        const double d2 = std::max(dx * dx + dy * dy, 1e-6);
        ax += dx / (d2 * std::sqrt(d2));
        ay += dy / (d2 * std::sqrt(d2));
      }
      if (ax != 0 || ay != 0) break;
    }
    if ((ax == 0 && ay == 0) || ctx.now - since_ + 1e-9 >= kSeconds) {
      ctx.body->command(0, 0);
      return true;
    }
    // 1 m ahead on the line away. Against a wall that point lies behind the wall: the robot slides
    // along the wall instead, in the direction it already escapes in while that stays open (so that
    // it does not swing from side to side as the chasers move), else turning off the line away a
    // little more at a time (45 degrees, 90, 135; one side first, in a fixed order, so that runs
    // stay deterministic). Cornered on every side, it stays there until the time is up.
    auto open = [&](double a, Vec2& target) {
      target = insideArena(ctx, {me.x + std::cos(a), me.y + std::sin(a)});
      return std::hypot(target.x - me.x, target.y - me.y) >= 0.5;
    };
    const double away = std::atan2(ay, ax);
    Vec2 target;
    if (open(away, target) || (sliding_ && open(slide_, target))) {
      steer(ctx, target);
      return false;
    }
    for (const double turn : {0.25, -0.25, 0.5, -0.5, 0.75, -0.75}) {
      if (open(away + turn * std::numbers::pi, target)) {
        slide_ = away + turn * std::numbers::pi;
        sliding_ = true;
        steer(ctx, target);
        return false;
      }
    }
    ctx.body->command(0, 0);
    return false;
  }

 private:
  static constexpr double kSeconds = 3.0;
  double since_ = 0;
  bool sliding_ = false;
  double slide_ = 0;  // the direction along a wall it escapes in
};

// wander: goes round a fixed square lap of 1 m from where the call starts (ahead, then to the left;
// within the arena), for ever: the mode change ends it. Deterministic, so runs with the same seed draw the same paths.
class Wander final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override {
    const Pose p = ctx.body->pose();
    const Vec2 ahead{std::cos(p.theta), std::sin(p.theta)}, left{-ahead.y, ahead.x};
    lap_ = {Vec2{p.x + ahead.x, p.y + ahead.y}, Vec2{p.x + ahead.x + left.x, p.y + ahead.y + left.y}, Vec2{p.x + left.x, p.y + left.y},
            Vec2{p.x, p.y}};
    for (Vec2& corner : lap_) corner = insideArena(ctx, corner);
    next_ = 0;
  }
  bool step(BehaviourContext& ctx) override {
    if (steer(ctx, lap_[next_], 0.6) < 0.1) next_ = (next_ + 1) % lap_.size();
    return false;
  }

 private:
  std::array<Vec2, 4> lap_{};
  std::size_t next_ = 0;
};

// patrolArea (group service, no goal: runs until the mode changes): round the world's fact sites
// (the aisles) in the order the world lists them, for ever. It resumes on the leg of that lap
// nearest to the robot, heading for the leg's end: a lap anchored on the world rather than on the
// robot keeps the guards in the area and going the same way however often they scatter and come
// back. The aisles' knowledge is found by passing them.
class Patrol final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override {
    ctx.body->command(0, 0);
    const std::vector<FactSite>& sites = ctx.world->facts;
    const Pose p = ctx.body->pose();
    double best = 1e300;
    for (std::size_t i = 0; i < sites.size(); ++i) {  // distance from p to the leg i -> i+1
      const Vec2 a = sites[i].at, b = sites[(i + 1) % sites.size()].at;
      const double lx = b.x - a.x, ly = b.y - a.y, len2 = lx * lx + ly * ly;
      const double u = len2 > 0 ? std::clamp(((p.x - a.x) * lx + (p.y - a.y) * ly) / len2, 0.0, 1.0) : 0.0;
      const double d = std::hypot(a.x + u * lx - p.x, a.y + u * ly - p.y);
      if (d < best) best = d, next_ = (i + 1) % sites.size();
    }
  }
  bool step(BehaviourContext& ctx) override {
    const std::vector<FactSite>& sites = ctx.world->facts;
    if (sites.empty()) ctx.body->command(0, 0);
    else if (steer(ctx, sites[next_].at, 0.8) < 0.15) next_ = (next_ + 1) % sites.size();
    return false;
  }

 private:
  std::size_t next_ = 0;
};

// scatter: drives 1 m straight out from the centre of its team's live robots (straight ahead when it
// stands at the centre), then stops: the group opens up around where it was (within the arena).
class Scatter final : public Behaviour {
 public:
  void start(BehaviourContext& ctx) override {
    const Pose me = ctx.body->pose();
    double cx = 0, cy = 0, n = 0;
    for (std::size_t r = 0; r < ctx.poses->size(); ++r) {
      if (!(*ctx.alive)[r] || (*ctx.teams)[r] != (*ctx.teams)[ctx.robot]) continue;
      cx += (*ctx.poses)[r].x, cy += (*ctx.poses)[r].y, n += 1;
    }
    double dx = me.x - cx / n, dy = me.y - cy / n;
    double d = std::hypot(dx, dy);
    if (d < 1e-3) dx = std::cos(me.theta), dy = std::sin(me.theta), d = 1;
    target_ = insideArena(ctx, {me.x + dx / d, me.y + dy / d});
  }
  bool step(BehaviourContext& ctx) override {
    if (steer(ctx, target_) < 0.1) {
      ctx.body->command(0, 0);
      return true;
    }
    return false;
  }

 private:
  Vec2 target_;
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
  lib.add("pursue", [] { return std::make_unique<Pursue>(); });
  lib.add("runAway", [] { return std::make_unique<RunAway>(); });
  lib.add("wander", [] { return std::make_unique<Wander>(); });
  lib.add("spreadOut", [] { return std::make_unique<SpreadOut>(); });
  lib.add("patrolArea", [] { return std::make_unique<Patrol>(); });
  lib.add("scatter", [] { return std::make_unique<Scatter>(); });
  lib.add("holdPosition", [] { return std::make_unique<Timed>(1.0, 0, 0); });  // stand still, then the final mode holds it
  return lib;
}

TaskLibrary& TaskLibrary::registry() {
  static TaskLibrary library = standard();
  return library;
}

void TaskLibrary::add(const std::string& service, Factory factory) { factories_[service] = std::move(factory); }

bool TaskLibrary::has(std::string_view service) const { return factories_.find(service) != factories_.end(); }

std::unique_ptr<Behaviour> TaskLibrary::make(std::string_view service) const {
  auto it = factories_.find(service);
  if (it != factories_.end()) return it->second();
  return std::make_unique<Timed>(0.1, 0, 0);
}

}  // namespace semo::runtime
