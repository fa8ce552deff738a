// End-to-end tests of `semo-verify simulate` on the examples of specs/examples with a world beside
// the paper's two experiments (simulate_test.cpp): chase, deployment and patrol. Each runs the real
// CLI with --check-conformance on several seeds, with message loss where the mission assumes it and
// a crash where it assumes crashes, and reads the trace back: no step the model does not allow,
// and what the mission says happens (modes, catches, sectors held, patrol rounds), on positions.
// Coordinates (sectors, aisles, bays, shelves) are read from the world files, not copied here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

using namespace semo::e2e;
using nlohmann::json;

struct Point {
  double x = 0, y = 0;
};
double distance(Point a, Point b) { return std::hypot(a.x - b.x, a.y - b.y); }

std::string example(const std::string& name) {
  return "specs/examples/" + name + "/" + name + ".semo -s specs/examples/" + name + "/strategy.xml";
}

json worldOf(const std::string& name) {
  return json::parse(slurp(fs::path(SEMO_SOURCE_DIR) / "specs/examples" / name / (name + ".world.json")));
}

Point point(const json& p) { return {p.at(0).get<double>(), p.at(1).get<double>()}; }

struct ModeChange {
  double t = 0;
  std::string robot, mode;
};

// One run's trace, read back.
class Trace {
 public:
  explicit Trace(json j) : j_(std::move(j)) {
    for (const json& r : j_["robots"]) names_.push_back(r["name"].get<std::string>());
    for (const json& e : j_["events"]) {
      // The mode changes: not the mode each robot starts in.
      if (e["kind"] == "mode" && e.value("label", "").rfind("starts in ", 0) != 0) modes_.push_back({e["t"].get<double>(), e["robot"].get<std::string>(), e["detail"].get<std::string>()});
      if (e["kind"] == "crash") crashes_[e["robot"].get<std::string>()] = e["t"].get<double>();
    }
  }
  const json& operator[](const char* key) const { return j_[key]; }
  const json& summary() const { return j_["summary"]; }
  const std::vector<std::string>& robots() const { return names_; }
  const std::vector<ModeChange>& modes() const { return modes_; }
  std::vector<ModeChange> modes(const std::string& robot) const {
    std::vector<ModeChange> out;
    for (const ModeChange& m : modes_) {
      if (m.robot == robot) out.push_back(m);
    }
    return out;
  }
  bool alive(const std::string& robot, double t) const {
    auto it = crashes_.find(robot);
    return it == crashes_.end() || it->second > t;
  }
  double crashTime(const std::string& robot) const {
    auto it = crashes_.find(robot);
    return it == crashes_.end() ? -1 : it->second;
  }
  double end() const { return j_["poses"].back()["t"].get<double>(); }

  // The robot's position at `t`, between the pose samples (every 0.1 s) on a straight line.
  Point at(const std::string& robot, double t) const {
    const std::size_t i = index(robot);
    const json& poses = j_["poses"];
    std::size_t hi = 0;
    while (hi + 1 < poses.size() && poses[hi]["t"].get<double>() < t) ++hi;
    const json& b = poses[hi];
    const json& a = poses[hi == 0 ? 0 : hi - 1];
    const double ta = a["t"].get<double>(), tb = b["t"].get<double>();
    const double f = tb > ta ? std::clamp((t - ta) / (tb - ta), 0.0, 1.0) : 1.0;
    const Point pa = point(a["robots"][i]), pb = point(b["robots"][i]);
    return {pa.x + f * (pb.x - pa.x), pa.y + f * (pb.y - pa.y)};
  }
  // Every sampled position of the robot, in time order.
  std::vector<std::pair<double, Point>> path(const std::string& robot) const {
    const std::size_t i = index(robot);
    std::vector<std::pair<double, Point>> out;
    for (const json& s : j_["poses"]) out.emplace_back(s["t"].get<double>(), point(s["robots"][i]));
    return out;
  }
  // The events of one kind ("send", "fact", ...).
  std::vector<json> events(const std::string& kind) const {
    std::vector<json> out;
    for (const json& e : j_["events"]) {
      if (e["kind"] == kind) out.push_back(e);
    }
    return out;
  }

 private:
  json j_;
  std::vector<std::string> names_;
  std::vector<ModeChange> modes_;
  std::map<std::string, double> crashes_;

  std::size_t index(const std::string& robot) const {
    const auto it = std::find(names_.begin(), names_.end(), robot);
    if (it == names_.end()) throw std::runtime_error("no robot " + robot + " in the trace");
    return static_cast<std::size_t>(it - names_.begin());
  }
};

// Runs seeds 1..count of `name` with `options` and --check-conformance in one CLI run (the task
// graphs are analysed once), each writing its trace (--trace with {seed}); empty (and a failure)
// when the CLI fails.
std::vector<Trace> simulateSeeds(const std::string& name, const std::string& options, std::uint64_t count, const fs::path& dir) {
  CliRun r = verify("simulate " + example(name) + " --check-conformance --seeds 1.." + std::to_string(count) + " " + options + " --trace '" +
                        (dir / "seed{seed}.json").string() + "'",
                    dir);
  EXPECT_EQ(r.exit, 0) << r.out << r.err;
  std::vector<Trace> out;
  for (std::uint64_t seed = 1; r.exit == 0 && seed <= count; ++seed) {
    const fs::path file = dir / ("seed" + std::to_string(seed) + ".json");
    EXPECT_TRUE(fs::exists(file)) << file;
    if (!fs::exists(file)) return {};
    out.emplace_back(json::parse(slurp(file)));
  }
  return out;
}

// Every step was one the model allows, and the run kept within the model's assumptions.
void expectConforms(const Trace& t) {
  EXPECT_EQ(t.summary()["mismatches"].get<int>(), 0);
  EXPECT_TRUE(t.summary()["violations"].empty()) << t.summary()["violations"].dump();
  EXPECT_EQ(t.summary()["outsideAssumptions"].get<std::string>(), "");
  EXPECT_GT(t.summary()["stepsChecked"].get<int>(), 10);
}

bool isTeam(const std::string& robot, const std::string& prefix) { return robot.rfind(prefix, 0) == 0; }

// ---------------------------------------------------------------------------------------------
// Chase: the red Burgers pursue the nearest blue Ev3 and catch one after another (each catch ends
// pursue() and restarts PURSUE_MODE); the blues graze, and flee for 3 s each time their range to
// red (a schedule in the world: from 13.5 s, 30 s and 45 s, a second each) drops below 50 cm.

// The times the world's schedule puts red within 50 cm.
std::vector<double> redCloseTimes() {
  std::vector<double> out;
  const json world = worldOf("chase");
  for (const json& entry : world["values"]["BlueTeam.red_distance"]["schedule"]) {
    if (entry[1].get<double>() < 50) out.push_back(entry[0].get<double>());
  }
  return out;
}

// Each PURSUE_MODE re-entry of a red is a catch: a live blue within pursue's reach (0.35 m; the
// poses are sampled every 0.1 s, hence the margin). Pursuits of a blue that has just crashed end
// without one: `skip` says when. Returns the catches per red.
std::map<std::string, int> expectEveryPursuitEndsInACatch(const Trace& t, double from, const std::vector<double>& skip = {}) {
  std::map<std::string, int> catches;
  for (const ModeChange& m : t.modes()) {
    if (!isTeam(m.robot, "red") || m.t < from) continue;
    if (std::any_of(skip.begin(), skip.end(), [&](double s) { return m.t >= s && m.t <= s + 0.2; })) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (const std::string& b : t.robots()) {
      if (isTeam(b, "blue") && t.alive(b, m.t)) nearest = std::min(nearest, distance(t.at(m.robot, m.t), t.at(b, m.t)));
    }
    EXPECT_LE(nearest, 0.45) << m.robot << " ended a pursuit at " << m.t << " s with no blue within reach";
    ++catches[m.robot];
  }
  return catches;
}

// Each live blue flees once per close pass of red, for 3 s, and is calm again at the end.
void expectBlueFlights(const Trace& t, const std::string& blue) {
  SCOPED_TRACE(blue);
  const std::vector<double> close = redCloseTimes();
  ASSERT_EQ(close.size(), 3u);
  std::vector<ModeChange> m = t.modes(blue);
  ASSERT_EQ(m.size(), 2 * close.size()) << "FLEE then CALM per close pass";
  for (std::size_t i = 0; i < close.size(); ++i) {
    const ModeChange& flee = m[2 * i];
    const ModeChange& calm = m[2 * i + 1];
    EXPECT_EQ(flee.mode, "FLEE_MODE");
    // Lookout reads the range every 200 ms; a peer's alarm arrives within a few ms.
    EXPECT_GE(flee.t, close[i]);
    EXPECT_LE(flee.t, close[i] + 0.25);
    EXPECT_EQ(calm.mode, "CALM_MODE");
    EXPECT_NEAR(calm.t - flee.t, 3.0, 0.1) << "runAway flees for 3 s";
    EXPECT_GE(distance(t.at(blue, flee.t), t.at(blue, calm.t)), 0.2) << "it ran";
  }
}

TEST(SimulateChase, BluesFleeEachCloseCallAndRedsCatchThem) {
  const fs::path dir = workDir("chase_seeds");
  const std::vector<Trace> runs = simulateSeeds("chase", "--loss 0.6", 20, dir);
  ASSERT_EQ(runs.size(), 20u);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Trace* t = &runs[seed - 1];
    expectConforms(*t);
    EXPECT_FALSE(t->summary()["completed"].get<bool>()) << "the chase never ends";
    EXPECT_DOUBLE_EQ(t->end(), 60.0);
    for (const std::string& r : t->robots()) {
      if (isTeam(r, "blue")) expectBlueFlights(*t, r);
    }
    // The reds close in: over the first 13 s each gains at least 2 m on the nearest blue.
    for (const std::string& red : t->robots()) {
      if (!isTeam(red, "red")) continue;
      auto nearestBlue = [&](double when) {
        double best = std::numeric_limits<double>::infinity();
        for (const std::string& b : t->robots()) {
          if (isTeam(b, "blue")) best = std::min(best, distance(t->at(red, when), t->at(b, when)));
        }
        return best;
      };
      EXPECT_LE(nearestBlue(13.0), nearestBlue(0.0) - 2.0) << red;
    }
    const std::map<std::string, int> catches = expectEveryPursuitEndsInACatch(*t, 0);
    for (const char* red : {"red_0", "red_1", "red_2"}) {
      EXPECT_GE(catches.count(red) ? catches.at(red) : 0, 3) << red << " catches blues again and again";
    }
  }
}

// The mission assumes at most one crash in BlueTeam: a blue crashing mid-chase leaves the others
// fleeing as before, and the reds chasing only them.
TEST(SimulateChase, SurvivorsCarryOnAfterABlueCrashes) {
  const fs::path dir = workDir("chase_crash");
  const std::vector<Trace> runs = simulateSeeds("chase", "--loss 0.6 --crash blue_0@10s", 10, dir);
  ASSERT_EQ(runs.size(), 10u);
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Trace* t = &runs[seed - 1];
    expectConforms(*t);
    EXPECT_DOUBLE_EQ(t->crashTime("blue_0"), 10.0);
    EXPECT_TRUE(t->modes("blue_0").empty()) << "crashed before red came close";
    for (const auto& [when, p] : t->path("blue_0")) {
      if (when >= 10.0) {
        EXPECT_LT(distance(p, t->at("blue_0", 10.0)), 1e-6) << "a crashed robot does not move (t = " << when << ")";
      }
    }
    expectBlueFlights(*t, "blue_1");
    expectBlueFlights(*t, "blue_2");
    const std::map<std::string, int> catches = expectEveryPursuitEndsInACatch(*t, 10.0, {10.0});
    int after = 0;
    for (const auto& [red, n] : catches) after += n;
    EXPECT_GE(after, 6) << "the reds go on catching the two left";
  }
  // A red crash is beyond the assumptions (crashes only in BlueTeam): the run says so and claims
  // no conformance from there.
  CliRun red = verify("simulate " + example("chase") + " --check-conformance --crash red_0@5s", dir);
  EXPECT_EQ(red.exit, 0) << red.out << red.err;
  EXPECT_TRUE(std::regex_search(red.out, std::regex("outside the model's assumptions: at 5[.0]* s red_0 crashed, beyond the model's assumption of at "
                                                    "most 0 crash\\(es\\) in RedTeam")))
      << red.out;
}

// ---------------------------------------------------------------------------------------------
// Deployment: six robots spread out from a ring; each claims the nearest free sector (a fact site)
// and stays there; the claims spread by broadcast (lossy: `assume loss knowledge`), and once every
// robot knows all four claimed, all hold (the world's goal). Crashes: at most two.

struct Sector {
  std::string name;
  Point at;
  double radius = 0;
};

std::vector<Sector> sectors() {
  std::vector<Sector> out;
  const json world = worldOf("deployment");
  for (const json& f : world["facts"]) out.push_back({f["fact"].get<std::string>(), point(f["at"]), f["radius"].get<double>()});
  return out;
}

// At the end of the run every sector has a live robot of its own on it (within its radius and a
// little), and each sector's first claimant, if it is alive, is that robot: it stayed.
void expectEverySectorHeld(const Trace& t) {
  std::map<std::string, std::string> claimant;  // sector -> first robot to find it
  for (const json& f : t.events("fact")) {
    const std::string label = f["label"].get<std::string>();
    if (label.rfind("finds sectors: ", 0) != 0) continue;
    claimant.emplace(label.substr(15), f["robot"].get<std::string>());
  }
  std::set<std::string> holders;
  for (const Sector& s : sectors()) {
    SCOPED_TRACE(s.name);
    ASSERT_TRUE(claimant.count(s.name)) << "nobody claimed it";
    std::string holder;
    double best = std::numeric_limits<double>::infinity();
    for (const std::string& r : t.robots()) {
      const double d = distance(t.at(r, t.end()), s.at);
      if (t.alive(r, t.end()) && d < best) best = d, holder = r;
    }
    EXPECT_LE(best, s.radius + 0.05) << "no live robot on it at the end";
    if (t.alive(claimant[s.name], t.end())) {
      EXPECT_EQ(holder, claimant[s.name]) << "its claimant left it";
    }
    holders.insert(holder);
  }
  EXPECT_EQ(holders.size(), sectors().size()) << "one robot per sector";
}

TEST(SimulateDeployment, EverySectorClaimedAndHeldThenTheTeamHolds) {
  const fs::path dir = workDir("deployment_seeds");
  // Going on 13 s after the goal: HOLD_MODE is final (stays_deployed) and nobody moves.
  const std::vector<Trace> runs = simulateSeeds("deployment", "--loss 0.5 --keep-running --duration 20s", 20, dir);
  ASSERT_EQ(runs.size(), 20u);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Trace* t = &runs[seed - 1];
    expectConforms(*t);
    ASSERT_TRUE(t->summary()["completed"].get<bool>());
    const double done = t->summary()["completedAt"].get<double>();
    EXPECT_LE(done, 10.0);
    const json& converged = t->summary()["convergedAt"].at(0);
    EXPECT_EQ(converged["knowledge"], "sectors");
    ASSERT_TRUE(converged["t"].is_number()) << "every robot ends up knowing every claim";
    EXPECT_LE(converged["t"].get<double>(), done);
    for (const std::string& r : t->robots()) {
      const std::vector<ModeChange> m = t->modes(r);
      ASSERT_EQ(m.size(), 1u) << r << ": DEPLOY_MODE, then HOLD_MODE for good";
      EXPECT_EQ(m[0].mode, "HOLD_MODE");
      EXPECT_LE(m[0].t, done);
      EXPECT_LT(distance(t->at(r, done + 1.0), t->at(r, t->end())), 0.01) << r << " holds its position";
    }
    expectEverySectorHeld(*t);
  }
}

// Two crashes (the assumed most), of the robots that head for the north and south sectors, before
// they claim them: two of the others take those sectors over, and the goal is still reached.
TEST(SimulateDeployment, TwoCrashedRobotsSectorsAreTakenOver) {
  const fs::path dir = workDir("deployment_crash");
  const std::vector<Trace> runs = simulateSeeds("deployment", "--loss 0.3 --crash burger_0@2s --crash ev3_0@2s", 10, dir);
  ASSERT_EQ(runs.size(), 10u);
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Trace* t = &runs[seed - 1];
    expectConforms(*t);
    ASSERT_TRUE(t->summary()["completed"].get<bool>()) << "every live robot holds, with all four sectors claimed";
    EXPECT_LE(t->summary()["completedAt"].get<double>(), 45.0);
    for (const json& f : t->events("fact")) {
      const std::string who = f["robot"].get<std::string>();
      EXPECT_TRUE(who != "burger_0" && who != "ev3_0") << who << " found something after crashing";
    }
    expectEverySectorHeld(*t);
  }
  // A third crash is beyond the assumptions, and the summary says so.
  CliRun third = verify("simulate " + example("deployment") + " --check-conformance --crash burger_0@2s --crash ev3_0@2s --crash burger_1@2s", dir);
  EXPECT_EQ(third.exit, 0) << third.out << third.err;
  EXPECT_NE(third.out.find("beyond the model's assumption of at most 2 crash(es) in Field"), std::string::npos) << third.out;
}

// ---------------------------------------------------------------------------------------------
// Patrol: the guards go round the four aisles of the warehouse in the world's order, for ever;
// passing a bay where a target roams, one detects it (laser range within 1.2 m of the bay's middle,
// bumper within 1 m: regions of the world) and the guards scatter, then resume the round.

struct Circle {
  Point at;
  double radius = 0;
};

struct Warehouse {
  std::vector<Point> aisles;                    // in the world's order: the round
  std::vector<Circle> laser, bumper;            // where Guards.target_range < 100, Guards.bumped
  Point shelvesLow, shelvesHigh;                // the shelves' bounding box (a rectangle)
  Point arenaLow, arenaHigh;
};

Warehouse warehouse() {
  const json w = worldOf("patrol");
  Warehouse h;
  for (const json& f : w["facts"]) h.aisles.push_back(point(f["at"]));
  for (const json& r : w["values"]["Guards.target_range"]["regions"]) {
    if (r["value"].get<double>() < 100) h.laser.push_back({point(r["circle"]["at"]), r["circle"]["radius"].get<double>()});
  }
  for (const json& r : w["values"]["Guards.bumped"]["regions"]) {
    if (r["value"].get<bool>()) h.bumper.push_back({point(r["circle"]["at"]), r["circle"]["radius"].get<double>()});
  }
  h.shelvesLow = {1e9, 1e9}, h.shelvesHigh = {-1e9, -1e9};
  for (const json& p : w["obstacles"].at(0)["polygon"]) {
    const Point q = point(p);
    h.shelvesLow = {std::min(h.shelvesLow.x, q.x), std::min(h.shelvesLow.y, q.y)};
    h.shelvesHigh = {std::max(h.shelvesHigh.x, q.x), std::max(h.shelvesHigh.y, q.y)};
  }
  h.arenaLow = point(w["arena"]["from"]), h.arenaHigh = point(w["arena"]["to"]);
  return h;
}

bool inside(const std::vector<Circle>& regions, Point p, double margin) {
  return std::any_of(regions.begin(), regions.end(), [&](const Circle& c) { return distance(p, c.at) <= c.radius + margin; });
}

// The aisles a guard passed (within 0.35 m of the marker), in order, a pass of the aisle it passed
// last not counted again.
std::vector<std::size_t> aislesPassed(const Trace& t, const std::string& guard, const Warehouse& h) {
  std::vector<std::size_t> out;
  for (const auto& [when, p] : t.path(guard)) {
    for (std::size_t a = 0; a < h.aisles.size(); ++a) {
      if (distance(p, h.aisles[a]) < 0.35 && (out.empty() || out.back() != a)) out.push_back(a);
    }
  }
  return out;
}

// The guard goes round: each aisle it passes is the next of the round after the one before, and it
// comes back to where it began after passing the other three.
void expectRounds(const Trace& t, const std::string& guard, const Warehouse& h) {
  SCOPED_TRACE(guard);
  const std::vector<std::size_t> passed = aislesPassed(t, guard, h);
  ASSERT_GE(passed.size(), h.aisles.size() + 1) << "a whole round and back to its first aisle";
  for (std::size_t i = 1; i < passed.size(); ++i) {
    EXPECT_EQ(passed[i], (passed[i - 1] + 1) % h.aisles.size()) << "pass " << i << ": aisles go in the world's order";
  }
}

// Every SCATTER_MODE is followed by PATROL_MODE within 6 s (scatter drives 1 m and stops), unless
// the run ends first; returns how many times the guard scattered from `from` on.
int expectScatterAndResume(const Trace& t, const std::string& guard, double from = 0) {
  SCOPED_TRACE(guard);
  const std::vector<ModeChange> m = t.modes(guard);
  int scattered = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (m[i].mode != "SCATTER_MODE") continue;
    if (m[i].t >= from) ++scattered;
    if (i + 1 < m.size()) {
      EXPECT_EQ(m[i + 1].mode, "PATROL_MODE");
      EXPECT_LE(m[i + 1].t - m[i].t, 6.0) << "scattered at " << m[i].t << " s";
    } else {
      EXPECT_GE(m[i].t, t.end() - 6.0) << "still scattering at the end, since " << m[i].t << " s";
    }
  }
  return scattered;
}

TEST(SimulatePatrol, GuardsGoRoundDetectScatterAndResume) {
  const fs::path dir = workDir("patrol_seeds");
  const Warehouse h = warehouse();
  const std::vector<std::string> guards = {"guard_0", "guard_1", "guard_2", "rover"};
  // A Burger's round takes about 140 s at its 0.22 m/s: 300 s shows it repeat.
  const std::vector<Trace> runs = simulateSeeds("patrol", "--loss 0.3 --duration 300s", 8, dir);
  ASSERT_EQ(runs.size(), 8u);
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Trace* t = &runs[seed - 1];
    expectConforms(*t);
    EXPECT_GT(t->summary()["messagesLost"].get<int>(), 0) << "the loss does happen";
    ASSERT_TRUE(t->summary()["convergedAt"].at(0)["t"].is_number()) << "the guards share the aisles' visits";
    for (const std::string& g : guards) {
      expectRounds(*t, g, h);
      EXPECT_GE(expectScatterAndResume(*t, g), 3) << g;
    }
    // Each detection (a guard throwing target_found) happens where its sensor can see a target.
    int detections = 0;
    for (const json& e : t->events("send")) {
      if (e.value("detail", "") != "target_found") continue;
      ++detections;
      const std::string who = e["robot"].get<std::string>();
      const double when = e["t"].get<double>();
      EXPECT_TRUE(inside(who == "rover" ? h.bumper : h.laser, t->at(who, when), 0.05)) << who << " detected a target at " << when << " s out of range";
    }
    EXPECT_GE(detections, 4);
    // The shared knowledge, fact by fact: a robot finds a fact it lacks, and learns from a peer
    // only facts it lacks and the peer holds (the trace names them).
    std::map<std::string, std::set<std::string>> held;
    int learnt = 0;
    for (const json& e : t->events("fact")) {
      const std::string who = e["robot"].get<std::string>(), label = e["label"].get<std::string>();
      static const std::regex finds("finds visited: (aisle[0-9]+)"), learns("learns visited from ([a-z_0-9]+): (.+)");
      std::smatch m;
      if (std::regex_match(label, m, finds)) {
        EXPECT_TRUE(held[who].insert(m[1]).second) << who << " finds " << m[1] << " again";
      } else if (std::regex_match(label, m, learns)) {
        const std::string peer = m[1], list = m[2];
        for (std::size_t at = 0; at <= list.size();) {
          const std::size_t end = std::min(list.find(", ", at), list.size());
          const std::string fact = list.substr(at, end - at);
          EXPECT_EQ(held[peer].count(fact), 1u) << who << " learns " << fact << " from " << peer << ", who does not hold it";
          EXPECT_TRUE(held[who].insert(fact).second) << who << " learns " << fact << ", which it held";
          ++learnt;
          at = end + 2;
        }
      } else {
        ADD_FAILURE() << "a fact event that names no fact: " << label;
      }
    }
    EXPECT_GE(learnt, 3) << "the guards learn each other's visits";
    for (const std::string& r : t->robots()) {
      for (const auto& [when, p] : t->path(r)) {
        const bool inShelves = p.x > h.shelvesLow.x - 0.15 && p.x < h.shelvesHigh.x + 0.15 && p.y > h.shelvesLow.y - 0.15 &&
                               p.y < h.shelvesHigh.y + 0.15;
        EXPECT_FALSE(inShelves) << r << " drove into the shelves at " << when << " s";
        EXPECT_TRUE(p.x > h.arenaLow.x && p.x < h.arenaHigh.x && p.y > h.arenaLow.y && p.y < h.arenaHigh.y) << r << " left the warehouse";
        if (isTeam(r, "target")) {
          EXPECT_TRUE(inside(h.laser, p, 0)) << r << " roams out of its bay at " << when << " s: the guards could not see it";
        }
      }
      if (isTeam(r, "target")) {
        EXPECT_TRUE(t->modes(r).empty()) << r << " roams throughout";
      }
    }
  }
  // The same over 20 seeds at the default 60 s, from the statistics the CLI prints.
  CliRun stats = verify("simulate " + example("patrol") + " --check-conformance --loss 0.3 --seeds 1..20", dir);
  EXPECT_EQ(stats.exit, 0) << stats.out << stats.err;
  EXPECT_NE(stats.out.find("conformance: 0 runs with a mismatch"), std::string::npos) << stats.out;
  EXPECT_NE(stats.out.find("; 0 runs where a robot reached one"), std::string::npos) << stats.out;
}

// At most one guard crashes: the others go on with the round, scattering and resuming. The rover is
// the only guard in the Lookout block's `others` arm (the bumper): its crash empties that arm.
TEST(SimulatePatrol, SurvivorsCarryOnAfterAGuardCrashes) {
  const fs::path dir = workDir("patrol_crash");
  const Warehouse h = warehouse();
  const std::vector<std::string> guards = {"guard_0", "guard_1", "guard_2", "rover"};
  for (const std::string crashed : {"guard_0", "rover"}) {
    const std::vector<Trace> runs = simulateSeeds("patrol", "--loss 0.3 --duration 300s --crash " + crashed + "@20s", 3, dir);
    ASSERT_EQ(runs.size(), 3u);
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      SCOPED_TRACE(crashed + ", seed " + std::to_string(seed));
      const Trace* t = &runs[seed - 1];
      expectConforms(*t);
      EXPECT_DOUBLE_EQ(t->crashTime(crashed), 20.0);
      for (const ModeChange& m : t->modes(crashed)) EXPECT_LE(m.t, 20.0) << "a crashed robot changes no mode";
      for (const std::string& g : guards) {
        if (g == crashed) continue;
        expectRounds(*t, g, h);
        EXPECT_GE(expectScatterAndResume(*t, g, 20.0), 2) << g << " scatters and resumes after the crash";
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The same seed gives the same trace, byte for byte, with loss and a crash injected; another seed
// draws other latencies and losses.
TEST(SimulateExamplesDeterminism, PatrolSameSeedSameTraceBytes) {
  const fs::path dir = workDir("patrol_determinism");
  const std::string base = "simulate " + example("patrol") + " --check-conformance --loss 0.3 --crash rover@20s ";
  for (const char* name : {"a", "b"}) {
    CliRun r = verify(base + "--seed 4 --trace '" + (dir / name).string() + ".json'", dir);
    ASSERT_EQ(r.exit, 0) << r.out << r.err;
  }
  CliRun c = verify(base + "--seed 5 --trace '" + (dir / "c").string() + ".json'", dir);
  ASSERT_EQ(c.exit, 0) << c.out << c.err;
  const std::string a = slurp(dir / "a.json");
  EXPECT_GT(a.size(), 100000u);
  EXPECT_EQ(a, slurp(dir / "b.json"));
  EXPECT_NE(a, slurp(dir / "c.json"));
}

}  // namespace
