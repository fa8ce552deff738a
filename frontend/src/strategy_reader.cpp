// Reads a strategy XML file (specs/strategy.md) into semo::strategy::Strategy.
#include <algorithm>
#include <filesystem>
#include <set>

#include "semo/frontend/strategy.hpp"
#include "semo/frontend/xml_reader.hpp"

namespace semo::strategy {

namespace {

using tinyxml2::XMLElement;

constexpr std::int64_t kMaxRate = 1000000;
constexpr std::int64_t kMaxCount = 1000000;

// Splits "Team.var" or "Team.Plan.Service"; empty on a malformed name.
std::vector<std::string> dotted(const std::string& name, std::size_t parts) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (true) {
    std::size_t dot = name.find('.', begin);
    out.push_back(name.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin));
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  bool ok = out.size() == parts && std::none_of(out.begin(), out.end(), [](const std::string& s) { return s.empty(); });
  return ok ? out : std::vector<std::string>{};
}

class StrategyReader {
 public:
  StrategyReader(const SourceManager& sources, FileId file, DiagnosticEngine& diags) : xml_(sources, file, diags) {}

  Strategy read(const std::string& path) {
    Strategy s;
    s.file = xml_.file();
    s.folder = std::filesystem::path(path).parent_path().string();
    tinyxml2::XMLDocument doc;
    if (!xml_.parse(doc)) return s;
    const XMLElement* root = doc.RootElement();
    if (root == nullptr) {
      xml_.diags().error({{xml_.file(), 1, 1}, 1}, "the strategy file has no root element; expected <strategy>");
      return s;
    }
    if (std::string_view(root->Name()) != "strategy") {
      xml_.error(root, std::string("the root element must be <strategy>, not <") + root->Name() + ">");
      return s;
    }
    xml_.checkAttributes(root, {"version", "mission"});
    if (const char* v = root->Attribute("version"); v != nullptr && std::string_view(v) != "1") {
      xml_.attributeError(root, "version", std::string("unsupported strategy version '") + v + "' (this semo reads version 1)");
    }
    xml_.checkChildren(root, {"robot", "service", "value", "topic", "leader-selection", "events", "event"});
    bool sawEvents = false;
    for (const XMLElement* e = root->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      std::string_view name = e->Name();
      if (name == "robot") readRobot(e, s);
      if (name == "service") readService(e, s);
      if (name == "value") readValue(e, s);
      if (name == "topic") readTopic(e, s);
      if (name == "leader-selection") readLeaderSelection(e, s);
      if (name == "event") readEventOverride(e, s);
      if (name == "events") {
        if (sawEvents) xml_.error(e, "only one <events> element is allowed");
        sawEvents = true;
        xml_.checkAttributes(e, {"delivery", "retransmissions"});
        xml_.checkChildren(e, {});
        s.events = readDelivery(e);
      }
    }
    return s;
  }

 private:
  template <typename Item, typename Key>
  bool duplicate(const std::vector<Item>& items, const Key& key, const XMLElement* e, const std::string& what) {
    for (const Item& item : items) {
      if (key(item)) {
        Diagnostic& d = xml_.error(e, what + " is defined twice");
        DiagnosticEngine::note(d, item.at, "first defined here");
        return true;
      }
    }
    return false;
  }

  void readRobot(const XMLElement* e, Strategy& s) {
    xml_.checkAttributes(e, {"urdf", "type"});
    xml_.checkChildren(e, {"capability"});
    RobotEntry robot;
    robot.at = xml_.at(e);
    auto urdf = xml_.required(e, "urdf");
    if (!urdf) return;
    robot.urdf = *urdf;
    if (const char* type = e->Attribute("type")) robot.type = type;
    for (const XMLElement* c = e->FirstChildElement("capability"); c != nullptr; c = c->NextSiblingElement("capability")) {
      xml_.checkAttributes(c, {"name", "link"});
      xml_.checkChildren(c, {});
      auto name = xml_.required(c, "name");
      if (!name) continue;
      robot.capabilities.push_back({*name, c->Attribute("link") ? c->Attribute("link") : "", xml_.at(c)});
    }
    s.robots.push_back(std::move(robot));
  }

  void readPorts(const XMLElement* taskElement, Task& task) {
    for (const XMLElement* p = taskElement->FirstChildElement("port"); p != nullptr; p = p->NextSiblingElement("port")) {
      xml_.checkAttributes(p, {"name", "dir", "rate"});
      xml_.checkChildren(p, {});
      auto name = xml_.required(p, "name");
      auto dir = xml_.required(p, "dir");
      if (!name || !dir) continue;
      Port port{*name, true, 1, xml_.at(p)};
      if (*dir != "in" && *dir != "out") {
        xml_.attributeError(p, "dir", "port direction must be 'in' or 'out', not '" + *dir + "'");
        continue;
      }
      port.input = *dir == "in";
      if (auto rate = xml_.integer(p, "rate", 1, kMaxRate)) port.rate = *rate;
      if (task.port(port.name) != nullptr) {
        Diagnostic& d = xml_.error(p, "port '" + port.name + "' is defined twice in task '" + task.name + "'");
        DiagnosticEngine::note(d, task.port(port.name)->at, "first defined here");
        continue;
      }
      task.ports.push_back(std::move(port));
    }
  }

  // Checks one end of a channel: "task.port", existing, with the right direction.
  bool resolveEnd(const XMLElement* e, const char* attribute, const Implementation& impl, bool wantInput,
                  std::string& task, std::string& port) {
    auto text = xml_.required(e, attribute);
    if (!text) return false;
    auto parts = dotted(*text, 2);
    if (parts.empty()) {
      xml_.attributeError(e, attribute, std::string("channel end '") + *text + "' must be written 'task.port'");
      return false;
    }
    const Task* t = nullptr;
    for (const Task& candidate : impl.tasks) {
      if (candidate.name == parts[0]) t = &candidate;
    }
    if (t == nullptr) {
      xml_.attributeError(e, attribute, "channel end names unknown task '" + parts[0] + "'");
      return false;
    }
    const Port* p = t->port(parts[1]);
    if (p == nullptr) {
      xml_.attributeError(e, attribute, "task '" + parts[0] + "' has no port '" + parts[1] + "'");
      return false;
    }
    if (p->input != wantInput) {
      xml_.attributeError(e, attribute, std::string("channel ") + (wantInput ? "must end at an input" : "must start at an output") +
                                            " port, but '" + *text + "' is an " + (p->input ? "input" : "output"));
      return false;
    }
    task = parts[0];
    port = parts[1];
    return true;
  }

  void readImplementations(const XMLElement* owner, std::vector<Implementation>& out) {
    for (const XMLElement* e = owner->FirstChildElement("implementation"); e != nullptr;
         e = e->NextSiblingElement("implementation")) {
      xml_.checkAttributes(e, {"robot"});
      xml_.checkChildren(e, {"task", "channel"});
      auto robot = xml_.required(e, "robot");
      if (!robot) continue;
      Implementation impl{*robot, {}, {}, xml_.at(e)};
      if (duplicate(out, [&](const Implementation& i) { return i.robotType == *robot; }, e,
                    "the implementation for robot type '" + *robot + "'")) {
        continue;
      }
      for (const XMLElement* t = e->FirstChildElement("task"); t != nullptr; t = t->NextSiblingElement("task")) {
        xml_.checkAttributes(t, {"name", "exec"});
        xml_.checkChildren(t, {"port"});
        auto name = xml_.required(t, "name");
        if (!name) continue;
        Task task{*name, 0, {}, xml_.at(t)};
        if (auto exec = xml_.durationMicros(t, "exec")) {
          task.execMicros = *exec;
        } else if (t->Attribute("exec") == nullptr) {
          xml_.error(t, "<task> needs attribute 'exec' (its worst-case execution time, e.g. '5 MSEC')");
        }
        if (duplicate(impl.tasks, [&](const Task& x) { return x.name == *name; }, t, "task '" + *name + "'")) continue;
        readPorts(t, task);
        impl.tasks.push_back(std::move(task));
      }
      for (const XMLElement* c = e->FirstChildElement("channel"); c != nullptr; c = c->NextSiblingElement("channel")) {
        xml_.checkAttributes(c, {"from", "to", "initial"});
        xml_.checkChildren(c, {});
        Channel ch;
        ch.at = xml_.at(c);
        bool ok = resolveEnd(c, "from", impl, false, ch.fromTask, ch.fromPort);
        ok = resolveEnd(c, "to", impl, true, ch.toTask, ch.toPort) && ok;
        if (auto initial = xml_.integer(c, "initial", 0, kMaxCount)) ch.initialTokens = *initial;
        if (ok) impl.channels.push_back(std::move(ch));
      }
      out.push_back(std::move(impl));
    }
  }

  void readService(const XMLElement* e, Strategy& s) {
    xml_.checkAttributes(e, {"name", "kind", "min-robots"});
    auto name = xml_.required(e, "name");
    if (!name) return;
    Service service;
    service.name = *name;
    service.at = xml_.at(e);
    std::string kind = e->Attribute("kind") ? e->Attribute("kind") : "primitive";
    if (kind == "group") {
      service.kind = Service::Kind::Group;
      xml_.checkChildren(e, {"param", "implementation", "knowledge", "dissemination", "goal"});
    } else {
      if (kind != "primitive") {
        xml_.attributeError(e, "kind", "service kind must be 'primitive' or 'group', not '" + kind + "'");
      } else {
        xml_.checkChildren(e, {"param", "implementation"});
      }
      if (e->Attribute("min-robots")) xml_.attributeError(e, "min-robots", "'min-robots' applies to group services only");
    }
    if (duplicate(s.services, [&](const Service& x) { return x.name == *name; }, e, "service '" + *name + "'")) return;
    if (auto min = xml_.integer(e, "min-robots", 1, kMaxCount)) service.minRobots = *min;
    for (const XMLElement* p = e->FirstChildElement("param"); p != nullptr; p = p->NextSiblingElement("param")) {
      xml_.checkAttributes(p, {"name"});
      xml_.checkChildren(p, {});
      service.paramsDeclared = true;
      if (auto param = xml_.required(p, "name")) service.params.push_back(*param);
    }
    readImplementations(e, service.implementations);
    if (service.kind == Service::Kind::Group) readGroupParts(e, service);
    s.services.push_back(std::move(service));
  }

  void readGroupParts(const XMLElement* e, Service& service) {
    for (const XMLElement* k = e->FirstChildElement("knowledge"); k != nullptr; k = k->NextSiblingElement("knowledge")) {
      xml_.checkAttributes(k, {"name", "values", "merge"});
      xml_.checkChildren(k, {});
      auto name = xml_.required(k, "name");
      auto values = xml_.required(k, "values");  // reported if missing; the item is kept for the goal
      if (!name) continue;
      Knowledge item{*name, xml::splitList(values.value_or("")), Knowledge::Merge::Newest, xml_.at(k)};
      std::string merge = k->Attribute("merge") ? k->Attribute("merge") : "newest";
      if (merge == "union") {
        item.merge = Knowledge::Merge::Union;
      } else if (merge != "newest") {
        xml_.attributeError(k, "merge", "knowledge merge must be 'newest' or 'union', not '" + merge + "'");
      }
      if (duplicate(service.knowledge, [&](const Knowledge& x) { return x.name == *name; }, k, "knowledge '" + *name + "'")) continue;
      service.knowledge.push_back(std::move(item));
    }
    if (service.knowledge.empty()) {
      xml_.error(e, "group service '" + service.name + "' shares no knowledge: add a <knowledge name=... values=...>");
    }
    if (const XMLElement* d = e->FirstChildElement("dissemination")) {
      xml_.checkAttributes(d, {"via", "period", "retransmissions"});
      xml_.checkChildren(d, {});
      Dissemination dis;
      dis.at = xml_.at(d);
      if (const char* via = d->Attribute("via"); via != nullptr) {
        if (std::string_view(via) == "broadcast" || std::string_view(via) == "reliable" || std::string_view(via) == "none") {
          dis.via = via;
        } else {
          xml_.attributeError(d, "via", std::string("dissemination via '") + via + "' is not supported; use 'broadcast', 'reliable' or 'none'");
        }
      }
      if (auto period = xml_.durationMicros(d, "period")) {
        if (*period < 1000) xml_.attributeError(d, "period", "the gossip period must be at least 1 MSEC");
        dis.periodMillis = *period / 1000;
      }
      if (auto r = xml_.integer(d, "retransmissions", 0, 100)) dis.retransmissions = *r;
      service.dissemination = dis;
      if (d->NextSiblingElement("dissemination")) xml_.error(d->NextSiblingElement("dissemination"), "only one <dissemination> per service");
    }
    if (const XMLElement* g = e->FirstChildElement("goal")) {
      xml_.checkAttributes(g, {"knowledge", "count"});
      xml_.checkChildren(g, {});
      auto knowledge = xml_.required(g, "knowledge");
      Goal goal{knowledge.value_or(""), 1, xml_.at(g)};
      if (auto count = xml_.integer(g, "count", 1, kMaxCount)) goal.count = *count;
      if (knowledge) {
        auto it = std::find_if(service.knowledge.begin(), service.knowledge.end(),
                               [&](const Knowledge& k) { return k.name == *knowledge; });
        if (it == service.knowledge.end()) {
          xml_.attributeError(g, "knowledge", "goal names unknown knowledge '" + *knowledge + "'");
        } else if (!it->values.empty() && goal.count > static_cast<std::int64_t>(it->values.size())) {
          xml_.attributeError(g, "count", "goal count " + std::to_string(goal.count) + " can never be reached: knowledge '" +
                                              it->name + "' has only " + std::to_string(it->values.size()) + " facts");
        }
      }
      service.goal = goal;
    }
  }

  void readDomain(const XMLElement* d, Domain& domain) {
    xml_.checkAttributes(d, {"kind", "thresholds", "values", "min", "max"});
    xml_.checkChildren(d, {});
    domain.at = xml_.at(d);
    auto kind = xml_.required(d, "kind");
    if (!kind) return;
    if (*kind == "bool") {
      domain.kind = Domain::Kind::Bool;
    } else if (*kind == "threshold") {
      domain.kind = Domain::Kind::Threshold;
      auto list = xml_.required(d, "thresholds");
      if (!list) return;
      for (const std::string& t : xml::splitList(*list)) {
        char* end = nullptr;
        double v = std::strtod(t.c_str(), &end);
        if (end == t.c_str() || *end != '\0') {
          xml_.attributeError(d, "thresholds", "threshold '" + t + "' is not a number");
          return;
        }
        domain.thresholds.push_back(v);
      }
      if (!std::is_sorted(domain.thresholds.begin(), domain.thresholds.end()) ||
          std::adjacent_find(domain.thresholds.begin(), domain.thresholds.end()) != domain.thresholds.end()) {
        xml_.attributeError(d, "thresholds", "thresholds must be strictly increasing");
      }
    } else if (*kind == "enum") {
      domain.kind = Domain::Kind::Enum;
      if (auto list = xml_.required(d, "values")) domain.values = xml::splitList(*list);
    } else if (*kind == "range") {
      domain.kind = Domain::Kind::Range;
      auto min = xml_.integer(d, "min", -1000000, 1000000);
      auto max = xml_.integer(d, "max", -1000000, 1000000);
      if (!d->Attribute("min") || !d->Attribute("max")) xml_.error(d, "a range domain needs 'min' and 'max'");
      if (min && max) {
        domain.min = *min;
        domain.max = *max;
        if (*min > *max) xml_.attributeError(d, "max", "range domain has max < min");
      }
    } else {
      xml_.attributeError(d, "kind", "domain kind must be one of bool, threshold, enum, range; not '" + *kind + "'");
    }
  }

  void readValue(const XMLElement* e, Strategy& s) {
    xml_.checkAttributes(e, {"name", "source"});
    xml_.checkChildren(e, {"domain", "implementation"});
    auto name = xml_.required(e, "name");
    if (!name) return;
    auto parts = dotted(*name, 2);
    if (parts.empty()) {
      xml_.attributeError(e, "name", "value name '" + *name + "' must be written 'Team.value'");
      return;
    }
    Value value;
    value.team = parts[0];
    value.var = parts[1];
    value.at = xml_.at(e);
    const std::string source = e->Attribute("source") ? e->Attribute("source") : "robot";
    if (source == "team") {
      value.teamSource = true;
    } else if (source != "robot") {
      xml_.attributeError(e, "source", "a value's source must be 'robot' (each robot senses it for itself) or 'team' (one source every robot reads), not '" + source + "'");
    }
    if (duplicate(s.values, [&](const Value& v) { return v.team == parts[0] && v.var == parts[1]; }, e, "value '" + *name + "'")) return;
    const XMLElement* d = e->FirstChildElement("domain");
    if (d == nullptr) {
      xml_.error(e, "value '" + *name + "' needs a <domain kind=...> (bool, threshold, enum or range)");
    } else {
      readDomain(d, value.domain);
      if (d->NextSiblingElement("domain")) xml_.error(d->NextSiblingElement("domain"), "only one <domain> per value");
    }
    readImplementations(e, value.implementations);
    s.values.push_back(std::move(value));
  }

  void readTopic(const XMLElement* e, Strategy& s) {
    xml_.checkAttributes(e, {"name", "values", "buffer"});
    xml_.checkChildren(e, {});
    auto name = xml_.required(e, "name");
    if (!name) return;
    auto parts = dotted(*name, 2);
    if (parts.empty()) {
      xml_.attributeError(e, "name", "topic name '" + *name + "' must be written 'Team.topic'");
      return;
    }
    Topic topic{parts[0], parts[1], {}, 1, xml_.at(e)};
    if (const char* values = e->Attribute("values")) topic.values = xml::splitList(values);
    if (auto buffer = xml_.integer(e, "buffer", 1, 1024)) topic.buffer = *buffer;
    if (duplicate(s.topics, [&](const Topic& t) { return t.team == parts[0] && t.var == parts[1]; }, e, "topic '" + *name + "'")) return;
    s.topics.push_back(std::move(topic));
  }

  void readLeaderSelection(const XMLElement* e, Strategy& s) {
    xml_.checkAttributes(e, {"service", "algorithm", "reelection", "on-mode-change", "heartbeat", "timeout"});
    xml_.checkChildren(e, {});
    auto service = xml_.required(e, "service");
    if (!service) return;
    auto parts = dotted(*service, 3);
    if (parts.empty()) {
      xml_.attributeError(e, "service", "leader selection names service '" + *service + "'; write it 'Team.Plan.Service'");
      return;
    }
    LeaderSelection ls;
    ls.team = parts[0];
    ls.plan = parts[1];
    ls.service = parts[2];
    ls.at = xml_.at(e);
    std::string algorithm = e->Attribute("algorithm") ? e->Attribute("algorithm") : "lowest-id";
    if (algorithm == "bully") {
      ls.algorithm = LeaderSelection::Algorithm::Bully;
    } else if (algorithm != "lowest-id") {
      xml_.attributeError(e, "algorithm", "leader selection algorithm must be 'bully' or 'lowest-id', not '" + algorithm + "'");
    }
    std::string reelection = e->Attribute("reelection") ? e->Attribute("reelection") : "timeout";
    if (reelection == "formation") {
      ls.reelection = LeaderSelection::Reelection::Formation;
      for (const char* timing : {"heartbeat", "timeout"}) {
        if (e->Attribute(timing)) {
          xml_.attributeError(e, timing, std::string("'") + timing + "' applies to reelection=\"timeout\" only: with \"formation\" " +
                                             "no heartbeats are sent and a new leader is chosen when the group forms again");
        }
      }
    } else if (reelection != "timeout") {
      xml_.attributeError(e, "reelection", "reelection must be 'timeout' or 'formation', not '" + reelection + "'");
    }
    const std::string onModeChange = e->Attribute("on-mode-change") ? e->Attribute("on-mode-change") : "release";
    if (onModeChange == "keep") {
      ls.onModeChange = LeaderSelection::OnModeChange::Keep;
    } else if (onModeChange != "release") {
      xml_.attributeError(e, "on-mode-change", "on-mode-change must be 'release' or 'keep', not '" + onModeChange + "'");
    }
    if (auto hb = xml_.durationMicros(e, "heartbeat")) ls.heartbeatMillis = *hb / 1000;
    if (auto to = xml_.durationMicros(e, "timeout")) ls.timeoutMillis = *to / 1000;
    if (ls.heartbeatMillis <= 0) xml_.attributeError(e, "heartbeat", "the heartbeat period must be at least 1 MSEC");
    if (ls.timeoutMillis <= 0) xml_.attributeError(e, "timeout", "the failure timeout must be at least 1 MSEC");
    if (ls.heartbeatMillis > 0 && ls.timeoutMillis > 0 && ls.timeoutMillis <= ls.heartbeatMillis) {
      xml_.diags().warning(xml_.attributeAt(e, "timeout"),
                           "failure timeout (" + std::to_string(ls.timeoutMillis) + " ms) is not longer than the heartbeat period (" +
                               std::to_string(ls.heartbeatMillis) + " ms): the leader will be suspected between two heartbeats");
    }
    if (duplicate(s.leaderSelections, [&](const LeaderSelection& x) {
          return x.team == ls.team && x.plan == ls.plan && x.service == ls.service;
        }, e, "leader selection for '" + *service + "'")) {
      return;
    }
    s.leaderSelections.push_back(std::move(ls));
  }

  EventDelivery readDelivery(const XMLElement* e) {
    EventDelivery d;
    d.at = xml_.at(e);
    if (const char* delivery = e->Attribute("delivery")) {
      std::string_view v(delivery);
      if (v == "reliable") {
        d.reliable = true;
      } else if (v != "broadcast") {
        xml_.attributeError(e, "delivery", std::string("event delivery must be 'broadcast' or 'reliable', not '") + delivery + "'");
      }
    }
    if (auto r = xml_.integer(e, "retransmissions", 0, 100)) d.retransmissions = *r;
    return d;
  }

  void readEventOverride(const XMLElement* e, Strategy& s) {
    xml_.checkAttributes(e, {"name", "delivery", "retransmissions"});
    xml_.checkChildren(e, {});
    auto name = xml_.required(e, "name");
    if (!name) return;
    EventOverride o{*name, readDelivery(e)};
    for (const EventOverride& existing : s.eventOverrides) {
      if (existing.name == *name) {
        Diagnostic& d = xml_.error(e, "event '" + *name + "' is configured twice");
        DiagnosticEngine::note(d, existing.delivery.at, "first configured here");
        return;
      }
    }
    s.eventOverrides.push_back(std::move(o));
  }

  xml::Reader xml_;
};

}  // namespace

const Port* Task::port(const std::string& portName) const {
  for (const Port& p : ports) {
    if (p.name == portName) return &p;
  }
  return nullptr;
}

const Implementation* findImplementation(const std::vector<Implementation>& implementations, const std::string& robotType) {
  for (const Implementation& i : implementations) {
    if (i.robotType == robotType) return &i;
  }
  return nullptr;
}

const Implementation* Service::implementationFor(const std::string& robotType) const {
  return findImplementation(implementations, robotType);
}

const Implementation* Value::implementationFor(const std::string& robotType) const {
  return findImplementation(implementations, robotType);
}

const Service* Strategy::service(const std::string& name) const {
  for (const Service& s : services) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

const Value* Strategy::value(const std::string& team, const std::string& var) const {
  for (const Value& v : values) {
    if (v.team == team && v.var == var) return &v;
  }
  return nullptr;
}

const Topic* Strategy::topic(const std::string& team, const std::string& var) const {
  for (const Topic& t : topics) {
    if (t.team == team && t.var == var) return &t;
  }
  return nullptr;
}

const LeaderSelection* Strategy::leaderSelection(const std::string& team, const std::string& plan,
                                                 const std::string& service) const {
  for (const LeaderSelection& l : leaderSelections) {
    if (l.team == team && l.plan == plan && l.service == service) return &l;
  }
  return nullptr;
}

EventDelivery Strategy::eventDelivery(const std::string& event) const {
  for (const EventOverride& o : eventOverrides) {
    if (o.name == event) return o.delivery;
  }
  return events;
}

Strategy readStrategy(const SourceManager& sources, FileId file, DiagnosticEngine& diags) {
  return StrategyReader(sources, file, diags).read(sources.path(file));
}

}  // namespace semo::strategy
