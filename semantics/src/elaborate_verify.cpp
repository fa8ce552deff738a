// The verify block: fault assumptions, checks, and LTL properties with resolved atoms.
#include <algorithm>

#include "elaborator.hpp"

namespace semo::detail {

namespace {

const std::vector<std::string>& allChecks() {
  static const std::vector<std::string> checks{"group_formation",       "unique_leader",  "leader_reelection",
                                               "knowledge_convergence", "mode_agreement", "deadlock_freedom",
                                               "buffer_bounds"};
  return checks;
}

}  // namespace

void Elaborator::elaborateVerify() {
  model::Assumptions& a = m_.assumptions;
  a.crashBudget.assign(m_.teams.size(), 0);
  if (ast_.verifies.size() > 1) {
    Diagnostic& d = diags_.error(ast_.verifies[1].range, "a mission has at most one verify block");
    DiagnosticEngine::note(d, ast_.verifies[0].range, "first verify block here");
  }
  if (ast_.verifies.empty()) {
    a.checks = allChecks();
    return;
  }
  const ast::VerifyBlock& v = ast_.verifies.front();

  std::vector<const ast::CrashAssumption*> crashOf(m_.teams.size(), nullptr);
  const ast::CrashAssumption* everyTeam = nullptr;
  for (const ast::CrashAssumption& c : v.crashes) {
    if (!c.team) {
      if (everyTeam != nullptr) {
        Diagnostic& d = diags_.error(c.range, "crash budget for every team is given twice");
        DiagnosticEngine::note(d, everyTeam->range, "first given here");
        continue;
      }
      everyTeam = &c;
      std::size_t largest = 0;
      for (const model::Team& t : m_.teams) largest = std::max(largest, t.robots.size());
      if (!m_.teams.empty() && c.budget > static_cast<std::int64_t>(largest)) {
        diags_.error(c.range, "crash budget " + std::to_string(c.budget) + " exceeds the size of every team (the largest has " +
                                  std::to_string(largest) + " robots)");
        continue;
      }
      for (Index t = 0; t < m_.teams.size(); ++t) {
        if (crashOf[t] == nullptr) {
          a.crashBudget[t] = std::min<std::int64_t>(c.budget, static_cast<std::int64_t>(m_.teams[t].robots.size()));
        }
      }
      continue;
    }
    Index team = teamOrError(*c.team, "in crash assumption");
    if (team == model::kNone) continue;
    if (crashOf[team] != nullptr) {
      Diagnostic& d = diags_.error(c.range, "crash budget of team '" + c.team->text + "' is given twice");
      DiagnosticEngine::note(d, crashOf[team]->range, "first given here");
      continue;
    }
    crashOf[team] = &c;
    auto size = static_cast<std::int64_t>(m_.teams[team].robots.size());
    if (c.budget > size) {
      diags_.error(c.range, "crash budget " + std::to_string(c.budget) + " exceeds the size of team '" + c.team->text + "' (" +
                                std::to_string(size) + " robots)");
      continue;
    }
    a.crashBudget[team] = c.budget;
  }

  const ast::Name* none = nullptr;
  for (const ast::Name& loss : v.losses) {
    const std::string& k = loss.text;
    if (k == "none") none = &loss;
    a.losePublish |= k == "publish" || k == "all";
    a.loseEvents |= k == "events" || k == "all";
    a.loseKnowledge |= k == "knowledge" || k == "all";
    a.loseHeartbeats |= k == "heartbeats" || k == "all";
  }
  if (none != nullptr && v.losses.size() > 1) diags_.error(none->range, "loss 'none' cannot be combined with other loss kinds");
  if (v.fairness) a.fairLoss = v.fairness->text == "fair";
  if (v.lossBurst) a.lossBurst = *v.lossBurst;
  a.lossProbability = v.lossProbability;

  for (const ast::Name& check : v.checks) {
    if (std::find(allChecks().begin(), allChecks().end(), check.text) == allChecks().end()) continue;  // parser reported it
    if (std::find(a.checks.begin(), a.checks.end(), check.text) != a.checks.end()) {
      diags_.warning(check.range, "check '" + check.text + "' is listed twice");
      continue;
    }
    a.checks.push_back(check.text);
  }
  if (v.checks.empty()) a.checks = allChecks();
  a.checksListed = !v.checks.empty();

  for (const ast::Property& p : v.properties) {
    auto twice = std::find_if(m_.properties.begin(), m_.properties.end(),
                              [&](const model::Property& q) { return q.name == p.name.text; });
    if (twice != m_.properties.end()) {
      Diagnostic& d = diags_.error(p.name.range, "property '" + p.name.text + "' is defined twice");
      DiagnosticEngine::note(d, twice->at, "first defined here");
      continue;
    }
    m_.properties.push_back({p.name.text, lowerLtl(*p.formula), p.name.range});
  }
}

std::unique_ptr<model::Ltl> Elaborator::lowerLtl(const ast::Ltl& f) {
  auto out = std::make_unique<model::Ltl>();
  out->at = f.range;
  out->kind = static_cast<model::Ltl::Kind>(static_cast<int>(f.kind));
  if (f.left) out->left = lowerLtl(*f.left);
  if (f.right) out->right = lowerLtl(*f.right);
  if (f.kind == ast::Ltl::Kind::Atom) lowerAtom(f, *out);
  return out;
}

void Elaborator::lowerAtom(const ast::Ltl& f, model::Ltl& out) {
  const ast::Expr& lhs = f.lhs;
  if (lhs.kind == ast::Expr::Kind::Bool && !f.op) {
    out.kind = lhs.intValue != 0 ? model::Ltl::Kind::Atom : model::Ltl::Kind::Not;
    if (lhs.intValue == 0) {
      // `false` is "not true": keep a constant-true atom underneath.
      out.left = std::make_unique<model::Ltl>();
      out.left->at = f.range;
      out.left->rhs.kind = model::Expr::Kind::Bool;
      out.left->rhs.intValue = 1;
    }
    out.rhs.kind = model::Expr::Kind::Bool;
    out.rhs.intValue = 1;
    return;
  }
  if (lhs.kind != ast::Expr::Kind::Value) {
    diags_.error(lhs.range, "expected an atom such as 'Team.mode == MODE', 'robot.alive' or 'Team.value < 3'");
    return;
  }
  Index team = m_.findTeam(lhs.owner.text);
  Index robot = m_.findRobot(lhs.owner.text);
  if (team == model::kNone && robot == model::kNone) {
    // `rover[2]` declares rover_0 and rover_1: a property that names the declaration names none.
    std::vector<std::string> numbered;
    for (const model::Robot& r : m_.robots) {
      if (r.name.size() > lhs.owner.text.size() + 1 && r.name.rfind(lhs.owner.text + "_", 0) == 0 &&
          r.name.find_first_not_of("0123456789", lhs.owner.text.size() + 1) == std::string::npos) {
        numbered.push_back(r.name);
      }
    }
    if (!numbered.empty()) {
      std::string list;
      for (const std::string& n : numbered) list += (list.empty() ? "'" : ", '") + n + "'";
      diags_.error(lhs.owner.range, "undefined team or robot '" + lhs.owner.text + "': the team declares " + list +
                                        "; name one of them (" + numbered.front() + "." + lhs.var.text + ")");
      return;
    }
    std::vector<std::string> names = teamNames();
    for (const model::Robot& r : m_.robots) names.push_back(r.name);
    diags_.error(lhs.owner.range, withHint("undefined team or robot '" + lhs.owner.text + "'", lhs.owner.text, names));
    return;
  }
  out.subject = team != model::kNone ? model::Ltl::Subject::Team : model::Ltl::Subject::Robot;
  out.subjectIndex = team != model::kNone ? team : robot;
  Index ownerTeam = team != model::kNone ? team : m_.robots[robot].team;
  const std::string& attr = lhs.var.text;
  if (f.op) out.op = static_cast<model::RelOp>(static_cast<int>(*f.op));

  if (attr == "alive" || attr == "leader") {
    out.attribute = attr == "alive" ? model::Ltl::Attribute::Alive : model::Ltl::Attribute::Leader;
    if (robot == model::kNone) {
      const std::vector<Index>& members = m_.teams[team].robots;
      std::string example = members.empty() ? "robot" : m_.robots[members.front()].name;
      diags_.error(lhs.var.range, "'" + attr + "' is a property of one robot; name a robot (for example '" + example +
                                      "." + attr + "')");
    } else if (f.op) {
      diags_.error(f.rhs.range, "'" + lhs.owner.text + "." + attr + "' is true or false; use it without a comparison");
    }
    return;
  }
  if (attr == "mode") {
    out.attribute = model::Ltl::Attribute::Mode;
    if (!f.op || (*f.op != ast::RelOp::Eq && *f.op != ast::RelOp::Ne) || f.rhs.kind != ast::Expr::Kind::Symbol) {
      diags_.error(lhs.range, "compare a mode with '==' or '!=' and a mode name (for example '" + lhs.owner.text +
                                  ".mode == " + (m_.teams[ownerTeam].modes.empty() ? "MODE" : m_.modes[m_.teams[ownerTeam].modes.front()].name) + "')");
      return;
    }
    out.mode = m_.findMode(ownerTeam, f.rhs.text);
    if (out.mode == model::kNone) {
      diags_.error(f.rhs.range, withHint("undefined mode '" + f.rhs.text + "' of team '" + m_.teams[ownerTeam].name + "'",
                                         f.rhs.text, modeNames(ownerTeam)));
    }
    return;
  }
  out.attribute = model::Ltl::Attribute::Value;
  out.var = attr;
  const std::string& teamName = m_.teams[ownerTeam].name;
  bool known = false;
  if (m_.strategy.value(teamName, attr) != nullptr) {
    out.valueKind = model::ValueKind::Sensed;
    known = true;
  } else if (m_.findTopic(ownerTeam, attr) != model::kNone) {
    out.valueKind = model::ValueKind::Topic;
    known = true;
  } else {
    for (const strategy::Service& s : m_.strategy.services) {
      for (const strategy::Knowledge& k : s.knowledge) known = known || k.name == attr;
    }
    out.valueKind = model::ValueKind::Knowledge;
  }
  if (!known) {
    diags_.error(lhs.var.range, "'" + attr + "' is not a mode, alive, leader, value, topic or knowledge of '" + lhs.owner.text + "'");
    return;
  }
  if (f.op) {
    model::Expr rhs;
    rhs.at = f.rhs.range;
    rhs.kind = static_cast<model::Expr::Kind>(static_cast<int>(f.rhs.kind));
    rhs.intValue = f.rhs.intValue;
    rhs.numberValue = f.rhs.numberValue;
    rhs.text = f.rhs.text;
    if (f.rhs.kind == ast::Expr::Kind::Value) diags_.error(f.rhs.range, "compare a value with a constant, not with another value");
    out.rhs = std::move(rhs);
  }
}

}  // namespace semo::detail
