// The projection of a translated mission onto its robots: everything but the plan rows
// (project_rows.cpp). Every table entry comes from the elaborated mission's structure or from the
// lowering the translation recorded beside the IR; no rule is derived here a second time.
#include <algorithm>

#include "projector.hpp"

namespace semo::codegen {
namespace detail {

using RoleKind = lowering::VariableRole::Kind;
using MeaningKind = lowering::RuleMeaning::Kind;

runtime::MissionTables Projector::run() {
  out_.rules.reserve(t_.model.rules.size());
  for (const ir::Rule& r : t_.model.rules) {
    out_.rules.push_back({r.name, r.label, r.origin.text(), r.robot < 0 ? kNone : static_cast<Id>(r.robot)});
  }
  const lowering::LoweredAssumptions& a = t_.lowering.assumptions;
  out_.assumptions.losePublish = a.losePublish;
  out_.assumptions.loseEvents = a.loseEvents;
  out_.assumptions.loseKnowledge = a.loseKnowledge;
  out_.assumptions.loseHeartbeats = a.loseHeartbeats;
  out_.assumptions.lossBurst = static_cast<std::int32_t>(a.lossBurst);
  out_.assumptions.words = t_.model.assumptions;
  teams();
  topicsAndValues();
  knowledge();
  groupBlocks();
  robots();
  networkRules();
  abstraction();
  return std::move(out_);
}

Id Projector::teamModeIndex(model::Index mode) const {
  const std::vector<model::Index>& modes = m_.teams[m_.modes[mode].team].modes;
  return static_cast<Id>(std::find(modes.begin(), modes.end(), mode) - modes.begin());
}

Id Projector::knowledgeItem(model::Index team, const std::string& item) const {
  auto it = knowledgeIndex_.find({team, item});
  return it == knowledgeIndex_.end() ? kNone : it->second;
}

void Projector::teams() {
  for (model::Index t = 0; t < m_.teams.size(); ++t) {
    const model::Team& team = m_.teams[t];
    runtime::TeamTable out;
    out.name = team.name;
    out.robots.assign(team.robots.begin(), team.robots.end());
    out.plans = team.plans;
    out.crashBudget = t < t_.lowering.assumptions.crashBudget.size() ? t_.lowering.assumptions.crashBudget[t] : 0;
    const std::vector<lowering::PlanProgram>& programs = t_.lowering.programs[t];
    for (std::size_t k = 0; k < team.modes.size(); ++k) {
      const model::Mode& mode = m_.modes[team.modes[k]];
      runtime::ModeTable mt;
      mt.name = mode.name;
      mt.entry.assign(team.plans.size(), 0);
      for (const model::PlanSetting& s : mode.settings) mt.entry[s.plan] = static_cast<Id>(programs[s.plan].entryOf[s.service]);
      for (const model::Transition& tr : mode.transitions) {
        if (tr.isDefault) mt.defaultTarget = teamModeIndex(tr.target);
        else mt.catches.emplace_back(tr.event, teamModeIndex(tr.target));
      }
      out.modes.push_back(std::move(mt));
      if (team.modes[k] == team.initialMode) out.initialMode = static_cast<Id>(k);
    }
    for (const model::Event& e : team.events) {
      runtime::EventTable et;
      et.name = e.name;
      et.reliable = e.delivery.reliable;
      et.retransmissions = e.delivery.retransmissions;
      et.lossy = t_.lowering.assumptions.loseEvents && !e.delivery.reliable;
      out.events.push_back(std::move(et));
    }
    out_.teams.push_back(std::move(out));
  }
  for (const model::CompositeService& s : m_.services) out_.services.push_back({s.name, s.plan});
}

void Projector::topicsAndValues() {
  for (const model::Topic& topic : m_.topics) {
    runtime::TopicTable out;
    out.name = m_.teams[topic.owner].name + "." + topic.var;
    out.owner = topic.owner;
    out.symbols = topic.symbols;
    out.reliable = topic.reliable;
    out.capacity = topic.buffer;
    out.lossy = !topic.reliable && t_.lowering.assumptions.losePublish;
    out_.topics.push_back(std::move(out));
  }
  for (const lowering::VariableRole& role : t_.lowering.variables) {
    if (role.kind == RoleKind::View) out_.topics[role.index].subscribers.push_back(role.robot);
  }
  for (const strategy::Value& v : m_.strategy.values) {
    runtime::SensedValueTable out;
    out.name = v.team + "." + v.var;
    using D = strategy::Domain::Kind;
    switch (v.domain.kind) {
      case D::Bool: out.domain = runtime::SensedValueTable::Domain::Bool; break;
      case D::Threshold: out.domain = runtime::SensedValueTable::Domain::Threshold; break;
      case D::Enum: out.domain = runtime::SensedValueTable::Domain::Enum; break;
      case D::Range: out.domain = runtime::SensedValueTable::Domain::Range; break;
    }
    out.thresholds = v.domain.thresholds;
    out.symbols = v.domain.values;
    out_.sensed.push_back(std::move(out));
  }
}

// One knowledge item per (team, name), as the IR has one `knows` variable per robot and name.
void Projector::knowledge() {
  for (model::Index t = 0; t < m_.teams.size(); ++t) {
    for (const lowering::PlanProgram& prog : t_.lowering.programs[t]) {
      for (const lowering::Instr& in : prog.code) {
        if (in.kind != lowering::Instr::Kind::GroupService) continue;
        const strategy::Service& sv = m_.serviceOf(*in.stmt);
        for (const strategy::Knowledge& k : sv.knowledge) {
          if (knowledgeItem(t, k.name) != kNone) continue;
          runtime::KnowledgeTable out;
          out.service = sv.name;
          out.name = k.name;
          out.team = t;
          out.facts = k.values;
          out.newest = k.merge == strategy::Knowledge::Merge::Newest;
          const std::string via = sv.dissemination ? sv.dissemination->via : "broadcast";
          out.shared = via != "none";
          out.reliable = via == "reliable";
          out.period = sv.dissemination ? static_cast<double>(sv.dissemination->periodMillis) / 1000.0 : 1.0;
          out.retransmissions = sv.dissemination ? sv.dissemination->retransmissions : 0;
          out.lossy = t_.lowering.assumptions.loseKnowledge && !out.reliable;
          knowledgeIndex_[{t, k.name}] = static_cast<Id>(out_.knowledge.size());
          out_.knowledge.push_back(std::move(out));
        }
      }
    }
  }
}

void Projector::groupBlocks() {
  leaderIndex_.assign(m_.groupBlocks.size(), kNone);
  for (model::Index b = 0; b < m_.groupBlocks.size(); ++b) {
    const model::GroupBlock& block = m_.groupBlocks[b];
    runtime::GroupBlockTable out;
    out.team = block.team;
    out.name = m_.teams[block.team].name + "." + m_.services[block.service].plan + "." + m_.services[block.service].name + "#" +
               std::to_string(b);
    const std::vector<lowering::PlanProgram>& programs = t_.lowering.programs[block.team];
    for (std::size_t p = 0; p < programs.size(); ++p) {
      for (const lowering::BlockRange& range : programs[p].blocks) {
        if (range.block != b) continue;
        out.plan = static_cast<Id>(p);
        out.first = static_cast<Id>(range.first);
        out.formPoint = static_cast<Id>(range.last);
        out.exit = static_cast<Id>(range.exit);
        for (std::size_t a = 0; a < block.arms.size(); ++a) {
          const model::GroupArm& arm = block.arms[a];
          runtime::ArmTable at;
          at.leader = arm.kind == model::GroupArm::Kind::Leader;
          at.others = arm.kind == model::GroupArm::Kind::Others;
          at.label = at.others ? "others" : std::string(at.leader ? "leader (" : "group (") + arm.names.front() + (arm.names.size() > 1 ? ", ...)" : ")");
          at.entry = static_cast<Id>(programs[p].code[range.last].arms[a]);
          at.first = static_cast<Id>(range.armFirst[a]);
          at.end = static_cast<Id>(range.armEnd(a));
          at.candidates.assign(arm.candidates.begin(), arm.candidates.end());
          out.arms.push_back(std::move(at));
        }
      }
    }
    if (block.isLeaderBlock) {
      runtime::LeaderBlockTable lb;
      lb.name = out.name;
      lb.block = b;
      for (std::size_t a = 0; a < out.arms.size(); ++a) {
        if (out.arms[a].leader) lb.leaderArm = static_cast<Id>(a), lb.candidates = out.arms[a].candidates;
        if (out.arms[a].others) lb.othersArm = static_cast<Id>(a);
      }
      lb.preference = lb.candidates;
      if (block.leader.algorithm == strategy::LeaderSelection::Algorithm::Bully) std::reverse(lb.preference.begin(), lb.preference.end());
      lb.heartbeat = static_cast<double>(block.leader.heartbeatMillis) / 1000.0;
      lb.timeoutPeriods = static_cast<std::int32_t>(std::max<std::int64_t>(1, block.leader.timeoutMillis / std::max<std::int64_t>(1, block.leader.heartbeatMillis)));
      lb.lossyHeartbeats = t_.lowering.assumptions.loseHeartbeats;
      lb.lossBurst = static_cast<std::int32_t>(t_.lowering.assumptions.lossBurst);
      // The model detects failures only where it has silence counters (a leader can fail or its
      // heartbeats can be lost, and the strategy re-elects on timeout).
      lb.detectsFailures = std::any_of(t_.lowering.variables.begin(), t_.lowering.variables.end(), [&](const lowering::VariableRole& r) {
        return r.kind == RoleKind::Silence && r.index == b;
      });
      lb.heartbeatRule.assign(std::size_t{1} << std::min<std::size_t>(lb.candidates.size(), 16), kNone);
      leaderIndex_[b] = static_cast<Id>(out_.leaderBlocks.size());
      out.leader = leaderIndex_[b];
      const std::vector<model::Index>& modes = m_.teams[block.team].modes;
      for (std::size_t k = 0; k < modes.size(); ++k) {  // as the translation's enterMode keeps `leads`
        if (m_.keepsLeadership(b, modes[k])) out_.teams[block.team].modes[k].keepsLeaders.push_back(leaderIndex_[b]);
      }
      out_.leaderBlocks.push_back(std::move(lb));
    }
    out_.groupBlocks.push_back(std::move(out));
  }
}

void Projector::robots() {
  for (model::Index r = 0; r < m_.robots.size(); ++r) {
    const model::Robot& robot = m_.robots[r];
    runtime::RobotTable out;
    out.name = robot.name;
    out.type = robot.type;
    out.team = robot.team;
    out.indexInTeam = robot.indexInTeam;
    if (const RobotType* type = m_.catalog.find(robot.type); type != nullptr && type->wheels && type->wheels->radius > 0) {
      out.geometry.wheeled = true;
      out.geometry.wheelRadius = type->wheels->radius;
      out.geometry.wheelSeparation = type->wheels->separation;
      // The URDF's wheel velocity limit: forward at full wheel speed, and turning in place with the
      // wheels at full speed in opposite directions. Without a limit the body's defaults stay.
      if (const double w = type->wheels->maxWheelSpeed; w > 0) {
        out.geometry.maxSpeed = w * type->wheels->radius;
        if (type->wheels->separation > 0) out.geometry.maxTurnRate = 2 * out.geometry.maxSpeed / type->wheels->separation;
      }
    }
    const runtime::TeamTable& team = out_.teams[robot.team];
    out.eventDeliveryRule.assign(team.events.size(), kNone);
    out.eventLossRule.assign(team.events.size(), kNone);
    out.messageDeliveryRule.assign(out_.topics.size(), kNone);
    out.messageLossRule.assign(out_.topics.size(), kNone);
    out.defaultRule.assign(team.modes.size(), kNone);
    for (Id lb = 0; lb < out_.leaderBlocks.size(); ++lb) {
      const std::vector<Id>& c = out_.leaderBlocks[lb].candidates;
      if (std::find(c.begin(), c.end(), r) != c.end()) out.leaderBlocks.push_back(lb);
    }
    out.takeoverRule.assign(out.leaderBlocks.size(), kNone);
    for (Id k = 0; k < out_.knowledge.size(); ++k) {
      if (out_.knowledge[k].team != robot.team) continue;
      out.knowledge.push_back(k);
      out.learnRule.emplace_back(out_.knowledge[k].facts.size() + 1, kNone);
    }
    out_.robots.push_back(std::move(out));
    plans(r);
  }
}

// Where the runtime takes each step outside the robots' programs.
void Projector::networkRules() {
  const std::vector<lowering::RuleMeaning>& rules = t_.lowering.rules;
  for (Id i = 0; i < rules.size(); ++i) {
    const lowering::RuleMeaning& m = rules[i];
    runtime::RobotTable* robot = m.robot == model::kNone ? nullptr : &out_.robots[m.robot];
    switch (m.kind) {
      case MeaningKind::ProgramStep: break;  // rows (project_rows.cpp)
      case MeaningKind::ModeDefault: robot->defaultRule[teamModeIndex(m.mode)] = i; break;
      case MeaningKind::Discover: {
        Id started = kNone;
        for (const lowering::Guard& g : m.guards) {
          if (g.kind == lowering::Guard::Kind::GroupStarted) started = pcSet(g.pcs);
        }
        robot->discoverRules.push_back({knowledgeItem(m_.robots[m.robot].team, m.knowledge), static_cast<Id>(m.plan), static_cast<Id>(m.from), i, started});
        break;
      }
      case MeaningKind::Learn: {
        Id k = knowledgeItem(m_.robots[m.robot].team, m.knowledge);
        auto slot = std::find(robot->knowledge.begin(), robot->knowledge.end(), k) - robot->knowledge.begin();
        robot->learnRule[slot][static_cast<std::size_t>(m.count)] = i;
        break;
      }
      case MeaningKind::EventDelivery: robot->eventDeliveryRule[m.index] = i; break;
      case MeaningKind::EventLoss: robot->eventLossRule[m.index] = i; break;
      case MeaningKind::MessageDelivery: robot->messageDeliveryRule[m.index] = i; break;
      case MeaningKind::MessageLoss: robot->messageLossRule[m.index] = i; break;
      case MeaningKind::Crash: robot->crashRule = i; break;
      case MeaningKind::HeartbeatPeriod: {
        runtime::LeaderBlockTable& lb = out_.leaderBlocks[leaderIndex_[m.index]];
        std::size_t mask = 0;
        for (model::Index lost : m.lostTo) {
          mask |= std::size_t{1} << (std::find(lb.candidates.begin(), lb.candidates.end(), lost) - lb.candidates.begin());
        }
        lb.heartbeatRule.at(mask) = i;
        break;
      }
      case MeaningKind::Takeover: {
        Id lb = leaderIndex_[m.index];
        auto slot = std::find(robot->leaderBlocks.begin(), robot->leaderBlocks.end(), lb) - robot->leaderBlocks.begin();
        robot->takeoverRule[slot] = i;
        break;
      }
    }
  }
}

// The abstraction function, one entry per IR variable (specs/runtime.md).
void Projector::abstraction() {
  const std::vector<lowering::VariableRole>& roles = t_.lowering.variables;
  for (std::size_t v = 0; v < roles.size(); ++v) {
    const lowering::VariableRole& role = roles[v];
    runtime::AbstractVar out;
    out.kind = static_cast<runtime::AbstractVar::Kind>(role.kind);
    out.robot = role.robot;
    out.team = role.team;
    out.index = role.index;
    out.init = t_.model.variables[v].init;
    out.name = t_.model.variables[v].name;
    if (role.kind == RoleKind::Leads || role.kind == RoleKind::Silence || role.kind == RoleKind::LostHeartbeats) out.index = leaderIndex_[role.index];
    if (role.kind == RoleKind::Knows || role.kind == RoleKind::Holding) out.index = knowledgeItem(role.team, role.knowledge);
    out.values = role.values;
    out_.abstraction.push_back(std::move(out));
  }
}

}  // namespace detail

runtime::MissionTables project(const model::MissionModel& mission, const Translation& translation, const SourceManager& sources) {
  return detail::Projector(mission, translation, sources).run();
}

}  // namespace semo::codegen
