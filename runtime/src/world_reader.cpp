// The world file reader (world.hpp; the format: runtime/WORLD.md). nlohmann::json parses the text;
// a scan of our own runs first, because the parser can neither bound the nesting depth nor say where
// a duplicate member or an overflowing number is. Every later check points at the value at fault
// through JsonPositions. The reader goes on after an error wherever the rest of the file still
// makes sense, so that one run reports every mistake; it never returns a World with an error.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <numbers>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "semo/runtime/json_positions.hpp"
#include "semo/runtime/world.hpp"
#include "world_scan.hpp"

namespace semo::runtime {

namespace {

using nlohmann::json;
using detail::errorAt;
using detail::isComment;
using detail::PreScan;
using detail::preScan;

constexpr const char* kSensors[] = {"at_destination", "not_at_destination", "touching_obstacle", "obstacle_ahead"};

std::string pointerKey(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
  return out;
}


class Reader {
 public:
  Reader(std::string_view text, const std::vector<std::size_t>& lineStarts, const std::string& path, std::vector<WorldError>& errors)
      : text_(text), lineStarts_(lineStarts), path_(path), errors_(errors), positions_(text) {}

  void read(const json& root) {
    if (!root.is_object()) return error("", "a world file is a JSON object");
    auto format = root.find("format");
    if (format == root.end() || *format != "semo-world") return error(format == root.end() ? "" : "/format", "\"format\" must be \"semo-world\"");
    auto version = root.find("version");
    if (version == root.end() || !version->is_number_integer() || *version != 1) {
      return error(version == root.end() ? "" : "/version", "unsupported world version (this semo reads \"version\": 1)");
    }
    // Checked only once the file says it is a world: another format's members are not worth listing.
    members(root, "", "the world", {"format", "version", "arena", "places", "robots", "obstacles", "facts", "values", "goal"});
    world_.path = path_;
    if (auto it = root.find("arena"); it != root.end()) arena(*it, "/arena");
    if (const json* o = object(root, "", "places")) {
      for (const auto& [name, v] : o->items()) {
        if (isComment(name)) continue;
        const std::string p = "/places/" + pointerKey(name);
        if (!named(name, p, "a place")) continue;
        if (auto at = vec2(v, p)) world_.places.push_back({name, *at, position(p)});
      }
    }
    if (const json* o = object(root, "", "robots")) {
      for (const auto& [name, v] : o->items()) {
        if (!isComment(name)) robot(name, v, "/robots/" + pointerKey(name));
      }
    }
    if (const json* a = array(root, "", "obstacles")) {
      std::set<std::string> names;
      for (std::size_t i = 0; i < a->size(); ++i) obstacle((*a)[i], "/obstacles/" + std::to_string(i), names);
    }
    if (const json* a = array(root, "", "facts")) {
      for (std::size_t i = 0; i < a->size(); ++i) fact((*a)[i], "/facts/" + std::to_string(i));
    }
    if (const json* o = object(root, "", "values")) {
      for (const auto& [name, v] : o->items()) {
        if (!isComment(name)) value(name, v, "/values/" + pointerKey(name));
      }
    }
    if (const json* a = array(root, "", "goal")) {
      for (std::size_t i = 0; i < a->size(); ++i) goal((*a)[i], "/goal/" + std::to_string(i));
    }
  }

  // nlohmann::json keeps an object's members sorted by key: put the named entries back in file order.
  World take() {
    auto byPosition = [](const auto& a, const auto& b) {
      return std::pair(a.written.line, a.written.column) < std::pair(b.written.line, b.written.column);
    };
    std::stable_sort(world_.places.begin(), world_.places.end(), byPosition);
    std::stable_sort(world_.starts.begin(), world_.starts.end(), byPosition);
    std::stable_sort(world_.values.begin(), world_.values.end(), byPosition);
    return std::move(world_);
  }

 private:
  std::string_view text_;
  const std::vector<std::size_t>& lineStarts_;
  const std::string& path_;
  std::vector<WorldError>& errors_;
  JsonPositions positions_;
  World world_;

  TextPosition position(const std::string& pointer) const {
    const WorldError e = errorAt(text_, lineStarts_, path_, positions_.offsetOf(pointer), "");
    return {e.line, e.column};
  }

  void error(const std::string& pointer, std::string message) {
    errors_.push_back(errorAt(text_, lineStarts_, path_, positions_.offsetOf(pointer), std::move(message)));
  }

  // Where the key of the member whose value starts at `pointer` is written: back from the value over
  // the colon to the key's closing quote, then to its opening quote (a quote after an odd number of
  // backslashes is part of the key).
  void errorAtKey(const std::string& pointer, std::string message) {
    std::size_t i = positions_.offsetOf(pointer);
    auto blank = [&](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ':'; };
    while (i > 0 && blank(text_[i - 1])) --i;
    if (i > 0 && text_[i - 1] == '"') {
      for (std::size_t j = i - 1; j > 0; --j) {
        if (text_[j - 1] != '"') continue;
        std::size_t slashes = 0;
        while (j - 1 > slashes && text_[j - 2 - slashes] == '\\') ++slashes;
        if (slashes % 2 == 0) {
          i = j - 1;
          break;
        }
      }
    }
    errors_.push_back(errorAt(text_, lineStarts_, path_, i, std::move(message)));
  }

  // Every member of `o` must be one of `allowed` (or a comment, "_...").
  void members(const json& o, const std::string& p, const char* what, std::initializer_list<const char*> allowed) {
    for (const auto& [key, v] : o.items()) {
      if (isComment(key)) continue;
      bool known = false;
      std::string list;
      for (const char* a : allowed) {
        known = known || key == a;
        list += (list.empty() ? "" : ", ") + std::string(a);
      }
      if (!known) errorAtKey(p + "/" + pointerKey(key), "unknown member '" + key + "' in " + what + " (expected " + list + ")");
    }
  }

  // An optional member that must be an object (or an array): nullptr when absent or wrong.
  const json* object(const json& o, const std::string& p, const char* key) {
    auto it = o.find(key);
    if (it == o.end()) return nullptr;
    if (it->is_object()) return &*it;
    error(p + "/" + key, std::string("\"") + key + "\" must be an object");
    return nullptr;
  }
  const json* array(const json& o, const std::string& p, const char* key) {
    auto it = o.find(key);
    if (it == o.end()) return nullptr;
    if (it->is_array()) return &*it;
    error(p + "/" + key, std::string("\"") + key + "\" must be an array");
    return nullptr;
  }

  bool named(const std::string& name, const std::string& p, const char* what) {
    if (!name.empty()) return true;
    errorAtKey(p, std::string(what) + " needs a non-empty name");
    return false;
  }

  std::optional<double> number(const json& v, const std::string& p, const std::string& what) {
    if (!v.is_number()) {
      error(p, what + " must be a number");
      return std::nullopt;
    }
    const double x = v.get<double>();
    if (!std::isfinite(x)) {
      error(p, what + " must be a finite number");
      return std::nullopt;
    }
    return x;
  }

  std::optional<double> positive(const json& v, const std::string& p, const std::string& what) {
    auto x = number(v, p, what);
    if (x && *x <= 0) {
      error(p, what + " must be greater than 0");
      return std::nullopt;
    }
    return x;
  }

  // A required string member; a non-empty one when `nonEmpty`.
  std::optional<std::string> text(const json& o, const std::string& p, const char* key, const char* what) {
    auto it = o.find(key);
    if (it == o.end()) {
      error(p, std::string(what) + " needs \"" + key + "\"");
      return std::nullopt;
    }
    if (!it->is_string() || it->get_ref<const std::string&>().empty()) {
      error(p + "/" + key, std::string("\"") + key + "\" must be a non-empty string");
      return std::nullopt;
    }
    return it->get<std::string>();
  }

  // A point, [x, y] in metres.
  std::optional<Vec2> vec2(const json& v, const std::string& p) {
    if (!v.is_array() || v.size() != 2) {
      error(p, "a point is [x, y] (two numbers, metres)");
      return std::nullopt;
    }
    auto x = number(v[0], p + "/0", "a coordinate");
    auto y = number(v[1], p + "/1", "a coordinate");
    if (!x || !y) return std::nullopt;
    return Vec2{*x, *y};
  }

  std::optional<Vec2> requiredPoint(const json& o, const std::string& p, const char* key, const char* what) {
    auto it = o.find(key);
    if (it == o.end()) {
      error(p, std::string(what) + " needs \"" + key + "\" (a point [x, y])");
      return std::nullopt;
    }
    return vec2(*it, p + "/" + key);
  }

  // The shape of an obstacle or a region: exactly one of "polygon" and "circle" in `o`.
  std::optional<Shape> shape(const json& o, const std::string& p, const char* what) {
    auto polygon = o.find("polygon"), circle = o.find("circle");
    if ((polygon == o.end()) == (circle == o.end())) {
      error(p, std::string(what) + " needs exactly one of \"polygon\" and \"circle\"");
      return std::nullopt;
    }
    Shape s;
    if (circle != o.end()) {
      const std::string cp = p + "/circle";
      if (!circle->is_object()) {
        error(cp, "a circle is {\"at\": [x, y], \"radius\": r}");
        return std::nullopt;
      }
      members(*circle, cp, "a circle", {"at", "radius"});
      s.kind = Shape::Kind::Circle;
      auto at = requiredPoint(*circle, cp, "at", "a circle");
      std::optional<double> r;
      if (auto it = circle->find("radius"); it != circle->end()) r = positive(*it, cp + "/radius", "a radius");
      else error(cp, "a circle needs \"radius\"");
      if (!at || !r) return std::nullopt;
      s.center = *at;
      s.radius = *r;
      return s;
    }
    const std::string pp = p + "/polygon";
    if (!polygon->is_array()) {
      error(pp, "a polygon is an array of points [[x, y], ...]");
      return std::nullopt;
    }
    s.kind = Shape::Kind::Polygon;
    bool ok = true;
    for (std::size_t i = 0; i < polygon->size(); ++i) {
      auto v = vec2((*polygon)[i], pp + "/" + std::to_string(i));
      ok = ok && v.has_value();
      if (v) s.points.push_back(*v);
    }
    if (!ok) return std::nullopt;
    if (s.points.size() < 3) {
      error(pp, "a polygon needs at least 3 points, not " + std::to_string(s.points.size()));
      return std::nullopt;
    }
    double area2 = 0;  // twice the signed area (shoelace): zero means every point is on one line
    for (std::size_t i = 0, n = s.points.size(); i < n; ++i) {
      const Vec2 a = s.points[i], b = s.points[(i + 1) % n];
      area2 += a.x * b.y - b.x * a.y;
    }
    if (area2 == 0) {
      error(pp, "a polygon's points must not all lie on one line");
      return std::nullopt;
    }
    return s;
  }

  void arena(const json& v, const std::string& p) {
    if (!v.is_object()) return error(p, "\"arena\" is {\"from\": [x, y], \"to\": [x, y]}");
    members(v, p, "the arena", {"from", "to"});
    auto from = requiredPoint(v, p, "from", "the arena");
    auto to = requiredPoint(v, p, "to", "the arena");
    if (!from || !to) return;
    if (from->x >= to->x || from->y >= to->y) return error(p + "/to", "the arena's \"to\" corner must be above and right of \"from\"");
    world_.arena = std::pair{*from, *to};
  }

  void robot(const std::string& name, const json& v, const std::string& p) {
    if (!named(name, p, "a robot")) return;
    if (!v.is_object()) return error(p, "a robot's start is {\"at\": [x, y], \"heading\": degrees}");
    members(v, p, "a robot's start", {"at", "heading"});
    StartPose s{name, {}, 0, position(p)};
    auto at = requiredPoint(v, p, "at", "a robot's start");
    std::optional<double> heading = 0.0;
    if (auto it = v.find("heading"); it != v.end()) heading = number(*it, p + "/heading", "a heading (degrees)");
    if (!at || !heading) return;
    s.at = *at;
    s.heading = *heading * std::numbers::pi / 180;
    world_.starts.push_back(std::move(s));
  }

  void obstacle(const json& v, const std::string& p, std::set<std::string>& names) {
    if (!v.is_object()) return error(p, "an obstacle is {\"name\": ..., \"polygon\" or \"circle\": ...}");
    members(v, p, "an obstacle", {"name", "polygon", "circle"});
    auto name = text(v, p, "name", "an obstacle");
    if (name && !names.insert(*name).second) error(p + "/name", "obstacle '" + *name + "' declared twice");
    auto s = shape(v, p, "an obstacle");
    if (name && s) world_.obstacles.push_back({*name, std::move(*s), position(p)});
  }

  void fact(const json& v, const std::string& p) {
    if (!v.is_object()) return error(p, "a fact site is {\"knowledge\": ..., \"fact\": ..., \"at\": [x, y]}");
    members(v, p, "a fact site", {"knowledge", "fact", "at", "radius"});
    auto knowledge = text(v, p, "knowledge", "a fact site");
    auto fact = text(v, p, "fact", "a fact site");
    auto at = requiredPoint(v, p, "at", "a fact site");
    std::optional<double> radius = 0.3;
    if (auto it = v.find("radius"); it != v.end()) radius = positive(*it, p + "/radius", "a radius");
    if (knowledge && fact && at && radius) world_.facts.push_back({*knowledge, *fact, *at, *radius, position(p)});
  }

  std::optional<SensedValue> sensed(const json& v, const std::string& p) {
    if (v.is_boolean()) return SensedValue{false, 0, v.get<bool>() ? "true" : "false"};
    if (v.is_string() && !v.get_ref<const std::string&>().empty()) return SensedValue{false, 0, v.get<std::string>()};
    if (v.is_number()) {
      auto x = number(v, p, "a value");
      if (!x) return std::nullopt;
      return SensedValue{true, *x, ""};
    }
    error(p, "a sensed value is a number, a non-empty string, true or false");
    return std::nullopt;
  }

  void value(const std::string& name, const json& v, const std::string& p) {
    const auto dot = name.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == name.size()) {
      return errorAtKey(p, "a sensed value is named 'Team.variable', not '" + name + "'");
    }
    if (!v.is_object()) return error(p, "a value source is an object with one of \"constant\", \"schedule\", \"regions\", \"sensor\"");
    ValueSource s;
    s.name = name;
    s.written = position(p);
    int kinds = 0;
    for (const char* k : {"constant", "schedule", "regions", "sensor"}) kinds += v.contains(k) ? 1 : 0;
    if (kinds != 1) return error(p, "a value source needs exactly one of \"constant\", \"schedule\", \"regions\", \"sensor\"");
    bool ok = true;
    if (v.contains("constant")) {
      members(v, p, "a constant value", {"constant"});
      s.kind = ValueSource::Kind::Constant;
      auto x = sensed(v["constant"], p + "/constant");
      ok = x.has_value();
      if (x) s.schedule.push_back({0.0, std::move(*x)});
    } else if (v.contains("schedule")) {
      members(v, p, "a scheduled value", {"schedule"});
      s.kind = ValueSource::Kind::Schedule;
      ok = schedule(v["schedule"], p + "/schedule", s);
    } else if (v.contains("regions")) {
      members(v, p, "a value by regions", {"regions", "otherwise"});
      s.kind = ValueSource::Kind::Regions;
      ok = regions(v, p, s);
    } else {
      members(v, p, "a sensor value", {"sensor", "range"});
      s.kind = ValueSource::Kind::Sensor;
      const json& sensor = v["sensor"];
      bool known = false;
      for (const char* k : kSensors) known = known || sensor == k;
      if (!known) {
        error(p + "/sensor", "unknown sensor " + sensor.dump() + " (the simulated sensors: at_destination, not_at_destination, touching_obstacle, obstacle_ahead)");
        ok = false;
      } else {
        s.sensor = sensor.get<std::string>();
      }
      if (auto it = v.find("range"); it != v.end()) {
        auto r = positive(*it, p + "/range", "a range (metres)");
        ok = ok && r.has_value();
        if (r) s.range = *r;
      }
    }
    if (ok) world_.values.push_back(std::move(s));
  }

  // [[time, value], ...]: times in seconds, the first 0, strictly increasing.
  bool schedule(const json& v, const std::string& p, ValueSource& s) {
    if (!v.is_array() || v.empty()) {
      error(p, "a schedule is a non-empty array of [time, value] pairs");
      return false;
    }
    bool ok = true;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string ep = p + "/" + std::to_string(i);
      if (!v[i].is_array() || v[i].size() != 2) {
        error(ep, "a schedule entry is [time (seconds), value]");
        ok = false;
        continue;
      }
      auto t = number(v[i][0], ep + "/0", "a time");
      auto x = sensed(v[i][1], ep + "/1");
      if (!t || !x) {
        ok = false;
        continue;
      }
      if (s.schedule.empty() && i == 0 && *t != 0) {
        error(ep + "/0", "a schedule starts at time 0");
        ok = false;
      } else if (!s.schedule.empty() && *t <= s.schedule.back().first) {
        error(ep + "/0", "schedule times must increase (" + json(*t).dump() + " after " + json(s.schedule.back().first).dump() + ")");
        ok = false;
      }
      s.schedule.push_back({*t, std::move(*x)});
    }
    return ok;
  }

  bool regions(const json& v, const std::string& p, ValueSource& s) {
    const json& regions = v["regions"];
    bool ok = true;
    if (!regions.is_array() || regions.empty()) {
      error(p + "/regions", "\"regions\" is a non-empty array of {\"polygon\" or \"circle\", \"value\"}");
      ok = false;
    } else {
      for (std::size_t i = 0; i < regions.size(); ++i) {
        const std::string rp = p + "/regions/" + std::to_string(i);
        const json& r = regions[i];
        if (!r.is_object()) {
          error(rp, "a region is {\"polygon\" or \"circle\", \"value\"}");
          ok = false;
          continue;
        }
        members(r, rp, "a region", {"polygon", "circle", "value"});
        auto sh = shape(r, rp, "a region");
        std::optional<SensedValue> x;
        if (r.contains("value")) x = sensed(r["value"], rp + "/value");
        else error(rp, "a region needs \"value\"");
        if (sh && x) s.regions.push_back({std::move(*sh), std::move(*x)});
        else ok = false;
      }
    }
    if (!v.contains("otherwise")) {
      error(p, "a value by regions needs \"otherwise\" (its value outside every region)");
      return false;
    }
    auto otherwise = sensed(v["otherwise"], p + "/otherwise");
    if (!otherwise) return false;
    s.otherwise = std::move(*otherwise);
    return ok;
  }

  void goal(const json& v, const std::string& p) {
    if (!v.is_object()) return error(p, "a goal is {\"team\": ..., \"mode\": ..., \"done\": [plans]}");
    members(v, p, "a goal", {"team", "mode", "done"});
    auto team = text(v, p, "team", "a goal");
    auto mode = text(v, p, "mode", "a goal");
    TeamGoal g{team.value_or(""), mode.value_or(""), {}, position(p)};
    if (auto it = v.find("done"); it != v.end()) {
      if (!it->is_array()) return error(p + "/done", "\"done\" is an array of plan names");
      for (std::size_t i = 0; i < it->size(); ++i) {
        const json& plan = (*it)[i];
        if (!plan.is_string() || plan.get_ref<const std::string&>().empty()) {
          error(p + "/done/" + std::to_string(i), "\"done\" is an array of plan names");
          return;
        }
        g.plansDone.push_back(plan.get<std::string>());
      }
    }
    if (team && mode) world_.goal.push_back(std::move(g));
  }
};

}  // namespace

std::optional<World> parseWorld(std::string_view text, const std::string& path, std::vector<WorldError>& errors) {
  const std::size_t before = errors.size();
  // The JSON parser would stop at a NUL byte and ignore what follows it.
  if (const auto nul = text.find('\0'); nul != std::string_view::npos) {
    errors.push_back(errorAt(text, path, nul, "not valid JSON: a NUL byte"));
    return std::nullopt;
  }
  const std::vector<std::size_t> starts = detail::lineStarts(text);
  PreScan scan = preScan(text);
  if (scan.tooDeep) {
    errors.push_back(errorAt(text, path, scan.problems.front().first, scan.problems.front().second));
    return std::nullopt;
  }
  json root;
  bool parsed = false;
  try {
    root = json::parse(text.begin(), text.end());
    parsed = true;
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    if (const auto at = what.find("syntax error"); at != std::string::npos) what = what.substr(at);
    errors.push_back(errorAt(text, path, e.byte == 0 ? 0 : e.byte - 1, "not valid JSON: " + what));
    return std::nullopt;
  } catch (const json::exception&) {
    // A number past what a double holds: nlohmann says so without a position, the scan has it.
    if (scan.problems.empty()) scan.problems.push_back({0, "not valid JSON"});
  }
  // Members given twice do not stop the reader: the other mistakes of the file are worth reporting too.
  for (const auto& [offset, message] : scan.problems) errors.push_back(errorAt(text, starts, path, offset, message));
  if (!parsed) return std::nullopt;
  Reader reader(text, starts, path, errors);
  try {
    reader.read(root);
  } catch (const json::exception& e) {  // a check above missed a type: report it rather than crash
    errors.push_back(errorAt(text, path, 0, std::string("unexpected JSON content: ") + e.what()));
  }
  if (errors.size() == before) return reader.take();
  // Members of an object are visited in key order: report in file order.
  std::stable_sort(errors.begin() + static_cast<std::ptrdiff_t>(before), errors.end(), [](const WorldError& a, const WorldError& b) {
    return std::pair(a.line, a.column) < std::pair(b.line, b.column);
  });
  return std::nullopt;
}

std::optional<World> readWorld(const std::string& path, std::vector<WorldError>& errors) {
  // A directory opens as a stream on Linux and then reads as nothing: ask first.
  std::error_code ec;
  std::ifstream in;
  if (!std::filesystem::is_directory(path, ec)) in.open(path, std::ios::binary);
  if (!in.is_open() || !in) {
    errors.push_back({path, 0, 0, "cannot read the world file", ""});
    return std::nullopt;
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parseWorld(buffer.str(), path, errors);
}

}  // namespace semo::runtime
