// Task graphs as JSON and Graphviz (task_graph_io.hpp; the format: specs/taskgraph.md).
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "semo/frontend/json_text.hpp"
#include "semo/runtime/json_positions.hpp"
#include "semo/sdf/task_graph_io.hpp"

namespace semo::sdf {

namespace {

using nlohmann::json;

constexpr std::int64_t kMaxRate = 1'000'000'000;

const char* remoteKindName(RemotePort::Kind k) { return k == RemotePort::Kind::Multicast ? "multicast" : "point-to-point"; }

std::string dotQuoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c == '\n' ? ' ' : c;
  }
  return out + "\"";
}

struct Invalid {};


class Reader {
 public:
  Reader(const SourceManager& sources, FileId file, DiagnosticEngine& diags)
      : sources_(sources), text_(sources.text(file)), file_(file), diags_(diags), positions_(text_) {}

  std::optional<TaskGraph> read(const json& root) {
    try {
      graph(root);
    } catch (const Invalid&) {
    }
    if (diags_.hasErrors()) return std::nullopt;
    return std::move(tg_);
  }

 private:
  const SourceManager& sources_;
  const std::string& text_;
  FileId file_;
  DiagnosticEngine& diags_;
  runtime::JsonPositions positions_;
  TaskGraph tg_;
  std::map<std::string, std::uint32_t> taskIndex_, channelIndex_;

  SourceRange at(const std::string& pointer) const { return {sources_.locationAt(file_, positions_.offsetOf(pointer)), 1}; }

  [[noreturn]] void fail(const std::string& pointer, const std::string& message) {
    diags_.error(at(pointer), message);
    throw Invalid{};
  }

  const json& member(const json& object, const std::string& pointer, const char* key, json::value_t type, const char* what) {
    if (!object.is_object()) fail(pointer, "expected an object here");
    auto it = object.find(key);
    if (it == object.end()) fail(pointer, std::string("missing \"") + key + "\" (" + what + ")");
    const bool ok = type == json::value_t::number_integer ? it->is_number_integer() : it->type() == type;
    if (!ok) fail(pointer + "/" + key, std::string("\"") + key + "\" must be " + what);
    return *it;
  }

  std::string text(const json& o, const std::string& p, const char* key) {
    return member(o, p, key, json::value_t::string, "a string").get<std::string>();
  }
  std::int64_t integer(const json& o, const std::string& p, const char* key, std::int64_t min, std::int64_t max) {
    const json& v = member(o, p, key, json::value_t::number_integer, "an integer");
    if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(max)) {
      fail(p + "/" + key, std::string("\"") + key + "\" must be between " + std::to_string(min) + " and " + std::to_string(max));
    }
    const std::int64_t x = v.get<std::int64_t>();
    if (x < min || x > max) fail(p + "/" + key, std::string("\"") + key + "\" must be between " + std::to_string(min) + " and " + std::to_string(max));
    return x;
  }
  const json& array(const json& o, const std::string& p, const char* key) {
    return member(o, p, key, json::value_t::array, "an array");
  }

  // An optional array of strings.
  std::vector<std::string> strings(const json& o, const std::string& p, const char* key) {
    std::vector<std::string> out;
    auto it = o.find(key);
    if (it == o.end()) return out;
    if (!it->is_array()) fail(p + "/" + key, std::string("\"") + key + "\" must be an array of strings");
    for (std::size_t i = 0; i < it->size(); ++i) {
      if (!(*it)[i].is_string()) fail(p + "/" + key + "/" + std::to_string(i), std::string("\"") + key + "\" must be an array of strings");
      out.push_back((*it)[i].get<std::string>());
    }
    return out;
  }

  std::uint32_t taskNamed(const std::string& name, const std::string& pointer) {
    auto it = taskIndex_.find(name);
    if (it == taskIndex_.end()) fail(pointer, "no task named '" + name + "'");
    return it->second;
  }

  const TaskPort& portNamed(std::uint32_t task, const std::string& port, bool input, const std::string& pointer) {
    for (const TaskPort& p : tg_.tasks[task].ports) {
      if (p.name == port) {
        if (p.input != input) fail(pointer, "port '" + tg_.tasks[task].name + "." + port + "' is an " + (p.input ? "input" : "output") + " port");
        return p;
      }
    }
    fail(pointer, "task '" + tg_.tasks[task].name + "' has no port '" + port + "'");
  }

  // "task.port" split at the first dot: task names have none, the control task's port names do ("planner.goal").
  std::pair<std::uint32_t, std::string> endpoint(const std::string& ref, const std::string& pointer) {
    const auto dot = ref.find('.');
    if (dot == std::string::npos) fail(pointer, "expected 'task.port', got '" + ref + "'");
    return {taskNamed(ref.substr(0, dot), pointer), ref.substr(dot + 1)};
  }

  void graph(const json& root) {
    if (!root.is_object()) fail("", "a task graph is a JSON object");
    if (text(root, "", "format") != "semo-taskgraph") fail("/format", "\"format\" must be \"semo-taskgraph\"");
    if (integer(root, "", "version", 0, 1000) != 1) fail("/version", "unsupported task-graph version (this semo reads version 1)");
    tg_.robot = text(root, "", "robot");
    tg_.robotType = text(root, "", "robotType");
    tg_.team = text(root, "", "team");
    const json& tasks = array(root, "", "tasks");
    for (std::size_t i = 0; i < tasks.size(); ++i) task(tasks[i], "/tasks/" + std::to_string(i));
    const json& channels = array(root, "", "channels");
    for (std::size_t i = 0; i < channels.size(); ++i) channel(channels[i], "/channels/" + std::to_string(i));
    if (auto it = root.find("remotePorts"); it != root.end()) {
      if (!it->is_array()) fail("/remotePorts", "\"remotePorts\" must be an array");
      for (std::size_t i = 0; i < it->size(); ++i) remote((*it)[i], "/remotePorts/" + std::to_string(i));
    }
    const json& scenarios = array(root, "", "scenarios");
    if (scenarios.empty()) fail("/scenarios", "a task graph needs at least one scenario");
    for (std::size_t i = 0; i < scenarios.size(); ++i) scenario(scenarios[i], "/scenarios/" + std::to_string(i));
  }

  void task(const json& o, const std::string& p) {
    Task t;
    t.name = text(o, p, "name");
    if (t.name.empty() || t.name.find('.') != std::string::npos) fail(p + "/name", "a task name must be non-empty and without '.'");
    const std::string kind = text(o, p, "kind");
    bool known = false;
    for (TaskKind k : {TaskKind::Service, TaskKind::Sensing, TaskKind::Control, TaskKind::Communication, TaskKind::Knowledge,
                       TaskKind::LeaderElection}) {
      if (kind == taskKindName(k)) {
        t.kind = k;
        known = true;
      }
    }
    if (!known) fail(p + "/kind", "unknown task kind '" + kind + "'");
    t.execMicros = integer(o, p, "execMicros", 0, std::int64_t{1} << 40);
    t.origins = strings(o, p, "origins");
    t.at = at(p);
    const json& ports = array(o, p, "ports");
    std::set<std::string> names;
    for (std::size_t i = 0; i < ports.size(); ++i) {
      const std::string pp = p + "/ports/" + std::to_string(i);
      TaskPort port;
      port.name = text(ports[i], pp, "name");
      if (!names.insert(port.name).second) fail(pp + "/name", "port '" + port.name + "' declared twice");
      const std::string dir = text(ports[i], pp, "dir");
      if (dir != "in" && dir != "out") fail(pp + "/dir", "\"dir\" must be \"in\" or \"out\"");
      port.input = dir == "in";
      port.rate = integer(ports[i], pp, "rate", t.kind == TaskKind::Control ? 0 : 1, kMaxRate);
      t.ports.push_back(std::move(port));
    }
    if (!taskIndex_.emplace(t.name, static_cast<std::uint32_t>(tg_.tasks.size())).second) fail(p + "/name", "task '" + t.name + "' declared twice");
    tg_.tasks.push_back(std::move(t));
  }

  void channel(const json& o, const std::string& p) {
    TaskChannel c;
    c.name = text(o, p, "name");
    auto [from, fromPort] = endpoint(text(o, p, "from"), p + "/from");
    auto [to, toPort] = endpoint(text(o, p, "to"), p + "/to");
    portNamed(from, fromPort, false, p + "/from");
    portNamed(to, toPort, true, p + "/to");
    c.fromTask = from;
    c.fromPort = fromPort;
    c.toTask = to;
    c.toPort = toPort;
    c.initialTokens = integer(o, p, "initialTokens", 0, kMaxRate);
    if (auto it = o.find("control"); it != o.end()) {
      if (!it->is_boolean()) fail(p + "/control", "\"control\" must be true or false");
      c.control = it->get<bool>();
    }
    if (!channelIndex_.emplace(c.name, static_cast<std::uint32_t>(tg_.channels.size())).second) fail(p + "/name", "channel '" + c.name + "' declared twice");
    tg_.channels.push_back(std::move(c));
  }

  void remote(const json& o, const std::string& p) {
    RemotePort r;
    r.task = taskNamed(text(o, p, "task"), p + "/task");
    r.port = text(o, p, "port");
    const std::string dir = text(o, p, "dir");
    if (dir != "in" && dir != "out") fail(p + "/dir", "\"dir\" must be \"in\" or \"out\"");
    r.output = dir == "out";
    portNamed(r.task, r.port, !r.output, p + "/port");
    const std::string kind = text(o, p, "kind");
    if (kind != "multicast" && kind != "point-to-point") fail(p + "/kind", "\"kind\" must be \"multicast\" or \"point-to-point\"");
    r.kind = kind == "multicast" ? RemotePort::Kind::Multicast : RemotePort::Kind::PointToPoint;
    r.id = text(o, p, "id");
    r.buffer = integer(o, p, "buffer", 1, kMaxRate);
    r.peers = strings(o, p, "peers");
    tg_.remotePorts.push_back(std::move(r));
  }

  void scenario(const json& o, const std::string& p) {
    Scenario s;
    s.name = text(o, p, "name");
    s.mode = text(o, p, "mode");
    s.services = strings(o, p, "services");
    const json& tasks = array(o, p, "tasks");
    std::set<std::uint32_t> active;
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      const std::string tp = p + "/tasks/" + std::to_string(i);
      if (!tasks[i].is_string()) fail(tp, "a scenario's tasks are task names");
      const std::uint32_t t = taskNamed(tasks[i].get<std::string>(), tp);
      if (!active.insert(t).second) fail(tp, "task '" + tg_.tasks[t].name + "' listed twice");
      s.tasks.push_back(t);
    }
    const json& channels = array(o, p, "channels");
    std::set<std::pair<std::uint32_t, std::string>> fed;
    for (std::size_t i = 0; i < channels.size(); ++i) {
      const std::string cp = p + "/channels/" + std::to_string(i);
      const std::string name = text(channels[i], cp, "channel");
      auto it = channelIndex_.find(name);
      if (it == channelIndex_.end()) fail(cp + "/channel", "no channel named '" + name + "'");
      const TaskChannel& ch = tg_.channels[it->second];
      for (std::uint32_t end : {ch.fromTask, ch.toTask}) {
        if (active.count(end) == 0) fail(cp + "/channel", "channel '" + name + "' connects task '" + tg_.tasks[end].name + "', which is not in the scenario");
      }
      if (!fed.insert({ch.toTask, ch.toPort}).second) fail(cp + "/channel", "two channels of the scenario feed input port '" + tg_.tasks[ch.toTask].name + "." + ch.toPort + "'");
      ScenarioChannel sc;
      sc.channel = it->second;
      sc.production = integer(channels[i], cp, "production", 1, kMaxRate);
      sc.consumption = integer(channels[i], cp, "consumption", 1, kMaxRate);
      sc.initialTokens = integer(channels[i], cp, "initialTokens", 0, kMaxRate);
      // A port's own rate holds in every scenario; only the control task's (0) varies.
      const std::int64_t fromRate = portNamed(ch.fromTask, ch.fromPort, false, cp).rate;
      const std::int64_t toRate = portNamed(ch.toTask, ch.toPort, true, cp).rate;
      if (fromRate != 0 && sc.production != fromRate) fail(cp + "/production", "port '" + tg_.tasks[ch.fromTask].name + "." + ch.fromPort + "' produces " + std::to_string(fromRate) + " tokens per firing, not " + std::to_string(sc.production));
      if (toRate != 0 && sc.consumption != toRate) fail(cp + "/consumption", "port '" + tg_.tasks[ch.toTask].name + "." + ch.toPort + "' consumes " + std::to_string(toRate) + " tokens per firing, not " + std::to_string(sc.consumption));
      s.channels.push_back(sc);
    }
    tg_.scenarios.push_back(std::move(s));
  }
};

}  // namespace

std::string taskGraphToJson(const TaskGraph& tg) {
  json root = {{"format", "semo-taskgraph"}, {"version", 1}, {"robot", tg.robot}, {"robotType", tg.robotType}, {"team", tg.team}};
  json tasks = json::array();
  for (const Task& t : tg.tasks) {
    json ports = json::array();
    for (const TaskPort& p : t.ports) ports.push_back({{"name", p.name}, {"dir", p.input ? "in" : "out"}, {"rate", p.rate}});
    tasks.push_back({{"name", t.name}, {"kind", taskKindName(t.kind)}, {"origins", t.origins}, {"execMicros", t.execMicros}, {"ports", ports}});
  }
  root["tasks"] = tasks;
  json channels = json::array();
  for (const TaskChannel& c : tg.channels) {
    channels.push_back({{"name", c.name},
                        {"from", tg.tasks[c.fromTask].name + "." + c.fromPort},
                        {"to", tg.tasks[c.toTask].name + "." + c.toPort},
                        {"initialTokens", c.initialTokens},
                        {"control", c.control}});
  }
  root["channels"] = channels;
  json remotes = json::array();
  for (const RemotePort& r : tg.remotePorts) {
    remotes.push_back({{"task", tg.tasks[r.task].name}, {"port", r.port}, {"dir", r.output ? "out" : "in"}, {"kind", remoteKindName(r.kind)},
                       {"id", r.id}, {"buffer", r.buffer}, {"peers", r.peers}});
  }
  root["remotePorts"] = remotes;
  json scenarios = json::array();
  for (const Scenario& s : tg.scenarios) {
    json active = json::array();
    for (std::uint32_t t : s.tasks) active.push_back(tg.tasks[t].name);
    json chans = json::array();
    for (const ScenarioChannel& sc : s.channels) {
      chans.push_back({{"channel", tg.channels[sc.channel].name}, {"production", sc.production}, {"consumption", sc.consumption},
                       {"initialTokens", sc.initialTokens}});
    }
    scenarios.push_back({{"name", s.name}, {"mode", s.mode}, {"services", s.services}, {"tasks", active}, {"channels", chans}});
  }
  root["scenarios"] = scenarios;
  return root.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::optional<TaskGraph> readTaskGraphJson(const SourceManager& sources, FileId file, DiagnosticEngine& diags) {
  std::optional<json> root = parseJsonFile(sources, file, diags);
  if (!root) return std::nullopt;
  return Reader(sources, file, diags).read(*root);
}

std::string taskGraphToGraphviz(const TaskGraph& tg) {
  std::string out = "digraph " + dotQuoted(tg.robot) + " {\n  rankdir=LR;\n  node [shape=box];\n";
  for (std::size_t t = 0; t < tg.tasks.size(); ++t) {
    const Task& task = tg.tasks[t];
    const char* shape = task.kind == TaskKind::Control ? "doubleoctagon" : task.kind == TaskKind::Service || task.kind == TaskKind::Sensing ? "box" : "ellipse";
    out += "  t" + std::to_string(t) + " [shape=" + shape + ", label=" + dotQuoted(task.name + "\n" + taskKindName(task.kind)) + "];\n";
  }
  std::map<std::uint32_t, const ScenarioChannel*> rates;
  for (const Scenario& s : tg.scenarios) {
    for (const ScenarioChannel& sc : s.channels) rates.try_emplace(sc.channel, &sc);
  }
  for (std::size_t c = 0; c < tg.channels.size(); ++c) {
    const TaskChannel& ch = tg.channels[c];
    std::string label;
    if (auto it = rates.find(static_cast<std::uint32_t>(c)); it != rates.end()) {
      label = std::to_string(it->second->production) + ":" + std::to_string(it->second->consumption);
      if (it->second->initialTokens != 0) label += " \xE2\x80\xA2" + std::to_string(it->second->initialTokens);
    }
    out += "  t" + std::to_string(ch.fromTask) + " -> t" + std::to_string(ch.toTask) + " [label=" + dotQuoted(label) +
           (ch.control ? ", color=gray40" : "") + "];\n";
  }
  std::map<std::string, std::size_t> groups;
  for (const RemotePort& r : tg.remotePorts) {
    auto [it, fresh] = groups.try_emplace(r.id, groups.size());
    if (fresh) out += "  g" + std::to_string(it->second) + " [shape=note, label=" + dotQuoted(r.id + "\n" + remoteKindName(r.kind)) + "];\n";
    const std::string task = "t" + std::to_string(r.task), group = "g" + std::to_string(it->second);
    out += "  " + (r.output ? task + " -> " + group : group + " -> " + task) + " [style=dashed, label=" + dotQuoted(r.port) + "];\n";
  }
  return out + "}\n";
}

}  // namespace semo::sdf
