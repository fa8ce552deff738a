// Task-graph generation from the elaborated mission and its strategy (task_graph.hpp).
#include <algorithm>
#include <functional>
#include <map>
#include <set>

#include "semo/sdf/consistency.hpp"
#include "semo/sdf/task_graph.hpp"

namespace semo::sdf {

const char* taskKindName(TaskKind k) {
  switch (k) {
    case TaskKind::Service: return "service";
    case TaskKind::Sensing: return "sensing";
    case TaskKind::Control: return "control";
    case TaskKind::Communication: return "communication";
    case TaskKind::Knowledge: return "knowledge";
    case TaskKind::LeaderElection: return "leader-election";
  }
  return "service";
}

namespace {

using model::Index;

// Generated tasks have no measured execution time in the strategy; a nominal 1 ms keeps every
// cycle's duration positive (a cycle of zero-time firings has no finite period).
constexpr std::int64_t kGeneratedTaskMicros = 1000;
constexpr std::size_t kMaxScenariosPerMode = 256;

// What one robot does in one plan of one mode.
struct PlanUse {
  Index plan = model::kNone;       // into the team's plans
  std::vector<std::string> calls;  // primitive and group services, in order, without repeats
};

// What one robot does in one mode.
struct ModeUse {
  std::vector<PlanUse> plans;
  std::set<std::string> valuesRead;                  // "Team.var" of sensed values
  std::set<Index> topicsOut, topicsIn;               // into MissionModel::topics
  std::set<std::string> knowledgeRead;               // "Team.var" of knowledge values
  bool throws = false, catches = false;
  std::set<bool> throwDelivery;                      // reliable?
  std::vector<Index> leaderBlocks;                   // blocks the robot may lead
};

class Generator {
 public:
  Generator(const model::MissionModel& m, DiagnosticEngine& diags) : m_(m), diags_(diags) {}

  std::optional<std::vector<TaskGraph>> run() {
    std::vector<TaskGraph> out;
    for (Index r = 0; r < m_.robots.size(); ++r) out.push_back(robotGraph(r));
    if (diags_.hasErrors()) return std::nullopt;
    return out;
  }

 private:
  const model::MissionModel& m_;
  DiagnosticEngine& diags_;

  // ---- what the robot runs
  void visitExpr(const model::Expr& e, ModeUse& use) {
    if (e.kind != model::Expr::Kind::Value) return;
    const std::string name = m_.teams[e.owner].name + "." + e.var;
    if (e.valueKind == model::ValueKind::Sensed) use.valuesRead.insert(name);
    if (e.valueKind == model::ValueKind::Knowledge) use.knowledgeRead.insert(name);
  }

  void visitCond(const model::Cond* c, ModeUse& use) {
    if (c == nullptr) return;
    visitExpr(c->lhs, use);
    visitExpr(c->rhs, use);
    visitCond(c->left.get(), use);
    visitCond(c->right.get(), use);
  }

  void visitBody(const std::vector<model::Stmt>& body, Index robot, ModeUse& use, PlanUse& plan, std::vector<Index>& stack) {
    for (const model::Stmt& s : body) {
      switch (s.kind) {
        case model::Stmt::Kind::CallPrimitive:
        case model::Stmt::Kind::CallGroupService:
          if (std::find(plan.calls.begin(), plan.calls.end(), s.service) == plan.calls.end()) plan.calls.push_back(s.service);
          for (const model::Expr& a : s.args) visitExpr(a, use);
          break;
        case model::Stmt::Kind::CallComposite:
          if (s.composite != model::kNone && std::find(stack.begin(), stack.end(), s.composite) == stack.end()) {
            stack.push_back(s.composite);
            visitComposite(s.composite, robot, use, plan, stack);
            stack.pop_back();
          }
          break;
        case model::Stmt::Kind::Throw: {
          use.throws = true;
          const model::Team& team = m_.teams[m_.robots[robot].team];
          if (s.event != model::kNone && s.event < team.events.size()) use.throwDelivery.insert(team.events[s.event].delivery.reliable);
          break;
        }
        case model::Stmt::Kind::If:
          visitCond(s.cond.get(), use);
          visitBody(s.thenBody, robot, use, plan, stack);
          visitBody(s.elseBody, robot, use, plan, stack);
          break;
        case model::Stmt::Kind::Publish:
        case model::Stmt::Kind::Send:
          if (s.topic != model::kNone) use.topicsOut.insert(s.topic);
          visitExpr(s.value, use);
          break;
        case model::Stmt::Kind::Subscribe:
        case model::Stmt::Kind::Receive:
          if (s.topic != model::kNone) use.topicsIn.insert(s.topic);
          break;
        case model::Stmt::Kind::Groups: {
          const model::GroupBlock& block = m_.groupBlocks[s.groupBlock];
          for (const model::GroupArm& arm : block.arms) {
            if (std::find(arm.candidates.begin(), arm.candidates.end(), robot) == arm.candidates.end()) continue;
            if (arm.kind == model::GroupArm::Kind::Leader &&
                std::find(use.leaderBlocks.begin(), use.leaderBlocks.end(), s.groupBlock) == use.leaderBlocks.end()) {
              use.leaderBlocks.push_back(s.groupBlock);
            }
            visitBody(arm.body, robot, use, plan, stack);
          }
          break;
        }
        case model::Stmt::Kind::Loop:
        case model::Stmt::Kind::Wait:
          break;  // timers of the control task
      }
    }
  }

  void visitComposite(Index service, Index robot, ModeUse& use, PlanUse& plan, std::vector<Index>& stack) {
    const model::CompositeService& cs = m_.services[service];
    if (cs.repeat && cs.repeat->cond) visitCond(cs.repeat->cond.get(), use);
    visitBody(cs.body, robot, use, plan, stack);
  }

  ModeUse modeUse(const model::Mode& mode, Index robot) {
    ModeUse use;
    for (const model::PlanSetting& setting : mode.settings) {
      PlanUse plan;
      plan.plan = setting.plan;
      std::vector<Index> stack{setting.service};
      visitComposite(setting.service, robot, use, plan, stack);
      use.plans.push_back(std::move(plan));
    }
    for (const model::Transition& t : mode.transitions) use.catches = use.catches || !t.isDefault;
    return use;
  }

  // ---- building the graph
  struct Builder {
    TaskGraph g;
    std::map<std::string, std::uint32_t> taskByName;
    std::map<std::string, std::uint32_t> channelByKey;  // "from.port>to.port"
  };

  std::uint32_t addTask(Builder& b, Task task, const std::string& origin) {
    auto [it, fresh] = b.taskByName.try_emplace(task.name, static_cast<std::uint32_t>(b.g.tasks.size()));
    if (fresh) {
      task.origins = {origin};
      b.g.tasks.push_back(std::move(task));
      return it->second;
    }
    Task& existing = b.g.tasks[it->second];
    if (std::find(existing.origins.begin(), existing.origins.end(), origin) == existing.origins.end()) existing.origins.push_back(origin);
    if (!samePorts(existing, task)) {
      Diagnostic& d = diags_.error(task.at, "task '" + task.name + "' of robot type '" + b.g.robotType +
                                                "' is declared with other ports or rates than in '" + existing.origins.front() + "'");
      DiagnosticEngine::note(d, existing.at, "declared here first");
    }
    return it->second;
  }

  static bool samePorts(const Task& a, const Task& b) {
    if (a.ports.size() != b.ports.size()) return false;
    for (const TaskPort& p : a.ports) {
      auto q = std::find_if(b.ports.begin(), b.ports.end(), [&](const TaskPort& x) { return x.name == p.name; });
      if (q == b.ports.end() || q->input != p.input || q->rate != p.rate) return false;
    }
    return true;
  }

  std::uint32_t addChannel(Builder& b, std::uint32_t from, const std::string& fromPort, std::uint32_t to, const std::string& toPort,
                           std::int64_t initial, bool control) {
    const std::string key = b.g.tasks[from].name + "." + fromPort + ">" + b.g.tasks[to].name + "." + toPort;
    auto [it, fresh] = b.channelByKey.try_emplace(key, static_cast<std::uint32_t>(b.g.channels.size()));
    if (fresh) {
      TaskChannel c;
      c.name = b.g.tasks[from].name + "." + fromPort + "->" + b.g.tasks[to].name + "." + toPort;
      c.fromTask = from;
      c.toTask = to;
      c.fromPort = fromPort;
      c.toPort = toPort;
      c.initialTokens = initial;
      c.control = control;
      b.g.channels.push_back(std::move(c));
    }
    return it->second;
  }

  std::uint32_t controlPort(Builder& b, const std::string& name, bool input) {
    Task& control = b.g.tasks[0];
    if (std::none_of(control.ports.begin(), control.ports.end(), [&](const TaskPort& p) { return p.name == name; })) {
      control.ports.push_back({name, input, 0});
    }
    return 0;
  }

  // An implementation's tasks and channels, its interface ports wired to the control task. Returns
  // the channels an activation of it uses.
  std::vector<std::uint32_t> addImplementation(Builder& b, const strategy::Implementation& impl, const std::string& origin,
                                               TaskKind kind) {
    std::vector<std::uint32_t> used;
    std::vector<std::uint32_t> ids;
    for (const strategy::Task& t : impl.tasks) {
      Task task;
      task.name = t.name;
      task.kind = kind;
      task.execMicros = t.execMicros;
      task.at = t.at;
      for (const strategy::Port& p : t.ports) task.ports.push_back({p.name, p.input, p.rate});
      ids.push_back(addTask(b, std::move(task), origin));
    }
    std::set<std::pair<std::string, std::string>> connected;
    for (const strategy::Channel& c : impl.channels) {
      auto find = [&](const std::string& name) {
        for (std::size_t i = 0; i < impl.tasks.size(); ++i) {
          if (impl.tasks[i].name == name) return ids[i];
        }
        return std::uint32_t{0};  // the strategy reader guarantees the task exists
      };
      used.push_back(addChannel(b, find(c.fromTask), c.fromPort, find(c.toTask), c.toPort, c.initialTokens, false));
      connected.insert({c.fromTask, c.fromPort});
      connected.insert({c.toTask, c.toPort});
    }
    for (std::size_t i = 0; i < impl.tasks.size(); ++i) {
      for (const strategy::Port& p : impl.tasks[i].ports) {
        if (connected.count({impl.tasks[i].name, p.name}) != 0) continue;
        const std::string controlSide = impl.tasks[i].name + "." + p.name;
        controlPort(b, controlSide, !p.input);
        used.push_back(p.input ? addChannel(b, 0, controlSide, ids[i], p.name, 0, true)
                               : addChannel(b, ids[i], p.name, 0, controlSide, 0, true));
      }
    }
    return used;
  }

  // A generated task with one port to or from the control task and one remote port.
  std::vector<std::uint32_t> addCommunication(Builder& b, const std::string& name, TaskKind kind, const std::string& origin,
                                              bool fromControl, bool toControl, std::vector<RemotePort> remotes) {
    Task task;
    task.name = name;
    task.kind = kind;
    task.execMicros = kGeneratedTaskMicros;
    if (fromControl) task.ports.push_back({"command", true, 1});
    if (toControl) task.ports.push_back({"status", false, 1});
    for (const RemotePort& r : remotes) task.ports.push_back({r.port, !r.output, 1});
    const bool fresh = b.taskByName.count(name) == 0;
    const std::uint32_t id = addTask(b, std::move(task), origin);
    if (fresh) {
      for (RemotePort& r : remotes) {
        r.task = id;
        b.g.remotePorts.push_back(std::move(r));
      }
    }
    std::vector<std::uint32_t> used;
    if (fromControl) {
      controlPort(b, name + ".command", false);
      used.push_back(addChannel(b, 0, name + ".command", id, "command", 0, true));
    }
    if (toControl) {
      controlPort(b, name + ".status", true);
      used.push_back(addChannel(b, id, "status", 0, name + ".status", 0, true));
    }
    return used;
  }

  std::vector<std::string> teamRobots(Index team, Index except = model::kNone) const {
    std::vector<std::string> out;
    for (Index r : m_.teams[team].robots) {
      if (r != except) out.push_back(m_.robots[r].name);
    }
    return out;
  }

  struct Activation {
    std::vector<std::uint32_t> channels;
  };

  TaskGraph robotGraph(Index robot) {
    const model::Robot& rb = m_.robots[robot];
    Builder b;
    b.g.robot = rb.name;
    b.g.robotType = rb.type;
    b.g.team = m_.teams[rb.team].name;
    Task control;
    control.name = "control";
    control.kind = TaskKind::Control;
    control.execMicros = kGeneratedTaskMicros;
    addTask(b, std::move(control), "modes of " + b.g.team);

    std::map<std::string, Activation> byService, byValue, byComm;
    auto serviceActivation = [&](const std::string& name) -> const Activation& {
      auto it = byService.find(name);
      if (it != byService.end()) return it->second;
      Activation a;
      if (const strategy::Service* sv = m_.strategy.service(name)) {
        if (const strategy::Implementation* impl = sv->implementationFor(rb.type)) {
          a.channels = addImplementation(b, *impl, name, TaskKind::Service);
        }
        for (const strategy::Knowledge& k : sv->knowledge) {
          RemotePort port{0, "share", true, RemotePort::Kind::Multicast, "knowledge:" + name + "." + k.name, 1, teamRobots(rb.team, robot)};
          RemotePort in = port;
          in.port = "gossip";
          in.output = false;
          auto used = addCommunication(b, "knowledge_" + k.name, TaskKind::Knowledge, name, true, true, {port, in});
          a.channels.insert(a.channels.end(), used.begin(), used.end());
        }
      }
      return byService.emplace(name, std::move(a)).first->second;
    };
    auto valueActivation = [&](const std::string& name) -> const Activation& {
      auto it = byValue.find(name);
      if (it != byValue.end()) return it->second;
      Activation a;
      const auto dot = name.find('.');
      if (const strategy::Value* v = m_.strategy.value(name.substr(0, dot), name.substr(dot + 1))) {
        if (const strategy::Implementation* impl = v->implementationFor(rb.type)) a.channels = addImplementation(b, *impl, name, TaskKind::Sensing);
      }
      return byValue.emplace(name, std::move(a)).first->second;
    };
    auto commActivation = [&](const std::string& key, const std::function<std::vector<std::uint32_t>()>& make) -> const Activation& {
      auto it = byComm.find(key);
      if (it != byComm.end()) return it->second;
      return byComm.emplace(key, Activation{make()}).first->second;
    };

    const model::Team& team = m_.teams[rb.team];
    for (Index modeIndex : team.modes) {
      const model::Mode& mode = m_.modes[modeIndex];
      if (!mode.reachable) continue;
      ModeUse use = modeUse(mode, robot);
      // Channels shared by every scenario of the mode.
      std::vector<std::uint32_t> common;
      auto take = [&](const Activation& a) { common.insert(common.end(), a.channels.begin(), a.channels.end()); };
      for (const std::string& v : use.valuesRead) take(valueActivation(v));
      for (Index t : use.topicsOut) {
        const model::Topic& topic = m_.topics[t];
        const std::string id = m_.teams[topic.owner].name + "." + topic.var;
        take(commActivation("out:" + id, [&] {
          std::vector<std::string> peers;
          for (const model::Robot& other : m_.robots) {
            if (&other != &rb) peers.push_back(other.name);
          }
          RemotePort port{0, "out", true, topic.reliable ? RemotePort::Kind::PointToPoint : RemotePort::Kind::Multicast,
                          "topic:" + id, topic.buffer, peers};
          return addCommunication(b, (topic.reliable ? "send_" : "publish_") + m_.teams[topic.owner].name + "_" + topic.var,
                                  TaskKind::Communication, "topic " + id, true, false, {port});
        }));
      }
      for (Index t : use.topicsIn) {
        const model::Topic& topic = m_.topics[t];
        const std::string id = m_.teams[topic.owner].name + "." + topic.var;
        take(commActivation("in:" + id, [&] {
          RemotePort port{0, "in", false, topic.reliable ? RemotePort::Kind::PointToPoint : RemotePort::Kind::Multicast,
                          "topic:" + id, topic.buffer, {}};
          return addCommunication(b, (topic.reliable ? "receive_" : "subscribe_") + m_.teams[topic.owner].name + "_" + topic.var,
                                  TaskKind::Communication, "topic " + id, false, true, {port});
        }));
      }
      if (use.throws) {
        take(commActivation("events-out", [&] {
          std::vector<RemotePort> ports;
          for (bool reliable : use.throwDelivery) {
            ports.push_back({0, reliable ? "reliable" : "broadcast", true,
                             reliable ? RemotePort::Kind::PointToPoint : RemotePort::Kind::Multicast, "events:" + team.name, 1,
                             teamRobots(rb.team, robot)});
          }
          return addCommunication(b, "event_out", TaskKind::Communication, "events of " + team.name, true, false, ports);
        }));
      }
      if (use.catches) {
        take(commActivation("events-in", [&] {
          RemotePort port{0, "in", false, RemotePort::Kind::Multicast, "events:" + team.name, 1, {}};
          return addCommunication(b, "event_in", TaskKind::Communication, "events of " + team.name, false, true, {port});
        }));
      }
      for (Index blockIndex : use.leaderBlocks) {
        const model::GroupBlock& block = m_.groupBlocks[blockIndex];
        const model::CompositeService& cs = m_.services[block.service];
        const std::string id = team.name + "." + cs.plan + "." + cs.name;
        take(commActivation("leader:" + id, [&] {
          RemotePort out{0, "heartbeat_out", true, RemotePort::Kind::Multicast, "leader:" + id, 1, teamRobots(rb.team, robot)};
          RemotePort in{0, "heartbeat_in", false, RemotePort::Kind::Multicast, "leader:" + id, 1, {}};
          return addCommunication(b, "leader_" + cs.plan + "_" + cs.name, TaskKind::LeaderElection, "leader of " + id, false, true,
                                  {out, in});
        }));
      }
      // Scenarios: one service per plan (plans without calls contribute nothing).
      std::vector<std::vector<std::string>> choices;
      std::vector<std::uint32_t> choicePlans;
      for (const PlanUse& p : use.plans) {
        if (!p.calls.empty()) choices.push_back(p.calls), choicePlans.push_back(static_cast<std::uint32_t>(p.plan));
      }
      for (const auto& cs : choices) {
        for (const std::string& s : cs) serviceActivation(s);
      }
      std::size_t count = 1;
      for (const auto& c : choices) count = std::min(count * c.size(), kMaxScenariosPerMode + 1);
      if (count > kMaxScenariosPerMode) {
        diags_.error(mode.at, "mode '" + mode.name + "' gives robot '" + rb.name + "' more than " +
                                  std::to_string(kMaxScenariosPerMode) + " scenarios (combinations of the services its plans call)");
        continue;
      }
      std::vector<std::size_t> pick(choices.size(), 0);
      for (std::size_t n = 0; n < count; ++n) {
        Scenario s;
        s.mode = mode.name;
        s.name = mode.name;
        std::vector<std::uint32_t> channels = common;
        bool several = false;
        for (std::size_t p = 0; p < choices.size(); ++p) {
          const std::string& service = choices[p][pick[p]];
          several = several || choices[p].size() > 1;
          s.services.push_back(service);
          s.plans.push_back(choicePlans[p]);
          const Activation& a = byService.at(service);
          channels.insert(channels.end(), a.channels.begin(), a.channels.end());
        }
        if (several) {
          std::string picked;
          for (const std::string& sv : s.services) picked += (picked.empty() ? "" : ",") + sv;
          s.name += "[" + picked + "]";
        }
        finishScenario(b, s, channels, mode);
        b.g.scenarios.push_back(std::move(s));
        for (std::size_t p = 0; p < choices.size(); ++p) {  // next combination
          if (++pick[p] < choices[p].size()) break;
          pick[p] = 0;
        }
      }
    }
    return std::move(b.g);
  }

  // Active tasks and channels, and the control task's rates from the repetition vector. An input
  // port that one active implementation connects and another leaves to the control task takes the
  // data channel (the control task would be a second feeder); an output port left to the control
  // task by an active implementation feeds it as well as any data channel (SDF fan-out: each
  // consumer gets every token).
  void finishScenario(Builder& b, Scenario& s, std::vector<std::uint32_t> channels, const model::Mode& mode) {
    std::sort(channels.begin(), channels.end());
    channels.erase(std::unique(channels.begin(), channels.end()), channels.end());
    const TaskGraph& g = b.g;
    std::set<std::pair<std::uint32_t, std::string>> dataInputs;
    for (std::uint32_t c : channels) {
      if (!g.channels[c].control) dataInputs.insert({g.channels[c].toTask, g.channels[c].toPort});
    }
    std::vector<std::uint32_t> kept;
    std::map<std::pair<std::uint32_t, std::string>, std::uint32_t> feeder;
    for (std::uint32_t c : channels) {
      const TaskChannel& ch = g.channels[c];
      if (ch.control && ch.fromTask == 0 && dataInputs.count({ch.toTask, ch.toPort}) != 0) continue;
      if (ch.toTask != 0) {
        auto [it, fresh] = feeder.try_emplace({ch.toTask, ch.toPort}, c);
        if (!fresh) {
          Diagnostic& d = diags_.error(mode.at, "in mode '" + mode.name + "', robot '" + g.robot + "' would feed input port '" +
                                                    g.tasks[ch.toTask].name + "." + ch.toPort + "' from two tasks at once ('" +
                                                    g.tasks[g.channels[it->second].fromTask].name + "' and '" +
                                                    g.tasks[ch.fromTask].name + "')");
          DiagnosticEngine::note(d, g.tasks[ch.toTask].at, "the task is declared here");
          continue;
        }
      }
      kept.push_back(c);
    }
    std::set<std::uint32_t> active{0};
    for (std::uint32_t c : kept) {
      active.insert(g.channels[c].fromTask);
      active.insert(g.channels[c].toTask);
    }
    s.tasks.assign(active.begin(), active.end());
    // Repetition counts of the tasks without the control task (per connected component).
    Graph data;
    std::map<std::uint32_t, ActorId> actorOf;
    for (std::uint32_t t : s.tasks) {
      if (t == 0) continue;
      actorOf[t] = static_cast<ActorId>(data.actors.size());
      data.actors.push_back({g.tasks[t].name, g.tasks[t].execMicros, {}});
    }
    auto rateOf = [&](std::uint32_t task, const std::string& port) {
      for (const TaskPort& p : g.tasks[task].ports) {
        if (p.name == port) return p.rate;
      }
      return std::int64_t{1};
    };
    for (std::uint32_t c : kept) {
      const TaskChannel& ch = g.channels[c];
      if (ch.control) continue;
      data.channels.push_back({ch.name, actorOf[ch.fromTask], actorOf[ch.toTask], rateOf(ch.fromTask, ch.fromPort),
                               rateOf(ch.toTask, ch.toPort), ch.initialTokens, {}});
    }
    RepetitionVector q = repetitionVector(data);
    for (std::uint32_t c : kept) {
      const TaskChannel& ch = g.channels[c];
      ScenarioChannel sc{c, 1, 1, ch.initialTokens};
      if (!ch.control) {
        sc.production = rateOf(ch.fromTask, ch.fromPort);
        sc.consumption = rateOf(ch.toTask, ch.toPort);
      } else {
        const std::uint32_t task = ch.fromTask == 0 ? ch.toTask : ch.fromTask;
        const std::string& port = ch.fromTask == 0 ? ch.toPort : ch.fromPort;
        const std::int64_t firings = q.consistent() ? q.firings[actorOf[task]] : 1;
        const std::int64_t perIteration = firings * rateOf(task, port);
        if (ch.fromTask == 0) {
          sc.production = perIteration;
          sc.consumption = rateOf(task, port);
          sc.initialTokens = perIteration;
        } else {
          sc.production = rateOf(task, port);
          sc.consumption = perIteration;
        }
      }
      s.channels.push_back(sc);
    }
  }
};

}  // namespace

std::optional<std::vector<TaskGraph>> generateTaskGraphs(const model::MissionModel& m, DiagnosticEngine& diags) {
  return Generator(m, diags).run();
}

Graph scenarioGraph(const TaskGraph& tg, const Scenario& s) {
  Graph g;
  g.name = tg.robot + ":" + s.name;
  std::vector<ActorId> actorOf(tg.tasks.size(), 0);
  for (std::uint32_t t : s.tasks) {
    actorOf[t] = static_cast<ActorId>(g.actors.size());
    g.actors.push_back({tg.tasks[t].name, tg.tasks[t].execMicros, tg.tasks[t].at});
  }
  for (const ScenarioChannel& sc : s.channels) {
    const TaskChannel& ch = tg.channels[sc.channel];
    g.channels.push_back({ch.name, actorOf[ch.fromTask], actorOf[ch.toTask], sc.production, sc.consumption, sc.initialTokens, {}});
  }
  for (std::uint32_t t : s.tasks) g.channels.push_back({tg.tasks[t].name + ".self", actorOf[t], actorOf[t], 1, 1, 1, {}});
  return g;
}

}  // namespace semo::sdf
