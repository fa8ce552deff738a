// Warnings about a mission that is legal but likely wrong: topics written and never taken in, read
// without being taken in, and crash budgets that can take every robot a group could have.
#include <functional>
#include <set>

#include "elaborator.hpp"

namespace semo::detail {

namespace {

using model::Index;

// Every statement of a body, nested ones included (if branches, group arms).
void forEachStmt(const model::MissionModel& m, const std::vector<model::Stmt>& body, const std::function<void(const model::Stmt&)>& f) {
  for (const model::Stmt& s : body) {
    f(s);
    forEachStmt(m, s.thenBody, f);
    forEachStmt(m, s.elseBody, f);
    if (s.kind == model::Stmt::Kind::Groups && s.groupBlock < m.groupBlocks.size()) {
      for (const model::GroupArm& arm : m.groupBlocks[s.groupBlock].arms) forEachStmt(m, arm.body, f);
    }
  }
}

void forEachValue(const model::Cond& c, const std::function<void(const model::Expr&)>& f) {
  f(c.lhs);
  f(c.rhs);
  if (c.left) forEachValue(*c.left, f);
  if (c.right) forEachValue(*c.right, f);
}

std::string topicName(const model::MissionModel& m, Index topic) {
  const model::Topic& t = m.topics[topic];
  return (t.owner < m.teams.size() ? m.teams[t.owner].name : std::string("?")) + "." + t.var;
}

}  // namespace

void Elaborator::checkTopics() {
  const std::size_t teams = m_.teams.size();
  std::vector<std::set<Index>> takesIn(teams), writes(teams);
  std::set<Index> takenAnywhere;
  std::vector<std::pair<Index, const model::Expr*>> reads;  // (team, a topic's value in a condition or an expression)
  for (Index t = 0; t < teams; ++t) {
    for (Index s : m_.teams[t].services) {
      const model::CompositeService& service = m_.services[s];
      auto read = [&](const model::Expr& e) {
        if (e.kind == model::Expr::Kind::Value && e.valueKind == model::ValueKind::Topic && e.topic < m_.topics.size()) reads.emplace_back(t, &e);
      };
      if (service.repeat && service.repeat->cond) forEachValue(*service.repeat->cond, read);
      forEachStmt(m_, service.body, [&](const model::Stmt& st) {
        if (st.topic < m_.topics.size()) {
          if (st.kind == model::Stmt::Kind::Subscribe || st.kind == model::Stmt::Kind::Receive) takesIn[t].insert(st.topic), takenAnywhere.insert(st.topic);
          if (st.kind == model::Stmt::Kind::Publish || st.kind == model::Stmt::Kind::Send) writes[t].insert(st.topic);
        }
        if (st.cond) forEachValue(*st.cond, read);
        for (const model::Expr& a : st.args) read(a);
        read(st.value);
      });
    }
  }
  for (Index topic = 0; topic < m_.topics.size(); ++topic) {
    const model::Topic& t = m_.topics[topic];
    if (!t.written || takenAnywhere.count(topic) != 0) continue;
    diags_.warning(t.firstUse, t.reliable ? "topic '" + topicName(m_, topic) + "' is sent but no robot receives it: its channel only fills up"
                                          : "topic '" + topicName(m_, topic) + "' is published but no robot subscribes to it: no robot ever "
                                                                               "gets what is published");
  }
  // A robot takes a topic in by subscribing (or receiving), and hears its own publishes: a team
  // that does neither reads the value it started with, for ever.
  std::set<std::pair<Index, Index>> warned;
  for (const auto& [team, e] : reads) {
    if (takesIn[team].count(e->topic) != 0 || writes[team].count(e->topic) != 0) continue;
    if (!warned.insert({team, e->topic}).second) continue;
    const bool reliable = m_.topics[e->topic].reliable;
    diags_.warning(e->at, "team '" + m_.teams[team].name + "' reads topic '" + topicName(m_, e->topic) + "' but never " +
                              (reliable ? "receives" : "subscribes to") + " it: its robots keep the initial value");
  }
}

void Elaborator::checkCrashBudgets() {
  for (const model::GroupBlock& block : m_.groupBlocks) {
    if (block.team >= m_.teams.size() || block.team >= m_.assumptions.crashBudget.size()) continue;
    const std::int64_t budget = m_.assumptions.crashBudget[block.team];
    if (budget <= 0) continue;
    for (const model::GroupArm& arm : block.arms) {
      if (arm.kind == model::GroupArm::Kind::Others || arm.candidates.empty()) continue;
      if (static_cast<std::int64_t>(arm.candidates.size()) > budget) continue;
      std::string names;
      for (Index r : arm.candidates) names += (names.empty() ? "" : ", ") + m_.robots[r].name;
      diags_.warning(arm.at, "the verify block lets up to " + std::to_string(budget) + " robot" + (budget == 1 ? "" : "s") + " of team '" +
                                 m_.teams[block.team].name + "' crash, as many as may take this group (" + names +
                                 "): once they have, the group cannot form and what needs it holds only vacuously");
    }
  }
}

}  // namespace semo::detail
