#pragma once
// The simulated world a mission runs in (specs/runtime.md, "The world file"): the places the
// mission names, where the robots start, obstacles, where the facts of group services' knowledge
// can be found, and where every sensed value comes from (a constant, a schedule over time, regions
// of the floor, or one of the simulated task library's sensors). Read from a JSON file
// ("semo-world", version 1); every error carries the file, line and column of the value at fault.
#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace semo::runtime {

struct Vec2 {
  double x = 0, y = 0;
};

// Where an entry was written in the world file (1-based; 0 when built in code).
struct TextPosition {
  std::size_t line = 0, column = 0;
};

// A circle or a convex or concave simple polygon, in metres.
struct Shape {
  enum class Kind { Circle, Polygon };
  Kind kind = Kind::Circle;
  Vec2 center;
  double radius = 0;
  std::vector<Vec2> points;  // Polygon, in order
  [[nodiscard]] bool contains(Vec2 p) const;
  // Distance from p to the shape (0 inside).
  [[nodiscard]] double distance(Vec2 p) const;
};

struct Place {
  std::string name;  // as the mission writes it: move("base camp")
  Vec2 at;
  TextPosition written;
};

struct StartPose {
  std::string robot;
  Vec2 at;
  double heading = 0;  // radians (the file gives degrees)
  TextPosition written;
};

struct Obstacle {
  std::string name;
  Shape shape;
  TextPosition written;
};

// A fact of a group service's knowledge item, found by a robot working in that service when it
// comes within `radius` of `at` (a coloured paper on the floor, an obstacle ahead).
struct FactSite {
  std::string knowledge, fact;
  Vec2 at;
  double radius = 0.3;
  TextPosition written;
};

// A value of a sensed value's domain: a number (threshold and range domains), or a symbol (enum
// domains; bool domains use the symbols "true" and "false").
struct SensedValue {
  bool isNumber = false;
  double number = 0;
  std::string symbol;
};

// Where a sensed value ("Team.var") comes from.
struct ValueSource {
  enum class Kind {
    Constant,  // schedule holds one entry at time 0
    Schedule,  // piecewise constant: each entry holds from its time (seconds) until the next
    Regions,   // by the robot's position: the first region containing it, else `otherwise`
    Sensor,    // a sensor of the simulated task library, by name (`sensor`, with `range`)
  };
  std::string name;
  Kind kind = Kind::Constant;
  std::vector<std::pair<double, SensedValue>> schedule;
  struct Region {
    Shape shape;
    SensedValue value;
  };
  std::vector<Region> regions;
  SensedValue otherwise;
  std::string sensor;  // "at_destination", "not_at_destination", "touching_obstacle", "obstacle_ahead"
  double range = 0.5;  // obstacle_ahead: metres
  TextPosition written;
};

// The mission is complete when every live robot of each named team is in `mode` with every plan in
// `plansDone` finished.
struct TeamGoal {
  std::string team, mode;
  std::vector<std::string> plansDone;
  TextPosition written;
};

struct World {
  std::string path;
  std::optional<std::pair<Vec2, Vec2>> arena;  // lower-left, upper-right corner (for pictures)
  std::vector<Place> places;
  std::vector<StartPose> starts;
  std::vector<Obstacle> obstacles;
  std::vector<FactSite> facts;
  std::vector<ValueSource> values;
  std::vector<TeamGoal> goal;

  [[nodiscard]] const Place* place(std::string_view name) const;
  [[nodiscard]] const StartPose* start(std::string_view robot) const;
  [[nodiscard]] const ValueSource* value(std::string_view name) const;
};

// A problem in a world file, at a position of the file.
struct WorldError {
  std::string file;
  std::size_t line = 0, column = 0;  // 1-based; 0 when the file could not be read at all
  std::string message;
  std::string lineText;  // the line, for the caret (of a long line, a window of it around the column)
  std::size_t caret = 0;  // the caret's column in lineText when it is a window (1-based); 0: `column`
};

// "file:line:col: error: message", then the line and a caret under the column.
std::string formatWorldError(const WorldError& e);

// Reads and checks a world file; nullopt (with every error found) when it is not a valid world.
std::optional<World> readWorld(const std::string& path, std::vector<WorldError>& errors);
std::optional<World> parseWorld(std::string_view text, const std::string& path, std::vector<WorldError>& errors);

struct MissionTables;  // tables.hpp

// A starting world for a mission (`semo-verify world`; runtime/WORLD.md, "Starting from `semo-verify
// world`"): what the simulator's check asks of a world (a start per robot, every place a call names,
// a source per sensed value read), and a site per fact of the group services' knowledge, laid out
// from the tables alone, with notes (members starting with '_') saying what to edit. The same tables
// give the same text, byte for byte.
struct StartingWorldOptions {
  enum class Layout { Ring, Grid };
  Layout layout = Layout::Ring;
  std::string mission;  // named in the file's first note
  // What the tables do not keep of the strategy's sensed values: a range domain's bounds (its
  // constant is the lower one) and the values read from one source for the whole team.
  std::map<std::string, std::pair<double, double>, std::less<>> ranges;
  std::set<std::string, std::less<>> teamSources;
};

// A name the world file cannot hold (empty, starting with '_', or not UTF-8): where the mission
// gives it ("file:line:col", or "" for a robot's name), and why.
struct StartingWorldProblem {
  std::string origin, message;
};

// The world file's text (JSON, "semo-world" version 1), or "" with `problems` when a name cannot be
// written.
std::string writeStartingWorld(const MissionTables& tables, const StartingWorldOptions& options,
                               std::vector<StartingWorldProblem>& problems);

}  // namespace semo::runtime
