// Teams, robots, service headers, modes, main blocks, events and mode reachability.
#include <algorithm>
#include <deque>

#include "elaborator.hpp"
#include "semo/semantics/elaborate.hpp"

namespace semo {

namespace model {

namespace {

std::int64_t largestMinimum(const MissionModel& m, const std::vector<Stmt>& body, int depth) {
  std::int64_t most = 1;
  if (depth > 32) return most;  // composites that call each other are refused by elaboration
  for (const Stmt& s : body) {
    if (s.kind == Stmt::Kind::CallGroupService && s.strategyService != kNone) most = std::max(most, m.serviceOf(s).minRobots);
    if (s.kind == Stmt::Kind::CallComposite && s.composite < m.services.size()) {
      most = std::max(most, largestMinimum(m, m.services[s.composite].body, depth + 1));
    }
    most = std::max({most, largestMinimum(m, s.thenBody, depth + 1), largestMinimum(m, s.elseBody, depth + 1)});
  }
  return most;
}

}  // namespace

std::int64_t MissionModel::armDemand(const GroupArm& arm) const { return largestMinimum(*this, arm.body, 0); }

bool MissionModel::keepsLeadership(Index block, Index mode) const {
  const GroupBlock& b = groupBlocks.at(block);
  if (!b.leader.keptAcrossModes) return false;
  const std::vector<PlanSetting>& settings = modes.at(mode).settings;
  return std::any_of(settings.begin(), settings.end(), [&](const PlanSetting& s) { return s.service == b.service; });
}

Index MissionModel::findTeam(const std::string& name) const {
  for (Index i = 0; i < teams.size(); ++i) {
    if (teams[i].name == name) return i;
  }
  return kNone;
}

Index MissionModel::findRobot(const std::string& name) const {
  for (Index i = 0; i < robots.size(); ++i) {
    if (robots[i].name == name) return i;
  }
  return kNone;
}

Index MissionModel::findService(Index team, const std::string& name) const {
  for (Index i = 0; i < services.size(); ++i) {
    if (services[i].team == team && services[i].name == name) return i;
  }
  return kNone;
}

Index MissionModel::findMode(Index team, const std::string& name) const {
  for (Index i = 0; i < modes.size(); ++i) {
    if (modes[i].team == team && modes[i].name == name) return i;
  }
  return kNone;
}

Index MissionModel::findTopic(Index owner, const std::string& var) const {
  for (Index i = 0; i < topics.size(); ++i) {
    if (topics[i].owner == owner && topics[i].var == var) return i;
  }
  return kNone;
}

}  // namespace model

namespace detail {

Index eventIndex(model::Team& team, const std::string& name) {
  for (Index i = 0; i < team.events.size(); ++i) {
    if (team.events[i].name == name) return i;
  }
  team.events.push_back({name, {}, {}, {}});
  return static_cast<Index>(team.events.size() - 1);
}

std::string withHint(std::string message, const std::string& name, const std::vector<std::string>& candidates) {
  std::string hint = suggestClosest(name, candidates);
  return hint.empty() ? message : message + "; " + hint;
}

std::vector<std::string> Elaborator::teamNames() const {
  std::vector<std::string> names;
  for (const model::Team& t : m_.teams) names.push_back(t.name);
  return names;
}

std::vector<std::string> Elaborator::modeNames(Index team) const {
  std::vector<std::string> names;
  for (Index md : m_.teams[team].modes) names.push_back(m_.modes[md].name);
  return names;
}

Index Elaborator::teamOrError(const ast::Name& name, const std::string& role) {
  Index t = m_.findTeam(name.text);
  // With no team declared at all, "the mission declares no team" already says it.
  if (t == model::kNone && !ast_.teams.empty()) {
    diags_.error(name.range, withHint("undefined team '" + name.text + "'" + (role.empty() ? "" : " " + role), name.text,
                                      teamNames()));
  }
  return t;
}

void Elaborator::run() {
  declareTeams();
  declareServices();
  for (Index s = 0; s < m_.services.size(); ++s) collectTopics(serviceAst_[s]->body, m_.services[s].team);
  lowerServices();
  declareModes();
  declareMains();
  checkRobotSets();
  for (const model::CompositeService& s : m_.services) {
    if (!s.used) {
      diags_.warning(s.at, "service '" + m_.teams[s.team].name + "." + s.plan + "." + s.name +
                               "' is never used: no mode sets it and no used service calls it");
    }
  }
  checkEvents();
  checkTopics();
  computeReachability();
  elaborateVerify();
  checkCrashBudgets();
  checkStrategyAgainstMission();
}

void Elaborator::declareTeams() {
  for (const ast::TeamDecl& decl : ast_.teams) {
    if (Index existing = m_.findTeam(decl.team.text); existing != model::kNone) {
      Diagnostic& d = diags_.error(decl.team.range, "team '" + decl.team.text + "' is declared twice");
      DiagnosticEngine::note(d, m_.teams[existing].declaredAt, "first declared here");
      continue;
    }
    auto teamIndex = static_cast<Index>(m_.teams.size());
    model::Team team;
    team.name = decl.team.text;
    team.declaredAt = decl.team.range;
    for (const ast::RobotDecl& r : decl.robots) {
      if (m_.catalog.find(r.type.text) == nullptr) {
        std::string message = "unknown robot type '" + r.type.text + "'";
        Diagnostic& d = diags_.error(r.type.range, withHint(message, r.type.text, m_.catalog.typeNames()));
        if (m_.catalog.types().empty()) {
          DiagnosticEngine::note(d, {}, "the robot catalog is empty: the strategy names no <robot> URDF file");
        }
      }
      std::int64_t count = r.count.value_or(1);
      if (static_cast<std::int64_t>(m_.robots.size()) + count > kMaxRobots) {
        diags_.error(r.count ? r.countRange : r.name.range,
                     "too many robots: a mission may declare at most " + std::to_string(kMaxRobots));
        continue;
      }
      for (std::int64_t i = 0; i < count; ++i) {
        std::string name = r.count ? r.name.text + "_" + std::to_string(i) : r.name.text;
        auto robotIndex = static_cast<Index>(m_.robots.size());
        if (auto [it, added] = robotByName_.emplace(name, robotIndex); !added) {
          Diagnostic& d = diags_.error(r.name.range, "robot '" + name + "' is declared twice");
          DiagnosticEngine::note(d, m_.robots[it->second].declaredAt, "first declared here");
          break;
        }
        m_.robots.push_back({name, teamIndex, r.type.text, static_cast<Index>(team.robots.size()), r.name.range});
        team.robots.push_back(robotIndex);
      }
    }
    m_.teams.push_back(std::move(team));
  }
  if (ast_.teams.empty()) {
    SourceRange at = !ast_.services.empty() ? ast_.services.front().range
                     : !ast_.modes.empty()  ? ast_.modes.front().team.range
                     : !ast_.mains.empty()  ? ast_.mains.front().range
                                            : SourceRange{{ast_.file, 1, 1}, 1};
    diags_.error(at, "the mission declares no team: start it with 'Team: RobotType robot'");
  }
}

void Elaborator::declareServices() {
  for (const ast::Service& s : ast_.services) {
    Index team = teamOrError(s.team, "in service definition");
    if (team == model::kNone) continue;
    if (Index existing = m_.findService(team, s.name.text); existing != model::kNone) {
      Diagnostic& d = diags_.error(s.name.range, "service '" + s.name.text + "' of team '" + s.team.text +
                                                     "' is defined twice (service names are unique across a team's plans)");
      DiagnosticEngine::note(d, m_.services[existing].at, "first defined here");
      continue;
    }
    model::CompositeService service;
    service.name = s.name.text;
    service.plan = s.plan.text;
    service.team = team;
    service.at = s.name.range;
    model::Team& t = m_.teams[team];
    if (std::find(t.plans.begin(), t.plans.end(), s.plan.text) == t.plans.end()) t.plans.push_back(s.plan.text);
    t.services.push_back(static_cast<Index>(m_.services.size()));
    m_.services.push_back(std::move(service));
    serviceAst_.push_back(&s);
  }
}

void Elaborator::declareModes() {
  for (const ast::ModeDef& def : ast_.modes) {
    Index team = teamOrError(def.team, "in mode definition");
    if (team == model::kNone) continue;
    if (Index existing = m_.findMode(team, def.mode.text); existing != model::kNone) {
      Diagnostic& d = diags_.error(def.mode.range, "mode '" + def.mode.text + "' of team '" + def.team.text + "' is defined twice");
      DiagnosticEngine::note(d, m_.modes[existing].at, "first defined here");
      continue;
    }
    model::Team& t = m_.teams[team];
    model::Mode mode;
    mode.name = def.mode.text;
    mode.team = team;
    mode.at = def.mode.range;
    for (const ast::SetItem& item : def.sets) {
      auto plan = std::find(t.plans.begin(), t.plans.end(), item.plan.text);
      Index service = m_.findService(team, item.service.text);
      if (service == model::kNone) {
        std::vector<std::string> names;
        for (Index s : t.services) names.push_back(m_.services[s].name);
        std::string message = "undefined service '" + item.service.text + "' in team '" + t.name + "'";
        Diagnostic& d = diags_.error(item.service.range, withHint(message, item.service.text, names));
        for (const model::CompositeService& other : m_.services) {
          if (other.name == item.service.text && other.team != team) {
            DiagnosticEngine::note(d, other.at, "a service of that name belongs to team '" + m_.teams[other.team].name +
                                                    "'; a mode can only set its own team's services");
            break;
          }
        }
        continue;
      }
      if (plan == t.plans.end()) {
        diags_.error(item.plan.range, withHint("undefined plan '" + item.plan.text + "' of team '" + t.name + "'",
                                               item.plan.text, t.plans));
        continue;
      }
      if (m_.services[service].plan != item.plan.text) {
        Diagnostic& d = diags_.error(item.service.range, "service '" + item.service.text + "' belongs to plan '" +
                                                             m_.services[service].plan + "', not '" + item.plan.text + "'");
        DiagnosticEngine::note(d, m_.services[service].at, "defined here");
        continue;
      }
      auto planIndex = static_cast<Index>(plan - t.plans.begin());
      auto twice = std::find_if(mode.settings.begin(), mode.settings.end(),
                                [&](const model::PlanSetting& p) { return p.plan == planIndex; });
      if (twice != mode.settings.end()) {
        Diagnostic& d = diags_.error(item.plan.range, "plan '" + item.plan.text + "' is set twice in mode '" + mode.name + "'");
        DiagnosticEngine::note(d, twice->at, "first set here");
        continue;
      }
      mode.settings.push_back({planIndex, service, item.range});
    }
    t.modes.push_back(static_cast<Index>(m_.modes.size()));
    m_.modes.push_back(std::move(mode));
  }
}

void Elaborator::declareMains() {
  std::vector<const ast::MainDef*> mainOf(m_.teams.size(), nullptr);
  for (const ast::MainDef& main : ast_.mains) {
    Index team = teamOrError(main.team, "in main block");
    if (team == model::kNone) continue;
    if (mainOf[team] != nullptr) {
      Diagnostic& d = diags_.error(main.team.range, "team '" + main.team.text + "' has two main blocks");
      DiagnosticEngine::note(d, mainOf[team]->team.range, "first main block here");
      continue;
    }
    mainOf[team] = &main;
    model::Team& t = m_.teams[team];
    std::vector<const ast::Case*> caseOf(m_.modes.size(), nullptr);
    for (const ast::Case& c : main.cases) {
      Index mode = m_.findMode(team, c.mode.text);
      if (mode == model::kNone) {
        diags_.error(c.mode.range, withHint("main case for undefined mode '" + c.mode.text + "' of team '" + t.name + "'",
                                            c.mode.text, modeNames(team)));
        continue;
      }
      if (caseOf[mode] != nullptr) {
        Diagnostic& d = diags_.error(c.mode.range, "mode '" + c.mode.text + "' has two cases in main");
        DiagnosticEngine::note(d, caseOf[mode]->mode.range, "first case here");
        continue;
      }
      caseOf[mode] = &c;
      if (t.initialMode == model::kNone) t.initialMode = mode;
      bool sawDefault = false;
      for (const ast::Transition& tr : c.transitions) {
        if (!tr.isDefault) {
          // Record the catch even when the target is wrong, so the event is not also reported unused.
          t.events[eventIndex(t, tr.event.text)].caughtAt.push_back(tr.event.range);
        }
        Index target = m_.findMode(team, tr.target.text);
        if (target == model::kNone) {
          diags_.error(tr.target.range, withHint("undefined mode '" + tr.target.text + "' of team '" + t.name + "'",
                                                 tr.target.text, modeNames(team)));
          continue;
        }
        model::Transition transition;
        transition.isDefault = tr.isDefault;
        transition.target = target;
        transition.at = tr.range;
        if (tr.isDefault) {
          if (sawDefault) {
            diags_.error(tr.range, "mode '" + c.mode.text + "' has two default transitions");
            continue;
          }
          sawDefault = true;
        } else {
          transition.event = eventIndex(t, tr.event.text);
          bool twice = false;
          for (const model::Transition& other : m_.modes[mode].transitions) {
            if (!other.isDefault && other.event == transition.event) {
              Diagnostic& d = diags_.error(tr.event.range, "event '" + tr.event.text + "' is caught twice in mode '" +
                                                               c.mode.text + "'");
              DiagnosticEngine::note(d, other.at, "first caught here");
              twice = true;
            }
          }
          if (twice) continue;
        }
        m_.modes[mode].transitions.push_back(transition);
      }
    }
  }
  for (Index team = 0; team < m_.teams.size(); ++team) {
    const model::Team& t = m_.teams[team];
    if (mainOf[team] == nullptr && (!t.services.empty() || !t.modes.empty())) {
      diags_.error(t.declaredAt, "team '" + t.name + "' has services or modes but no main block ('" + t.name +
                                     ".main { case (MODE): ... }')");
    }
  }
}

void Elaborator::checkEvents() {
  for (model::Team& t : m_.teams) {
    for (model::Event& e : t.events) {
      e.delivery = m_.strategy.eventDelivery(e.name);
      if (e.caughtAt.empty()) {
        for (const SourceRange& at : e.thrownAt) {
          diags_.warning(at, "event '" + e.name + "' is thrown but never caught by team '" + t.name + "'");
        }
      }
      if (e.thrownAt.empty()) {
        for (const SourceRange& at : e.caughtAt) {
          diags_.warning(at, "event '" + e.name + "' is caught but never thrown in team '" + t.name + "'");
        }
      }
    }
  }
}

void Elaborator::computeReachability() {
  for (const model::Team& t : m_.teams) {
    if (t.initialMode == model::kNone) continue;
    std::deque<Index> queue{t.initialMode};
    m_.modes[t.initialMode].reachable = true;
    while (!queue.empty()) {
      Index mode = queue.front();
      queue.pop_front();
      for (const model::Transition& tr : m_.modes[mode].transitions) {
        if (!m_.modes[tr.target].reachable) {
          m_.modes[tr.target].reachable = true;
          queue.push_back(tr.target);
        }
      }
    }
    for (Index md : t.modes) {
      if (!m_.modes[md].reachable) {
        diags_.warning(m_.modes[md].at, "mode '" + m_.modes[md].name + "' is unreachable from the initial mode '" +
                                            m_.modes[t.initialMode].name + "'");
      }
    }
  }
}

void Elaborator::checkStrategyAgainstMission() {
  auto checkImplementations = [&](const std::vector<strategy::Implementation>& impls) {
    for (const strategy::Implementation& impl : impls) {
      if (m_.catalog.find(impl.robotType) != nullptr) continue;
      diags_.error(impl.at, withHint("implementation for unknown robot type '" + impl.robotType + "'", impl.robotType,
                                     m_.catalog.typeNames()));
    }
  };
  for (const strategy::Service& s : m_.strategy.services) checkImplementations(s.implementations);
  for (const strategy::Value& v : m_.strategy.values) checkImplementations(v.implementations);
  for (const strategy::EventOverride& o : m_.strategy.eventOverrides) {
    bool thrown = std::any_of(m_.teams.begin(), m_.teams.end(), [&](const model::Team& t) {
      return std::any_of(t.events.begin(), t.events.end(),
                         [&](const model::Event& e) { return e.name == o.name && !e.thrownAt.empty(); });
    });
    if (!thrown) diags_.warning(o.delivery.at, "event '" + o.name + "' is configured but the mission never throws it");
  }
  for (const strategy::LeaderSelection& ls : m_.strategy.leaderSelections) {
    Index team = m_.findTeam(ls.team);
    Index service = team == model::kNone ? model::kNone : m_.findService(team, ls.service);
    if (service == model::kNone || m_.services[service].plan != ls.plan) {
      // A warning, not an error: one strategy may serve several missions of the same robots.
      diags_.warning(ls.at, "leader selection names service '" + ls.team + "." + ls.plan + "." + ls.service +
                                "', which the mission does not define");
      continue;
    }
    bool hasLeader = std::any_of(m_.groupBlocks.begin(), m_.groupBlocks.end(), [&](const model::GroupBlock& b) {
      return b.service == service && b.isLeaderBlock;
    });
    if (!hasLeader) {
      diags_.warning(ls.at, "leader selection for '" + ls.team + "." + ls.plan + "." + ls.service +
                                "' is unused: that service has no 'leader (...)' block");
    }
  }
}

}  // namespace detail

model::MissionModel elaborate(const ast::Mission& mission, strategy::Strategy strategy, RobotCatalog catalog,
                              DiagnosticEngine& diags) {
  model::MissionModel m;
  m.strategy = std::move(strategy);
  m.catalog = std::move(catalog);
  detail::Elaborator(mission, m, diags).run();
  return m;
}

}  // namespace semo
