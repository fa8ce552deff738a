#include "semo/frontend/ast_json.hpp"

#include <nlohmann/json.hpp>

namespace semo {

namespace ast {
const char* spelling(RelOp op) {
  switch (op) {
    case RelOp::Lt: return "<";
    case RelOp::Le: return "<=";
    case RelOp::Gt: return ">";
    case RelOp::Ge: return ">=";
    case RelOp::Eq: return "==";
    case RelOp::Ne: return "!=";
  }
  return "==";
}
}  // namespace ast

namespace {

using nlohmann::json;

json at(const SourceRange& r) { return {{"line", r.begin.line}, {"col", r.begin.column}}; }
json name(const ast::Name& n) { return {{"name", n.text}, {"line", n.range.begin.line}, {"col", n.range.begin.column}}; }
json duration(const ast::Duration& d) { return {{"ms", d.milliseconds()}, {"line", d.range.begin.line}, {"col", d.range.begin.column}}; }

json expr(const ast::Expr& e) {
  json j = at(e.range);
  switch (e.kind) {
    case ast::Expr::Kind::Int: j["int"] = e.intValue; break;
    case ast::Expr::Kind::Number: j["number"] = e.numberValue; break;
    case ast::Expr::Kind::String: j["string"] = e.text; break;
    case ast::Expr::Kind::Bool: j["bool"] = e.intValue != 0; break;
    case ast::Expr::Kind::Symbol: j["symbol"] = e.text; break;
    case ast::Expr::Kind::Value: j["value"] = e.owner.text + "." + e.var.text; break;
  }
  return j;
}

json cond(const ast::Cond& c) {
  json j = at(c.range);
  switch (c.kind) {
    case ast::Cond::Kind::Compare:
      j["compare"] = ast::spelling(c.op);
      j["lhs"] = expr(c.lhs);
      j["rhs"] = expr(c.rhs);
      break;
    case ast::Cond::Kind::Test: j["test"] = expr(c.lhs); break;
    case ast::Cond::Kind::Not: j["not"] = cond(*c.left); break;
    case ast::Cond::Kind::And: j["and"] = {cond(*c.left), cond(*c.right)}; break;
    case ast::Cond::Kind::Or: j["or"] = {cond(*c.left), cond(*c.right)}; break;
  }
  return j;
}

json stmts(const std::vector<ast::Stmt>& body);

json stmt(const ast::Stmt& s) {
  json j = at(s.range);
  switch (s.kind) {
    case ast::Stmt::Kind::Call: {
      j["kind"] = "call";
      j["service"] = s.name.text;
      json args = json::array();
      for (const ast::Expr& a : s.args) args.push_back(expr(a));
      j["args"] = args;
      break;
    }
    case ast::Stmt::Kind::Throw: j["kind"] = "throw"; j["event"] = s.name.text; break;
    case ast::Stmt::Kind::Loop: j["kind"] = "loop"; j["period"] = duration(s.duration); break;
    case ast::Stmt::Kind::Wait: j["kind"] = "wait"; j["duration"] = duration(s.duration); break;
    case ast::Stmt::Kind::If:
      j["kind"] = "if";
      j["cond"] = cond(*s.cond);
      j["then"] = stmts(s.thenBody);
      if (s.hasElse) j["else"] = stmts(s.elseBody);
      break;
    case ast::Stmt::Kind::Publish:
    case ast::Stmt::Kind::Send:
    case ast::Stmt::Kind::Subscribe:
    case ast::Stmt::Kind::Receive: {
      static const char* kinds[] = {"publish", "subscribe", "send", "receive"};
      int index = s.kind == ast::Stmt::Kind::Publish ? 0 : s.kind == ast::Stmt::Kind::Subscribe ? 1
                  : s.kind == ast::Stmt::Kind::Send  ? 2 : 3;
      j["kind"] = kinds[index];
      j["team"] = s.peer.text;
      j["topic"] = s.topicOwner.text + "." + s.topicVar.text;
      if (index == 0 || index == 2) j["value"] = expr(s.value);
      break;
    }
    case ast::Stmt::Kind::GroupBlock: {
      j["kind"] = "groups";
      json arms = json::array();
      for (const ast::GroupArm& arm : s.arms) {
        json a = at(arm.keyword);
        a["arm"] = arm.kind == ast::GroupArm::Kind::Group ? "group" : arm.kind == ast::GroupArm::Kind::Leader ? "leader" : "others";
        if (arm.condition) {
          a["condition"] = arm.condition->kind == ast::GroupCondition::Kind::InstanceOf ? "instance of" : "capable of";
          json names = json::array();
          for (const ast::Name& n : arm.condition->names) names.push_back(n.text);
          a["names"] = names;
        }
        a["body"] = stmts(arm.body);
        arms.push_back(a);
      }
      j["arms"] = arms;
      break;
    }
  }
  return j;
}

json stmts(const std::vector<ast::Stmt>& body) {
  json out = json::array();
  for (const ast::Stmt& s : body) out.push_back(stmt(s));
  return out;
}

json ltl(const ast::Ltl& f) {
  json j = at(f.range);
  static const char* names[] = {"atom", "not", "always", "eventually", "next", "and", "or", "until", "implies"};
  j["op"] = names[static_cast<int>(f.kind)];
  if (f.kind == ast::Ltl::Kind::Atom) {
    j["lhs"] = expr(f.lhs);
    if (f.op) {
      j["compare"] = ast::spelling(*f.op);
      j["rhs"] = expr(f.rhs);
    }
  }
  if (f.left) j["left"] = ltl(*f.left);
  if (f.right) j["right"] = ltl(*f.right);
  return j;
}

}  // namespace

std::string missionToJson(const ast::Mission& m) {
  json teams = json::array();
  for (const ast::TeamDecl& t : m.teams) {
    json robots = json::array();
    for (const ast::RobotDecl& r : t.robots) {
      json jr = name(r.name);
      jr["type"] = r.type.text;
      if (r.count) jr["count"] = *r.count;
      robots.push_back(jr);
    }
    json jt = name(t.team);
    jt["robots"] = robots;
    teams.push_back(jt);
  }
  json services = json::array();
  for (const ast::Service& s : m.services) {
    json js = at(s.range);
    js["team"] = s.team.text;
    js["plan"] = s.plan.text;
    js["name"] = s.name.text;
    js["body"] = stmts(s.body);
    if (s.repeat) {
      js["repeat"] = s.repeat->isPeriod ? json{{"period", duration(s.repeat->period)}} : json{{"while", cond(*s.repeat->cond)}};
    }
    services.push_back(js);
  }
  json modes = json::array();
  for (const ast::ModeDef& md : m.modes) {
    json sets = json::array();
    for (const ast::SetItem& item : md.sets) {
      json ji = at(item.range);
      ji["plan"] = item.plan.text;
      ji["service"] = item.service.text;
      sets.push_back(ji);
    }
    json jm = name(md.mode);
    jm["team"] = md.team.text;
    jm["sets"] = sets;
    modes.push_back(jm);
  }
  json mains = json::array();
  for (const ast::MainDef& mn : m.mains) {
    json cases = json::array();
    for (const ast::Case& c : mn.cases) {
      json transitions = json::array();
      for (const ast::Transition& t : c.transitions) {
        json jt = at(t.range);
        if (t.isDefault) {
          jt["default"] = true;
        } else {
          jt["catch"] = t.event.text;
        }
        jt["mode"] = t.target.text;
        transitions.push_back(jt);
      }
      json jc = name(c.mode);
      jc["transitions"] = transitions;
      cases.push_back(jc);
    }
    json jm = at(mn.range);
    jm["team"] = mn.team.text;
    jm["cases"] = cases;
    mains.push_back(jm);
  }
  json verifies = json::array();
  for (const ast::VerifyBlock& v : m.verifies) {
    json jv = at(v.range);
    json crashes = json::array();
    for (const ast::CrashAssumption& c : v.crashes) {
      json jc = at(c.range);
      jc["budget"] = c.budget;
      if (c.team) jc["team"] = c.team->text;
      crashes.push_back(jc);
    }
    jv["crash"] = crashes;
    json losses = json::array();
    for (const ast::Name& n : v.losses) losses.push_back(n.text);
    jv["loss"] = losses;
    if (v.fairness) jv["fairness"] = v.fairness->text;
    json checks = json::array();
    for (const ast::Name& n : v.checks) checks.push_back(n.text);
    jv["check"] = checks;
    json properties = json::array();
    for (const ast::Property& p : v.properties) {
      json jp = name(p.name);
      jp["formula"] = ltl(*p.formula);
      properties.push_back(jp);
    }
    jv["properties"] = properties;
    verifies.push_back(jv);
  }
  json root = {{"teams", teams}, {"services", services}, {"modes", modes}, {"mains", mains}, {"verify", verifies}};
  return root.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string missionSummary(const ast::Mission& m) {
  std::size_t robots = 0;
  for (const ast::TeamDecl& t : m.teams) {
    for (const ast::RobotDecl& r : t.robots) robots += static_cast<std::size_t>(r.count.value_or(1));
  }
  std::size_t properties = 0;
  for (const ast::VerifyBlock& v : m.verifies) properties += v.properties.size();
  std::string out;
  out += "teams:      " + std::to_string(m.teams.size()) + " (" + std::to_string(robots) + " robots)\n";
  for (const ast::TeamDecl& t : m.teams) {
    std::size_t n = 0;
    for (const ast::RobotDecl& r : t.robots) n += static_cast<std::size_t>(r.count.value_or(1));
    out += "  " + t.team.text + ": " + std::to_string(n) + (n == 1 ? " robot\n" : " robots\n");
  }
  out += "services:   " + std::to_string(m.services.size()) + "\n";
  out += "modes:      " + std::to_string(m.modes.size()) + "\n";
  out += "mains:      " + std::to_string(m.mains.size()) + "\n";
  out += "verify:     " + std::string(m.verifies.empty() ? "no" : "yes") + " (" + std::to_string(properties) + " properties)\n";
  return out;
}

}  // namespace semo
