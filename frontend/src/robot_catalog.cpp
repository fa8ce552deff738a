#include "semo/frontend/robot_catalog.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "semo/frontend/xml_reader.hpp"

namespace semo {

namespace {

using tinyxml2::XMLElement;

// Collects urdfdom's console_bridge messages while a file is parsed, instead of printing them.
class CapturedLog : public console_bridge::OutputHandler {
 public:
  CapturedLog() { console_bridge::useOutputHandler(this); }
  ~CapturedLog() override { console_bridge::restorePreviousOutputHandler(); }
  CapturedLog(const CapturedLog&) = delete;
  CapturedLog& operator=(const CapturedLog&) = delete;
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors.push_back(text);
  }
  std::vector<std::string> errors;
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

const char* capabilityOfSensorType(const std::string& type) {
  static const std::pair<const char*, const char*> table[] = {
      {"camera", "Camera"}, {"depth", "Camera"}, {"multicamera", "Camera"}, {"wideanglecamera", "Camera"},
      {"ray", "LaserDistanceSensor"}, {"gpu_ray", "LaserDistanceSensor"}, {"lidar", "LaserDistanceSensor"},
      {"gpu_lidar", "LaserDistanceSensor"}, {"sonar", "ProximitySensor"}, {"range", "ProximitySensor"},
      {"imu", "Imu"}, {"contact", "ContactSensor"}, {"gps", "Gps"}, {"navsat", "Gps"},
      {"magnetometer", "Magnetometer"}};
  for (const auto& [t, cap] : table) {
    if (type == t) return cap;
  }
  return nullptr;
}

std::vector<const char*> capabilitiesOfLinkName(std::string name) {
  name = lower(name);
  if (name.size() > 5 && name.compare(name.size() - 5, 5, "_link") == 0) name.resize(name.size() - 5);
  static const std::pair<const char*, const char*> table[] = {
      {"camera", "Camera"}, {"lidar", "LaserDistanceSensor"}, {"laser", "LaserDistanceSensor"},
      {"scan", "LaserDistanceSensor"}, {"lds", "LaserDistanceSensor"}, {"sonar", "ProximitySensor"},
      {"ultrasonic", "ProximitySensor"}, {"proximity", "ProximitySensor"}, {"distance", "ProximitySensor"},
      {"light", "LightSensor"}, {"color", "ColorSensor"}, {"colour", "ColorSensor"}, {"imu", "Imu"},
      {"bumper", "Bumper"}, {"cliff", "CliffSensor"}, {"gps", "Gps"}, {"led", "Led"}, {"gripper", "Gripper"}};
  std::vector<const char*> out;
  for (const auto& [word, cap] : table) {
    if (name.find(word) != std::string::npos) out.push_back(cap);
  }
  return out;
}

void addCapability(RobotType& type, const std::string& name, const std::string& source) {
  for (const Capability& c : type.capabilities) {
    if (c.name == name) return;  // the first source found is kept
  }
  type.capabilities.push_back({name, source});
}

// urdfdom names the culprit in brackets or quotes ("joint [x]", "link 'y'"): find that element.
const XMLElement* culprit(const XMLElement* robot, const std::string& message) {
  std::vector<std::string> names;
  for (char open : {'[', '\''}) {
    char close = open == '[' ? ']' : '\'';
    for (std::size_t b = message.find(open); b != std::string::npos; b = message.find(open, b + 1)) {
      std::size_t e = message.find(close, b + 1);
      if (e == std::string::npos) break;
      names.push_back(message.substr(b + 1, e - b - 1));
      b = e;
    }
  }
  // For "not unique" the second element of that name is the culprit, otherwise the first.
  bool duplicate = message.find("unique") != std::string::npos;
  for (const std::string& n : names) {
    const XMLElement* found = nullptr;
    for (const XMLElement* e = robot->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      if (const char* attr = e->Attribute("name"); attr != nullptr && n == attr) {
        found = e;
        if (!duplicate) break;
      }
    }
    if (found != nullptr) return found;
  }
  return robot;
}

void deriveFromSensors(const XMLElement* robot, RobotType& type) {
  auto visit = [&](const XMLElement* sensor) {
    std::string name = sensor->Attribute("name") ? sensor->Attribute("name") : "?";
    if (const char* t = sensor->Attribute("type")) {
      if (const char* cap = capabilityOfSensorType(lower(t))) addCapability(type, cap, "sensor '" + name + "' (" + t + ")");
      return;
    }
    if (sensor->FirstChildElement("camera")) addCapability(type, "Camera", "sensor '" + name + "' (camera)");
    if (sensor->FirstChildElement("ray")) addCapability(type, "LaserDistanceSensor", "sensor '" + name + "' (ray)");
  };
  for (const XMLElement* e = robot->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    std::string_view tag = e->Name();
    if (tag == "sensor") visit(e);
    if (tag == "gazebo") {
      for (const XMLElement* s = e->FirstChildElement("sensor"); s != nullptr; s = s->NextSiblingElement("sensor")) visit(s);
    }
  }
}

double cylinderRadius(const urdf::Link& link) {
  auto radiusOf = [](const urdf::GeometrySharedPtr& g) -> double {
    if (g && g->type == urdf::Geometry::CYLINDER) return std::static_pointer_cast<urdf::Cylinder>(g)->radius;
    if (g && g->type == urdf::Geometry::SPHERE) return std::static_pointer_cast<urdf::Sphere>(g)->radius;
    return 0;
  };
  if (link.collision) {
    if (double r = radiusOf(link.collision->geometry); r > 0) return r;
  }
  if (link.visual) return radiusOf(link.visual->geometry);
  return 0;
}

void deriveFromModel(const urdf::ModelInterface& model, RobotType& type) {
  for (const auto& [name, link] : model.links_) {
    type.links.push_back(name);
    for (const char* cap : capabilitiesOfLinkName(name)) addCapability(type, cap, "link '" + name + "'");
    if (link->inertial) type.massKg += link->inertial->mass;
  }
  std::sort(type.links.begin(), type.links.end());
  std::vector<const urdf::Joint*> wheels;
  for (const auto& [name, joint] : model.joints_) {
    std::string n = lower(name);
    if (joint->type == urdf::Joint::FIXED) continue;
    if (n.find("wheel") != std::string::npos) wheels.push_back(joint.get());
    bool revolute = joint->type == urdf::Joint::REVOLUTE;
    if (revolute && (n.find("leg") != std::string::npos || n.find("hip") != std::string::npos ||
                     n.find("knee") != std::string::npos)) {
      addCapability(type, "Legs", "joint '" + name + "'");
    }
  }
  if (wheels.empty()) return;
  addCapability(type, "Wheels", "joint '" + wheels.front()->name + "'");
  if (wheels.size() >= 2) addCapability(type, "DifferentialDrive", std::to_string(wheels.size()) + " wheel joints");
  WheelGeometry g;
  g.wheelCount = static_cast<int>(wheels.size());
  double minY = 0, maxY = 0;
  bool first = true;
  for (const urdf::Joint* j : wheels) {
    double y = j->parent_to_joint_origin_transform.position.y;
    minY = first ? y : std::min(minY, y);
    maxY = first ? y : std::max(maxY, y);
    first = false;
    if (auto child = model.getLink(j->child_link_name)) g.radius = std::max(g.radius, cylinderRadius(*child));
    // The slowest wheel bounds the robot: driving straight needs every wheel at the same speed.
    if (j->limits && j->limits->velocity > 0) {
      g.maxWheelSpeed = g.maxWheelSpeed > 0 ? std::min(g.maxWheelSpeed, j->limits->velocity) : j->limits->velocity;
    }
  }
  g.separation = maxY - minY;
  type.wheels = g;
}

// Checks that the joints form a tree before urdfdom sees them: urdfdom leaks the links of a cycle,
// and its message ("No root link found") names neither the joint nor the link at fault.
bool checkJointTree(const XMLElement* robot, xml::Reader& xml) {
  std::map<std::string, const XMLElement*> parentJointOf;  // child link -> joint
  std::map<std::string, std::string> parentLinkOf;         // child link -> parent link
  bool ok = true;
  for (const XMLElement* j = robot->FirstChildElement("joint"); j != nullptr; j = j->NextSiblingElement("joint")) {
    const XMLElement* parent = j->FirstChildElement("parent");
    const XMLElement* child = j->FirstChildElement("child");
    if (parent == nullptr || child == nullptr || !parent->Attribute("link") || !child->Attribute("link")) continue;
    std::string childLink = child->Attribute("link");
    if (auto [it, added] = parentJointOf.emplace(childLink, j); !added) {
      Diagnostic& d = xml.error(j, "invalid URDF: link '" + childLink + "' is the child of two joints");
      DiagnosticEngine::note(d, xml.at(it->second), "first joint with that child");
      ok = false;
      continue;
    }
    parentLinkOf[childLink] = parent->Attribute("link");
  }
  // From each child link up to the root; a link whose way up is known to end at the root is not
  // walked again (else a chain of n links costs n^2), and a link met twice on one walk closes a cycle.
  std::map<std::string, int> state;  // 1: on the current walk; 2: its way up ends at the root
  for (const auto& [start, joint] : parentJointOf) {
    std::vector<const std::string*> walk;
    bool cycle = false;
    for (const std::string* link = &start;;) {
      int& s = state[*link];
      if (s == 2) break;
      if (s == 1) {
        cycle = true;
        break;
      }
      s = 1;
      walk.push_back(link);
      const auto up = parentLinkOf.find(*link);
      if (up == parentLinkOf.end()) break;
      link = &up->second;
    }
    if (cycle) {
      xml.error(joint, "invalid URDF: joints form a cycle through link '" + start + "' (a robot's links must form a tree)");
      return false;
    }
    for (const std::string* link : walk) state[*link] = 2;
  }
  return ok;
}

}  // namespace

bool RobotType::has(const std::string& capability) const {
  return std::any_of(capabilities.begin(), capabilities.end(), [&](const Capability& c) { return c.name == capability; });
}

const RobotType* RobotCatalog::find(const std::string& name) const {
  for (const RobotType& t : types_) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

std::vector<std::string> RobotCatalog::typeNames() const {
  std::vector<std::string> out;
  for (const RobotType& t : types_) out.push_back(t.name);
  return out;
}

std::vector<std::string> RobotCatalog::capabilityNames() const {
  std::set<std::string> names;
  for (const RobotType& t : types_) {
    for (const Capability& c : t.capabilities) names.insert(c.name);
  }
  return {names.begin(), names.end()};
}

std::optional<RobotType> loadRobotType(SourceManager& sources, const std::string& path, SourceRange requestedAt,
                                       DiagnosticEngine& diags) {
  std::string why;
  FileId file = sources.load(path, why);
  if (file == kNoFile) {
    diags.error(requestedAt, "cannot read robot description: " + why);
    return std::nullopt;
  }
  xml::Reader xml(sources, file, diags);
  tinyxml2::XMLDocument doc;
  if (!xml.parse(doc)) return std::nullopt;
  const XMLElement* robot = doc.RootElement();
  if (robot == nullptr || std::string_view(robot->Name()) != "robot") {
    if (robot == nullptr) {
      diags.error({{file, 1, 1}, 1}, "not a URDF file: no root element");
    } else {
      xml.error(robot, std::string("not a URDF file: the root element must be <robot>, not <") + robot->Name() + ">");
    }
    return std::nullopt;
  }

  // A xacro file (ROS's macro language for URDF) is not a URDF: semo reads what xacro writes.
  for (const XMLElement* e = robot; e != nullptr;) {
    std::string_view name = e->Name();
    bool macro = name.rfind("xacro:", 0) == 0;
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a != nullptr && !macro; a = a->Next()) {
      macro = std::string_view(a->Value()).find("${") != std::string_view::npos;
    }
    if (macro) {
      xml.error(e, "a xacro file, not a URDF: semo reads plain URDF; expand it first (ROS: `xacro " +
                       std::filesystem::path(path).filename().string() + " > robot.urdf`) and give the strategy that file");
      return std::nullopt;
    }
    // Depth first through the document, without recursion.
    if (const XMLElement* child = e->FirstChildElement()) {
      e = child;
      continue;
    }
    while (e != nullptr && e != robot && e->NextSiblingElement() == nullptr) e = e->Parent() ? e->Parent()->ToElement() : nullptr;
    e = e == nullptr || e == robot ? nullptr : e->NextSiblingElement();
  }
  if (!checkJointTree(robot, xml)) return std::nullopt;
  urdf::ModelInterfaceSharedPtr model;
  std::vector<std::string> errors;
  {
    CapturedLog log;
    try {
      model = urdf::parseURDF(sources.text(file));
    } catch (const std::exception& e) {
      log.errors.push_back(e.what());
    }
    errors = std::move(log.errors);
  }
  if (!model) {
    if (errors.empty()) errors.push_back("urdfdom rejected the robot description");
    // urdfdom follows its specific message with generic ones ("joint xml is not initialized
    // correctly"): the first says what is wrong.
    xml.error(culprit(robot, errors.front()), "invalid URDF: " + errors.front());
    return std::nullopt;
  }

  RobotType type;
  type.name = model->getName();
  type.urdfPath = path;
  deriveFromSensors(robot, type);
  deriveFromModel(*model, type);
  return type;
}

RobotCatalog buildCatalog(const strategy::Strategy& strategy, const std::optional<std::string>& robotsDir,
                          SourceManager& sources, DiagnosticEngine& diags) {
  namespace fs = std::filesystem;
  RobotCatalog catalog;
  auto addType = [&](RobotType type, SourceRange at) {
    if (const RobotType* existing = catalog.find(type.name)) {
      Diagnostic& d = diags.error(at, "robot type '" + type.name + "' is described twice (" + existing->urdfPath + " and " +
                                          type.urdfPath + ")");
      if (existing->declaredAt.begin.valid()) DiagnosticEngine::note(d, existing->declaredAt, "first described here");
      return;
    }
    type.declaredAt = at;
    catalog.add(std::move(type));
  };

  if (strategy.robots.empty() && robotsDir) {
    std::error_code ec;
    std::vector<fs::path> files;
    for (fs::directory_iterator it(*robotsDir, ec), end; !ec && it != end; it.increment(ec)) {
      if (it->path().extension() == ".urdf") files.push_back(it->path());
    }
    if (ec) diags.error({}, "cannot list robot folder '" + *robotsDir + "': " + ec.message());
    std::sort(files.begin(), files.end());
    for (const fs::path& p : files) {
      if (auto type = loadRobotType(sources, p.string(), {}, diags)) addType(std::move(*type), {});
    }
    return catalog;
  }

  for (const strategy::RobotEntry& entry : strategy.robots) {
    fs::path base = robotsDir ? fs::path(*robotsDir) : fs::path(strategy.folder);
    fs::path path = fs::path(entry.urdf).is_absolute() ? fs::path(entry.urdf) : base / entry.urdf;
    // `package://PKG/rest`, as ROS writes it: PKG/rest under --robots or a ROS_PACKAGE_PATH folder
    // (or that folder itself named PKG), else the file name alone in --robots.
    constexpr std::string_view kPackage = "package://";
    if (entry.urdf.rfind(kPackage, 0) == 0) {
      const std::string rest = entry.urdf.substr(kPackage.size());
      const std::string package = rest.substr(0, rest.find('/'));
      const std::string inside = rest.find('/') == std::string::npos ? std::string() : rest.substr(rest.find('/') + 1);
      std::vector<fs::path> tried;
      std::vector<fs::path> roots;
      if (robotsDir) roots.push_back(*robotsDir);
      if (const char* ros = std::getenv("ROS_PACKAGE_PATH")) {
        for (std::string_view list(ros); !list.empty();) {
          const std::size_t colon = std::min(list.find(':'), list.size());
          if (colon > 0) roots.emplace_back(std::string(list.substr(0, colon)));
          list.remove_prefix(std::min(colon + 1, list.size()));
        }
      }
      std::error_code ec;
      std::optional<fs::path> found;
      for (const fs::path& root : roots) {
        for (const fs::path& candidate : {root / package / inside, root.filename() == package ? root / inside : fs::path(),
                                          robotsDir && root == fs::path(*robotsDir) ? root / fs::path(inside).filename() : fs::path()}) {
          if (candidate.empty() || found) continue;
          tried.push_back(candidate);
          if (fs::exists(candidate, ec)) found = candidate;
        }
      }
      if (!found) {
        std::string where;
        for (const fs::path& t : tried) where += (where.empty() ? "" : ", ") + t.string();
        diags.error(entry.at, "cannot find '" + entry.urdf + "': " +
                                  (roots.empty() ? std::string("a package:// path needs --robots DIR or ROS_PACKAGE_PATH to say where packages are")
                                                 : "looked for " + where));
        continue;
      }
      path = *found;
    }
    // With --robots, a strategy written for another layout still works: fall back to the file name.
    std::error_code ec;
    if (robotsDir && !fs::exists(path, ec) && fs::exists(base / fs::path(entry.urdf).filename(), ec)) {
      path = base / fs::path(entry.urdf).filename();
    }
    if (!fs::exists(path, ec)) {
      // Say where it was looked for, offer a file of that folder with a close name, and --robots.
      const fs::path folder = robotsDir ? fs::path(*robotsDir) : path.lexically_normal().parent_path();
      const std::string file = fs::path(entry.urdf).filename().string();
      std::vector<std::string> near;
      for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec), end; !ec && it != end; it.increment(ec)) {
        if (it->path().extension() == ".urdf") near.push_back(it->path().filename().string());
      }
      const std::string suggestion = suggestClosest(file, near);
      const std::string where = robotsDir ? "--robots '" + *robotsDir + "' has no '" + file + "' (nor is there '" + path.lexically_normal().string() + "')"
                                          : "no file '" + path.lexically_normal().string() + "' (urdf=\"" + entry.urdf +
                                                "\" resolved against the strategy's folder '" +
                                                (strategy.folder.empty() ? std::string(".") : strategy.folder) + "')";
      Diagnostic& d = diags.error(entry.at, "cannot read robot description: " + where + (suggestion.empty() ? "" : "; " + suggestion));
      if (!robotsDir) DiagnosticEngine::note(d, entry.at, "if the URDF files are elsewhere, give their folder with --robots DIR");
      continue;
    }
    auto type = loadRobotType(sources, path.lexically_normal().string(), entry.at, diags);
    if (!type) continue;
    if (entry.type && *entry.type != type->name) {
      diags.error(entry.at, "robot type '" + *entry.type + "' does not match the URDF robot name '" + type->name + "' in " +
                                path.string());
      continue;
    }
    for (const strategy::CapabilityAddition& add : entry.capabilities) {
      if (!add.link.empty() && std::find(type->links.begin(), type->links.end(), add.link) == type->links.end()) {
        diags.error(add.at, "capability '" + add.name + "' names link '" + add.link + "', which robot type '" + type->name +
                                "' does not have");
        continue;
      }
      addCapability(*type, add.name, "strategy");
    }
    addType(std::move(*type), entry.at);
  }
  return catalog;
}

}  // namespace semo
