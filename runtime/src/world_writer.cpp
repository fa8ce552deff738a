// A starting world for a mission (world.hpp, writeStartingWorld): built from the tables the
// simulator checks a world against, so that it gives everything the check asks for; laid out so
// that a first run moves (robots facing open floor, fact sites on their way, places apart from
// them); written by hand rather than through a JSON library, so that a point stays on one line and
// every entry keeps the mission's order, with the notes next to what they are about.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "semo/runtime/tables.hpp"
#include "semo/runtime/world.hpp"
#include "text_output.hpp"

// A namespace of its own: in a unity build this file shares its translation unit with the
// simulator's, whose helpers have short names too.
namespace semo::runtime::starting_world {
namespace {

// Metres. The simulator moves a legged robot as a unicycle without a size: it gets the size of a
// small quadruped's body with its legs.
constexpr double kLeggedFootprint = 0.3;
constexpr double kSmallestFootprint = 0.1;
constexpr double kFactAhead = 1.0;    // a fact site lies this far ahead of the robots of its lane
constexpr double kFactRadius = 0.3;   // WORLD.md's default, written out so that it can be seen and edited
constexpr double kPlaceGap = 1.5;     // from the farthest fact site to the places
constexpr double kPlaceSpacing = 1.0; // between two places, at least
constexpr double kMargin = 1.0;       // around everything, to the arena's edge

// The width a robot takes on the floor, from the geometry the simulator drives it with: a wheeled
// robot's wheel separation plus a wheel's diameter (its wheels and what lies between them).
double footprint(const RobotTable& r) {
  if (!r.geometry.wheeled) return kLeggedFootprint;
  return std::max(r.geometry.wheelSeparation + 2 * r.geometry.wheelRadius, kSmallestFootprint);
}

// Between two neighbours' centres: half of each body, and a clearance as wide as the wider body.
double spacing(double a, double b) { return (a + b) / 2 + std::max(a, b); }

// Millimetres are as fine as a world needs, and rounding to them keeps the text the same where two
// machines' sines differ in the last bit.
double mm(double x) { return std::round(x * 1000) / 1000; }

// A number with at most `decimals` decimals and no trailing zeros ("1.2", "0", "-3.05").
std::string num(double x, int decimals = 3) {
  std::string s = detail::fixed(x, decimals);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s == "-0" ? "0" : s;
}

std::string point(Vec2 p) { return "[" + num(p.x) + ", " + num(p.y) + "]"; }

std::string jsonQuoted(std::string_view s) { return detail::jsonString(s); }

std::string joined(const std::vector<std::string>& items, std::string_view separator = ", ") {
  std::string out;
  for (const std::string& i : items) out += (out.empty() ? "" : std::string(separator)) + i;
  return out;
}

// A fact site, before the layout is moved into the arena.
struct Site {
  std::string knowledge, fact;
  Vec2 at;
};

struct Layout {
  std::vector<Vec2> robots;          // per robot of the tables
  std::vector<double> headings;      // radians
  std::vector<Site> facts;
  std::vector<Vec2> places;          // per place name, in order
  std::vector<double> sizes;         // per robot: its footprint
  std::string robotsNote;            // how they stand
};

// A lane leads from a robot (the ring) or a file of the grid straight out over open floor: a
// behaviour that goes straight ahead (marchInLine) meets the fact sites on its lane.
struct Lane {
  Vec2 from;
  double heading = 0;
};

// Where each fact of each knowledge item goes: on the lanes of its team's robots, spread evenly
// over them while there are fewer facts than lanes, else one after another further out. A lane
// position two teams would share moves one step further out.
void placeFacts(const MissionTables& t, const std::vector<std::vector<std::size_t>>& teamLanes, const std::vector<Lane>& lanes,
                Layout& out) {
  std::set<std::pair<std::size_t, std::size_t>> taken;  // (lane, depth)
  for (Id team = 0; team < t.teams.size(); ++team) {
    std::vector<std::pair<std::string, std::string>> facts;
    for (const KnowledgeTable& k : t.knowledge) {
      if (k.team != team) continue;
      for (const std::string& f : k.facts) facts.emplace_back(k.name, f);
    }
    const std::vector<std::size_t>& mine = teamLanes[team];
    if (facts.empty() || mine.empty()) continue;
    const std::size_t n = mine.size(), total = facts.size();
    for (std::size_t g = 0; g < total; ++g) {
      const std::size_t lane = total <= n ? mine[g * n / total] : mine[g % n];
      std::size_t depth = total <= n ? 0 : g / n;
      while (!taken.insert({lane, depth}).second) ++depth;
      const Lane& l = lanes[lane];
      const double d = kFactAhead * static_cast<double>(depth + 1);
      out.facts.push_back({facts[g].first, facts[g].second, {l.from.x + d * std::cos(l.heading), l.from.y + d * std::sin(l.heading)}});
    }
  }
}

// Every robot on one circle, facing out, neighbours spaced by their footprints; the teams follow
// one another round it in the mission's order. The places lie on a wider circle beyond the facts.
Layout ring(const MissionTables& t, std::size_t placeCount) {
  Layout out;
  const std::size_t n = t.robots.size();
  for (const RobotTable& r : t.robots) out.sizes.push_back(footprint(r));
  std::vector<double> gaps(n, 0);  // from robot i to the next round the circle
  double circumference = 0;
  for (std::size_t i = 0; i < n; ++i) circumference += gaps[i] = spacing(out.sizes[i], out.sizes[(i + 1) % n]);
  // The chord between two neighbours, not the arc, must be as long as their spacing.
  double radius = 0;
  if (n > 1) {
    for (const double g : gaps) radius = std::max(radius, g / (2 * std::sin(std::numbers::pi * g / circumference)));
  }
  double along = 0;
  std::vector<Lane> lanes;
  for (std::size_t i = 0; i < n; ++i) {
    const double angle = n > 1 ? 2 * std::numbers::pi * along / circumference : 0;
    along += gaps[i];
    out.robots.push_back({radius * std::cos(angle), radius * std::sin(angle)});
    out.headings.push_back(angle);
    lanes.push_back({out.robots.back(), angle});
  }
  std::vector<std::vector<std::size_t>> teamLanes(t.teams.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (t.robots[i].team < teamLanes.size()) teamLanes[t.robots[i].team].push_back(i);
  }
  placeFacts(t, teamLanes, lanes, out);
  double farthest = radius;
  for (const Site& s : out.facts) farthest = std::max(farthest, std::hypot(s.at.x, s.at.y));
  const double placeRadius =
      std::max(farthest + kPlaceGap, static_cast<double>(placeCount) * kPlaceSpacing / (2 * std::numbers::pi));
  for (std::size_t p = 0; p < placeCount; ++p) {
    // Half a step round from the robots' first lane, so that no place sits on it.
    const double angle = 2 * std::numbers::pi * (static_cast<double>(p) + 0.5) / static_cast<double>(placeCount);
    out.places.push_back({placeRadius * std::cos(angle), placeRadius * std::sin(angle)});
  }
  std::string spaced;
  if (n > 1) {
    const auto [closest, widest] = std::minmax_element(gaps.begin(), gaps.end());
    spaced = num(*closest, 2) == num(*widest, 2) ? num(*closest, 2) + " m" : num(*closest, 2) + " to " + num(*widest, 2) + " m";
  }
  out.robotsNote = n > 1 ? fmt::format("In a ring of radius {} m, facing out, their centres {} apart round it", num(radius, 2), spaced)
                         : "One robot, facing +x";
  return out;
}

// Ranks abreast, facing +x: files across (y), ranks one behind another (x), every robot a grid
// step from the next, the step of the widest robot. Fact sites lie ahead of the front rank, on the
// files of their team's robots; the places in a column behind the last rank.
Layout grid(const MissionTables& t, std::size_t placeCount) {
  Layout out;
  const std::size_t n = t.robots.size();
  double widest = 0;
  for (const RobotTable& r : t.robots) {
    out.sizes.push_back(footprint(r));
    widest = std::max(widest, out.sizes.back());
  }
  const double step = spacing(widest, widest);
  const auto files = static_cast<std::size_t>(std::max(1.0, std::ceil(std::sqrt(static_cast<double>(n)))));
  const std::size_t ranks = n == 0 ? 0 : (n + files - 1) / files;
  const double front = ranks > 0 ? static_cast<double>(ranks - 1) * step : 0;
  auto fileY = [&](std::size_t file) { return static_cast<double>(files - 1 - file) * step; };
  for (std::size_t i = 0; i < n; ++i) {
    out.robots.push_back({front - static_cast<double>(i / files) * step, fileY(i % files)});
    out.headings.push_back(0);
  }
  std::vector<Lane> lanes;
  for (std::size_t f = 0; f < files; ++f) lanes.push_back({{front, fileY(f)}, 0});
  std::vector<std::vector<std::size_t>> teamLanes(t.teams.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (t.robots[i].team >= teamLanes.size()) continue;
    std::vector<std::size_t>& mine = teamLanes[t.robots[i].team];
    if (std::find(mine.begin(), mine.end(), i % files) == mine.end()) mine.push_back(i % files);
  }
  for (std::vector<std::size_t>& mine : teamLanes) std::sort(mine.begin(), mine.end());
  placeFacts(t, teamLanes, lanes, out);
  const double middle = n > 0 ? fileY(0) / 2 : 0;
  for (std::size_t p = 0; p < placeCount; ++p) {
    const double offset = (static_cast<double>(p) - static_cast<double>(placeCount - 1) / 2) * std::max(kPlaceSpacing, step);
    out.places.push_back({-kPlaceGap - kFactAhead, middle + offset});
  }
  out.robotsNote = fmt::format("In a grid of {} files by {} ranks, facing +x, their centres {} m apart", files, ranks, num(step, 2));
  return out;
}

// The places the mission names: the first argument of a call when it is a string, in the order of
// the calls. A team's name is no place (pursue("BlueTeam") chases that team), except for move and
// walk, which the simulator always drives to a place.
std::vector<const CallTable*> placeCalls(const MissionTables& t, std::vector<std::string>& names) {
  std::vector<const CallTable*> firstCall;
  for (const CallTable& call : t.calls) {
    if (call.args.empty() || call.args.front().kind != Operand::Kind::Symbol) continue;
    const std::string& name = call.args.front().text;
    const bool drives = call.service == "move" || call.service == "walk";
    const bool team = std::any_of(t.teams.begin(), t.teams.end(), [&](const TeamTable& tt) { return tt.name == name; });
    if (!drives && (team || name == "true" || name == "false")) continue;
    if (std::find(names.begin(), names.end(), name) != names.end()) continue;
    names.push_back(name);
    firstCall.push_back(&call);
  }
  return firstCall;
}

// Why a world file cannot hold `name` as a member's key ("" when it can).
std::string unwritable(const std::string& name) {
  if (name.empty()) return "its name is empty";
  if (name.front() == '_') return "its name starts with '_' (a world file reads such a member as a note)";
  if (detail::validUtf8(name) != name) return "its name is not UTF-8 text";
  return {};
}

// The constant a sensed value starts with, and a note on its domain: what makes nothing happen
// where semo can tell (false; a number above every threshold, as a range to an obstacle far away
// reads), else the domain's first value.
std::pair<std::string, std::string> startingValue(const SensedValueTable& v, const StartingWorldOptions& options) {
  const bool team = options.teamSources.count(v.name) > 0;
  const std::string sources =
      team ? "one source for the whole team (source=\"team\"): a constant or a schedule"
           : "or a schedule over time, or by regions of the floor";
  switch (v.domain) {
    case SensedValueTable::Domain::Bool:
      return {"false", team ? "true or false; " + sources
                            : "true or false; or a sensor of the robot: at_destination, not_at_destination, touching_obstacle, obstacle_ahead"};
    case SensedValueTable::Domain::Threshold: {
      std::vector<std::string> ts;
      for (const double x : v.thresholds) ts.push_back(num(x, 6));
      if (v.thresholds.empty()) return {"0", "a number; " + sources};
      const double top = *std::max_element(v.thresholds.begin(), v.thresholds.end());
      return {num(top + std::max(1.0, std::abs(top)), 6), "a number; the mission compares it with " + joined(ts) + ", and this one is above them all; " + sources};
    }
    case SensedValueTable::Domain::Enum: {
      std::vector<std::string> symbols;
      for (const std::string& s : v.symbols) symbols.push_back(s);
      if (symbols.empty()) return {"\"none\"", sources};
      return {jsonQuoted(v.symbols.front()), "one of " + joined(symbols) + "; " + sources};
    }
    case SensedValueTable::Domain::Range: {
      const auto it = options.ranges.find(v.name);
      if (it == options.ranges.end()) return {"0", "a whole number; " + sources};
      return {num(it->second.first, 6), fmt::format("a whole number from {} to {}; {}", num(it->second.first, 6), num(it->second.second, 6), sources)};
    }
  }
  return {"0", sources};
}

}  // namespace
}  // namespace semo::runtime::starting_world

namespace semo::runtime {

std::string writeStartingWorld(const MissionTables& t, const StartingWorldOptions& options, std::vector<StartingWorldProblem>& problems) {
  using namespace starting_world;
  std::vector<std::string> placeNames;
  const std::vector<const CallTable*> placeOrigins = placeCalls(t, placeNames);
  const std::size_t before = problems.size();
  for (std::size_t p = 0; p < placeNames.size(); ++p) {
    if (std::string why = unwritable(placeNames[p]); !why.empty()) {
      problems.push_back({placeOrigins[p]->origin, placeOrigins[p]->service + "(" + jsonQuoted(placeNames[p]) +
                                                       "): no world file can hold this place, as " + why + "; name it otherwise"});
    }
  }
  for (const RobotTable& r : t.robots) {
    if (std::string why = unwritable(r.name); !why.empty()) {
      problems.push_back({"", "robot '" + r.name + "': no world file can hold its start, as " + why + "; rename it"});
    }
  }
  std::vector<bool> read(t.sensed.size(), false);  // as checkWorld marks them
  auto mark = [&](const Operand& o) {
    if (o.kind == Operand::Kind::Sensed && o.index < read.size()) read[o.index] = true;
  };
  for (const CondNode& c : t.conditions) mark(c.lhs), mark(c.rhs);
  for (const CallTable& call : t.calls) {
    for (const Operand& o : call.args) mark(o);
  }
  for (std::size_t s = 0; s < t.sensed.size(); ++s) {
    if (std::string why = unwritable(t.sensed[s].name); read[s] && !why.empty()) {
      problems.push_back({"", "sensed value '" + t.sensed[s].name + "': no world file can give it a source, as " + why});
    }
  }
  for (const KnowledgeTable& k : t.knowledge) {
    for (const std::string& f : k.facts) {
      if (detail::validUtf8(k.name) != k.name || detail::validUtf8(f) != f) {
        problems.push_back({"", "knowledge '" + detail::validUtf8(k.name) + "' or its fact '" + detail::validUtf8(f) + "' is not UTF-8 text: no world file can hold it"});
      }
    }
  }
  if (problems.size() > before) return {};

  const bool grid = options.layout == StartingWorldOptions::Layout::Grid;
  Layout lay = grid ? starting_world::grid(t, placeNames.size()) : ring(t, placeNames.size());
  // Everything moved so that the arena's lower-left corner is (0, 0), a margin from the nearest thing.
  double lowX = 0, lowY = 0, highX = 0, highY = 0;
  bool any = false;
  auto cover = [&](Vec2 p, double r) {
    if (!any) lowX = highX = p.x, lowY = highY = p.y, any = true;
    lowX = std::min(lowX, p.x - r), lowY = std::min(lowY, p.y - r), highX = std::max(highX, p.x + r), highY = std::max(highY, p.y + r);
  };
  for (std::size_t i = 0; i < lay.robots.size(); ++i) cover(lay.robots[i], lay.sizes[i] / 2);
  for (const Site& s : lay.facts) cover(s.at, kFactRadius);
  for (const Vec2& p : lay.places) cover(p, 0);
  const Vec2 shift{kMargin - lowX, kMargin - lowY};
  auto moved = [&](Vec2 p) { return Vec2{mm(p.x + shift.x), mm(p.y + shift.y)}; };
  // Up to the next half metre: a round figure to edit.
  const Vec2 top{std::ceil((highX - lowX + 2 * kMargin) * 2) / 2, std::ceil((highY - lowY + 2 * kMargin) * 2) / 2};

  std::string o = "{\n";
  auto member = [&](std::string_view key, const std::string& value, bool last = false) {
    o += "  " + jsonQuoted(key) + ": " + value + (last ? "\n" : ",\n");
  };
  member("_", jsonQuoted("A starting world for " + (options.mission.empty() ? std::string("the mission") : options.mission) +
                     ", written by semo-verify world: everything the simulator needs to run the mission, laid out without knowing "
                     "the real site. Edit it to stand for the site (runtime/WORLD.md); members whose names start with '_' are notes "
                     "the reader ignores."));
  member("format", "\"semo-world\"");
  member("version", "1");
  member("_arena", jsonQuoted("The floor around everything below, with a margin. It frames the pictures and keeps in the behaviours "
                          "that aim at points of their own (runAway, wander, scatter); it holds no robot back: walls are obstacles."));
  member("arena", "{\"from\": [0, 0], \"to\": " + point(top) + "}");

  member("_places", jsonQuoted(placeNames.empty()
                               ? "The mission names no place. Add one per place a call names, as \"name\": [x, y]."
                               : std::string(grid ? "In a column behind the robots" : "On a circle around the robots") +
                                     ", one per place the mission names (the first argument of a call, as a string): the simulator "
                                     "drives move and walk there; a service of your own reads the name. Put each where it is on the site."));
  std::string places = "{";
  for (std::size_t p = 0; p < placeNames.size(); ++p) places += (p == 0 ? "\n    " : ",\n    ") + jsonQuoted(placeNames[p]) + ": " + point(moved(lay.places[p]));
  member("places", places + (placeNames.empty() ? "}" : "\n  }"));

  member("_robots", jsonQuoted(lay.robotsNote + " (each robot's footprint from its URDF: its wheel separation plus a wheel's "
                                            "diameter, or 0.3 m for a legged robot; a clearance as wide as the wider of two "
                                            "neighbours between them). \"heading\": degrees, counter-clockwise from +x."));
  std::string robots = "{";
  for (std::size_t i = 0; i < t.robots.size(); ++i) {
    double degrees = lay.headings[i] * 180 / std::numbers::pi;
    if (degrees > 180) degrees -= 360;
    robots += (i == 0 ? "\n    " : ",\n    ") + jsonQuoted(t.robots[i].name) + ": {\"at\": " + point(moved(lay.robots[i])) +
              ", \"heading\": " + num(std::round(degrees * 100) / 100, 2) + "}";
  }
  member("robots", robots + (t.robots.empty() ? "}" : "\n  }"));

  member("_obstacles", jsonQuoted("None yet. Add walls, ditches and rocks: {\"name\": \"wall\", \"polygon\": [[x, y], ...]} or {\"name\": "
                              "\"rock\", \"circle\": {\"at\": [x, y], \"radius\": r}}."));
  member("obstacles", "[]");

  member("_facts", jsonQuoted(lay.facts.empty()
                              ? "The mission's group services share no knowledge, so there is nothing to find."
                              : fmt::format("One site per fact of each group service's knowledge, {} m ahead of {} of the team that "
                                            "shares it (further out when the team has more facts than {}): a robot working in the "
                                            "service finds the fact within \"radius\" of \"at\". Move each where it lies on the site.",
                                            num(kFactAhead), grid ? "the front rank, in a file of a robot" : "a robot",
                                            grid ? "files" : "robots")));
  std::string facts = "[";
  for (std::size_t f = 0; f < lay.facts.size(); ++f) {
    const Site& s = lay.facts[f];
    facts += (f == 0 ? "\n    " : ",\n    ") + std::string("{\"knowledge\": ") + jsonQuoted(s.knowledge) + ", \"fact\": " + jsonQuoted(s.fact) +
             ", \"at\": " + point(moved(s.at)) + ", \"radius\": " + num(kFactRadius) + "}";
  }
  member("facts", facts + (lay.facts.empty() ? "]" : "\n  ]"));

  const bool readsAny = std::find(read.begin(), read.end(), true) != read.end();
  member("_values", jsonQuoted(readsAny ? "A constant for each sensed value the mission reads: false, the first of its symbols, the lowest of "
                                      "its range, or a number above every threshold it is compared with. Give each the source it has on "
                                      "the site (the note beside it says what it may be)."
                                    : "The mission reads no sensed value."));
  std::string values = "{";
  bool first = true;
  for (std::size_t s = 0; s < t.sensed.size(); ++s) {
    if (!read[s]) continue;
    const auto [value, note] = startingValue(t.sensed[s], options);
    values += (first ? "\n    " : ",\n    ") + jsonQuoted(t.sensed[s].name) + ": {\"constant\": " + value + ", \"_\": " + jsonQuoted(note) + "}";
    first = false;
  }
  member("values", values + (first ? "}" : "\n  }"));

  std::vector<std::string> modes;
  for (const TeamTable& team : t.teams) {
    std::vector<std::string> names;
    for (const ModeTable& m : team.modes) names.push_back(m.name);
    modes.push_back(team.name + " (" + joined(names) + ")");
  }
  member("_goal", jsonQuoted("No goal: a run ends at --duration, or once every live robot has finished its plans. To end it when a team "
                         "reaches a mode, add \"goal\": [{\"team\": T, \"mode\": M, \"done\": [plans]}]. The teams and their modes: " +
                         joined(modes, "; ") + "."),
         true);
  return o + "}\n";
}

}  // namespace semo::runtime
