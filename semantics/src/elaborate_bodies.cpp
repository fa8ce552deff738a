// Service bodies: statements, calls, group blocks, conditions, values and topics.
#include <algorithm>

#include "elaborator.hpp"

namespace semo::detail {

namespace {

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

std::string formatNumber(double v) {
  std::string s = std::to_string(v);
  s.erase(s.find_last_not_of('0') + 1);
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

model::RelOp relOp(ast::RelOp op) {
  switch (op) {
    case ast::RelOp::Lt: return model::RelOp::Lt;
    case ast::RelOp::Le: return model::RelOp::Le;
    case ast::RelOp::Gt: return model::RelOp::Gt;
    case ast::RelOp::Ge: return model::RelOp::Ge;
    case ast::RelOp::Eq: return model::RelOp::Eq;
    case ast::RelOp::Ne: return model::RelOp::Ne;
  }
  return model::RelOp::Eq;
}

// The symbol a constant contributes to a topic's domain, or "" for numbers.
std::string symbolOf(const ast::Expr& e) {
  if (e.kind == ast::Expr::Kind::Symbol || e.kind == ast::Expr::Kind::String) return e.text;
  if (e.kind == ast::Expr::Kind::Bool) return e.intValue != 0 ? "true" : "false";
  return "";
}

}  // namespace

void Elaborator::collectTopics(const std::vector<ast::Stmt>& body, Index team) {
  for (const ast::Stmt& s : body) {
    if (s.kind == ast::Stmt::Kind::If) {
      collectTopics(s.thenBody, team);
      collectTopics(s.elseBody, team);
    } else if (s.kind == ast::Stmt::Kind::GroupBlock) {
      for (const ast::GroupArm& arm : s.arms) collectTopics(arm.body, team);
    }
    if (s.kind != ast::Stmt::Kind::Publish && s.kind != ast::Stmt::Kind::Send) continue;
    Index owner = m_.findTeam(s.topicOwner.text);
    if (owner == model::kNone) continue;  // reported when the statement is lowered
    bool reliable = s.kind == ast::Stmt::Kind::Send;
    Index topic = m_.findTopic(owner, s.topicVar.text);
    if (topic == model::kNone) {
      model::Topic t;
      t.owner = owner;
      t.var = s.topicVar.text;
      t.reliable = reliable;
      t.firstUse = s.range;
      if (const strategy::Topic* declared = m_.strategy.topic(s.topicOwner.text, s.topicVar.text)) {
        t.symbols = declared->values;
        t.buffer = declared->buffer;
      }
      m_.topics.push_back(std::move(t));
      topic = static_cast<Index>(m_.topics.size() - 1);
    } else if (m_.topics[topic].reliable != reliable) {
      Diagnostic& d = diags_.error(s.range, "topic '" + s.topicOwner.text + "." + s.topicVar.text +
                                                "' is written both by 'publish' (lossy) and 'send' (reliable); use one");
      DiagnosticEngine::note(d, m_.topics[topic].firstUse, "first written here");
      continue;
    }
    model::Topic& t = m_.topics[topic];
    t.written = true;
    std::string symbol = symbolOf(s.value);
    bool declaredDomain = m_.strategy.topic(s.topicOwner.text, s.topicVar.text) != nullptr &&
                          !m_.strategy.topic(s.topicOwner.text, s.topicVar.text)->values.empty();
    if (!symbol.empty() && !declaredDomain &&
        std::find(t.symbols.begin(), t.symbols.end(), symbol) == t.symbols.end()) {
      t.symbols.push_back(symbol);
    }
  }
}

void Elaborator::lowerServices() {
  for (Index s = 0; s < m_.services.size(); ++s) {
    const ast::Service& def = *serviceAst_[s];
    Index team = m_.services[s].team;
    m_.services[s].body = lowerBody(def.body, team, s);
    if (def.repeat) {
      model::Repeat repeat;
      repeat.isPeriod = def.repeat->isPeriod;
      if (repeat.isPeriod) {
        repeat.periodMillis = def.repeat->period.milliseconds();
        if (repeat.periodMillis == 0) diags_.error(def.repeat->period.range, "a repeat period must be longer than 0");
      } else {
        repeat.cond = lowerCond(*def.repeat->cond, team);
      }
      m_.services[s].repeat = std::move(repeat);
    }
  }
}

std::vector<model::Stmt> Elaborator::lowerBody(const std::vector<ast::Stmt>& body, Index team, Index service) {
  std::vector<model::Stmt> out;
  out.reserve(body.size());
  for (const ast::Stmt& s : body) out.push_back(lowerStmt(s, team, service));
  return out;
}

model::Stmt Elaborator::lowerStmt(const ast::Stmt& s, Index team, Index service) {
  model::Stmt out;
  out.at = s.range;
  switch (s.kind) {
    case ast::Stmt::Kind::Call:
      lowerCall(s, out, team);
      break;
    case ast::Stmt::Kind::Throw:
      out.kind = model::Stmt::Kind::Throw;
      out.event = eventIndex(m_.teams[team], s.name.text);
      m_.teams[team].events[out.event].thrownAt.push_back(s.name.range);
      break;
    case ast::Stmt::Kind::Loop:
    case ast::Stmt::Kind::Wait:
      out.kind = s.kind == ast::Stmt::Kind::Loop ? model::Stmt::Kind::Loop : model::Stmt::Kind::Wait;
      out.durationMillis = s.duration.milliseconds();
      if (out.kind == model::Stmt::Kind::Loop && out.durationMillis == 0) {
        diags_.error(s.duration.range, "a loop period must be longer than 0");
      }
      break;
    case ast::Stmt::Kind::If:
      out.kind = model::Stmt::Kind::If;
      out.cond = lowerCond(*s.cond, team);
      out.thenBody = lowerBody(s.thenBody, team, service);
      out.elseBody = lowerBody(s.elseBody, team, service);
      break;
    case ast::Stmt::Kind::Publish:
    case ast::Stmt::Kind::Send:
    case ast::Stmt::Kind::Subscribe:
    case ast::Stmt::Kind::Receive: {
      bool writes = s.kind == ast::Stmt::Kind::Publish || s.kind == ast::Stmt::Kind::Send;
      bool reliable = s.kind == ast::Stmt::Kind::Send || s.kind == ast::Stmt::Kind::Receive;
      out.kind = s.kind == ast::Stmt::Kind::Publish   ? model::Stmt::Kind::Publish
                 : s.kind == ast::Stmt::Kind::Send    ? model::Stmt::Kind::Send
                 : s.kind == ast::Stmt::Kind::Receive ? model::Stmt::Kind::Receive
                                                      : model::Stmt::Kind::Subscribe;
      out.peerTeam = teamOrError(s.peer, writes ? "as destination" : "as source");
      out.topic = topicFor(s.topicOwner, s.topicVar, reliable, writes, s.range);
      if (writes) {
        out.value = lowerExpr(s.value, team);
        std::string symbol = symbolOf(s.value);
        const strategy::Topic* declared = m_.strategy.topic(s.topicOwner.text, s.topicVar.text);
        if (!symbol.empty() && declared != nullptr && !declared->values.empty() &&
            std::find(declared->values.begin(), declared->values.end(), symbol) == declared->values.end()) {
          Diagnostic& d = diags_.error(s.value.range, "'" + symbol + "' is not a value of topic '" + s.topicOwner.text + "." +
                                                          s.topicVar.text + "' (values: " + joined(declared->values) + ")");
          DiagnosticEngine::note(d, declared->at, "the topic's values are declared here");
        }
      }
      break;
    }
    case ast::Stmt::Kind::GroupBlock:
      lowerGroupBlock(s, out, team, service);
      break;
  }
  return out;
}

Index Elaborator::topicFor(const ast::Name& owner, const ast::Name& var, bool reliable, bool writing, SourceRange at) {
  Index ownerTeam = teamOrError(owner, "in topic '" + owner.text + "." + var.text + "'");
  if (ownerTeam == model::kNone) return model::kNone;
  Index topic = m_.findTopic(ownerTeam, var.text);
  std::string name = owner.text + "." + var.text;
  if (topic == model::kNone) {
    if (writing) return model::kNone;  // a conflict already reported by collectTopics
    diags_.warning(at, reliable ? "no 'send' writes topic '" + name + "': this receive would wait for ever"
                                : "no 'publish' writes topic '" + name + "': this subscription never receives anything");
    model::Topic t;
    t.owner = ownerTeam;
    t.var = var.text;
    t.reliable = reliable;
    t.firstUse = at;
    m_.topics.push_back(std::move(t));
    topic = static_cast<Index>(m_.topics.size() - 1);
  }
  model::Topic& t = m_.topics[topic];
  if (!writing) {
    if (t.reliable != reliable && t.written) {
      Diagnostic& d = diags_.error(at, "topic '" + name + "' is written with '" + (t.reliable ? "send" : "publish") +
                                           "'; read it with '" + (t.reliable ? "receive" : "subscribe") + "'");
      DiagnosticEngine::note(d, t.firstUse, "first written here");
    }
    t.read = true;
  }
  return topic;
}

void Elaborator::lowerCall(const ast::Stmt& s, model::Stmt& out, Index team) {
  out.service = s.name.text;
  for (const ast::Expr& arg : s.args) out.args.push_back(lowerExpr(arg, team));
  if (Index composite = m_.findService(team, s.name.text); composite != model::kNone) {
    out.kind = model::Stmt::Kind::CallComposite;
    out.composite = composite;
    if (!s.args.empty()) {
      diags_.error(s.args.front().range, "'" + s.name.text + "' is a composite service and takes no arguments");
    }
    return;
  }
  if (const strategy::Service* service = m_.strategy.service(s.name.text)) {
    out.kind = service->kind == strategy::Service::Kind::Group ? model::Stmt::Kind::CallGroupService
                                                               : model::Stmt::Kind::CallPrimitive;
    out.strategyService = static_cast<Index>(service - m_.strategy.services.data());
    if (service->paramsDeclared && service->params.size() != s.args.size()) {
      Diagnostic& d = diags_.error(s.name.range, "service '" + s.name.text + "' takes " + std::to_string(service->params.size()) +
                                                     " argument" + (service->params.size() == 1 ? "" : "s") + " (" +
                                                     joined(service->params) + "), but " + std::to_string(s.args.size()) +
                                                     (s.args.size() == 1 ? " is" : " are") + " given");
      DiagnosticEngine::note(d, service->at, "declared here");
    }
    return;
  }
  std::vector<std::string> candidates;
  for (Index c : m_.teams[team].services) candidates.push_back(m_.services[c].name);
  for (const strategy::Service& sv : m_.strategy.services) candidates.push_back(sv.name);
  Diagnostic& d = diags_.error(s.name.range, withHint("undefined service '" + s.name.text +
                                                          "': not a service of team '" + m_.teams[team].name +
                                                          "' nor of the strategy",
                                                      s.name.text, candidates));
  for (const model::CompositeService& other : m_.services) {
    if (other.name == s.name.text) {
      DiagnosticEngine::note(d, other.at, "team '" + m_.teams[other.team].name + "' has a service of this name; a team calls only its own");
      break;
    }
  }
}

void Elaborator::lowerGroupBlock(const ast::Stmt& s, model::Stmt& out, Index team, Index service) {
  out.kind = model::Stmt::Kind::Groups;
  model::GroupBlock block;
  block.team = team;
  block.service = service;
  block.at = s.range;
  const model::Team& t = m_.teams[team];
  std::vector<bool> matched(m_.robots.size(), false);
  std::vector<std::string> teamTypes;
  for (Index r : t.robots) {
    if (std::find(teamTypes.begin(), teamTypes.end(), m_.robots[r].type) == teamTypes.end()) teamTypes.push_back(m_.robots[r].type);
  }

  for (const ast::GroupArm& arm : s.arms) {
    model::GroupArm lowered;
    lowered.kind = arm.kind == ast::GroupArm::Kind::Group    ? model::GroupArm::Kind::Group
                   : arm.kind == ast::GroupArm::Kind::Leader ? model::GroupArm::Kind::Leader
                                                             : model::GroupArm::Kind::Others;
    lowered.at = arm.keyword;
    if (arm.kind == ast::GroupArm::Kind::Leader) block.isLeaderBlock = true;
    if (arm.condition) {
      const ast::GroupCondition& c = *arm.condition;
      lowered.byCapability = c.kind == ast::GroupCondition::Kind::CapableOf;
      bool namesOk = true;
      for (const ast::Name& n : c.names) {
        lowered.names.push_back(n.text);
        if (!lowered.byCapability && m_.catalog.find(n.text) == nullptr) {
          diags_.error(n.range, withHint("unknown robot type '" + n.text + "'", n.text, m_.catalog.typeNames()));
          namesOk = false;
        }
        if (lowered.byCapability) {
          std::vector<std::string> known = m_.catalog.capabilityNames();
          if (std::find(known.begin(), known.end(), n.text) == known.end()) {
            diags_.error(n.range, withHint("unknown capability '" + n.text + "': no robot type of the catalog has it", n.text, known));
            namesOk = false;
          }
        }
      }
      for (Index r : t.robots) {
        const RobotType* type = m_.catalog.find(m_.robots[r].type);
        bool meets = false;
        if (lowered.byCapability) {
          meets = type != nullptr && std::all_of(lowered.names.begin(), lowered.names.end(),
                                                 [&](const std::string& cap) { return type->has(cap); });
        } else {
          meets = std::find(lowered.names.begin(), lowered.names.end(), m_.robots[r].type) != lowered.names.end();
        }
        if (meets) {
          lowered.candidates.push_back(r);
          matched[r] = true;
        }
      }
      if (namesOk && lowered.candidates.empty()) {
        diags_.error(c.range, "no robot of team '" + t.name + "' can meet this condition (the team has " +
                                  joined(teamTypes) + ")");
      }
    }
    lowered.body = lowerBody(arm.body, team, service);
    block.arms.push_back(std::move(lowered));
  }
  for (model::GroupArm& arm : block.arms) {
    if (arm.kind != model::GroupArm::Kind::Others) continue;
    for (Index r : t.robots) {
      if (block.isLeaderBlock || !matched[r]) arm.candidates.push_back(r);
    }
    if (arm.candidates.empty() && !t.robots.empty()) {
      diags_.warning(arm.at, "no robot of team '" + t.name + "' reaches 'others': every robot meets a group condition");
    }
  }
  if (block.isLeaderBlock) {
    const model::CompositeService& sv = m_.services[service];
    if (const strategy::LeaderSelection* ls = m_.strategy.leaderSelection(t.name, sv.plan, sv.name)) {
      block.leader = {ls->algorithm, ls->heartbeatMillis, ls->timeoutMillis, true,
                      ls->reelection == strategy::LeaderSelection::Reelection::Timeout,
                      ls->onModeChange == strategy::LeaderSelection::OnModeChange::Keep};
    } else {
      SourceRange at = block.arms.front().at;
      for (const model::GroupArm& arm : block.arms) {
        if (arm.kind == model::GroupArm::Kind::Leader) at = arm.at;
      }
      diags_.warning(at, "the strategy has no <leader-selection service=\"" + t.name + "." + sv.plan + "." + sv.name +
                             "\">; using lowest-id with heartbeat 1 SEC and timeout 3 SEC");
    }
  }
  m_.groupBlocks.push_back(std::move(block));
  out.groupBlock = static_cast<Index>(m_.groupBlocks.size() - 1);
}

std::unique_ptr<model::Cond> Elaborator::lowerCond(const ast::Cond& c, Index team) {
  auto out = std::make_unique<model::Cond>();
  out->at = c.range;
  switch (c.kind) {
    case ast::Cond::Kind::Not: out->kind = model::Cond::Kind::Not; break;
    case ast::Cond::Kind::And: out->kind = model::Cond::Kind::And; break;
    case ast::Cond::Kind::Or: out->kind = model::Cond::Kind::Or; break;
    case ast::Cond::Kind::Test: out->kind = model::Cond::Kind::Test; break;
    case ast::Cond::Kind::Compare: out->kind = model::Cond::Kind::Compare; break;
  }
  if (c.left) out->left = lowerCond(*c.left, team);
  if (c.right) out->right = lowerCond(*c.right, team);
  if (c.kind != ast::Cond::Kind::Test && c.kind != ast::Cond::Kind::Compare) return out;

  std::size_t errorsBefore = diags_.errorCount();
  out->lhs = lowerExpr(c.lhs, team);
  if (c.kind == ast::Cond::Kind::Compare) {
    out->op = relOp(c.op);
    out->rhs = lowerExpr(c.rhs, team);
  }
  if (diags_.errorCount() != errorsBefore) return out;  // one error per operand is enough
  // Check the comparison against the abstract domain the checker will use.
  const model::Expr& v = out->lhs;
  if (v.kind != model::Expr::Kind::Value) {
    if (c.kind == ast::Cond::Kind::Test && v.kind != model::Expr::Kind::Bool) {
      diags_.error(c.lhs.range, "a condition must test a value 'Team.value' or compare two expressions");
    }
    return out;
  }
  std::string name = m_.teams[v.owner].name + "." + v.var;
  const model::Expr& k = out->rhs;
  if (v.valueKind == model::ValueKind::Sensed) {
    const strategy::Value* value = m_.strategy.value(m_.teams[v.owner].name, v.var);
    const strategy::Domain& d = value->domain;
    bool numeric = k.kind == model::Expr::Kind::Int || k.kind == model::Expr::Kind::Number;
    double constant = k.kind == model::Expr::Kind::Int ? static_cast<double>(k.intValue) : k.numberValue;
    if (c.kind == ast::Cond::Kind::Test) {
      if (d.kind != strategy::Domain::Kind::Bool) {
        diags_.error(c.lhs.range, "value '" + name + "' is not boolean in the strategy; compare it (for example '" + name + " < 10')");
      }
    } else if (d.kind == strategy::Domain::Kind::Threshold) {
      if (!numeric) {
        diags_.error(c.rhs.range, "value '" + name + "' is numeric; compare it with a number");
      } else if (std::find(d.thresholds.begin(), d.thresholds.end(), constant) == d.thresholds.end()) {
        std::vector<std::string> ts;
        for (double t : d.thresholds) ts.push_back(formatNumber(t));
        Diagnostic& diag = diags_.error(c.rhs.range, "the strategy's abstract domain of '" + name + "' has no threshold " +
                                                         formatNumber(constant) + " (thresholds: " + joined(ts) + ")");
        DiagnosticEngine::note(diag, d.at, "domain declared here");
      }
    } else if (d.kind == strategy::Domain::Kind::Range) {
      if (k.kind != model::Expr::Kind::Int) diags_.error(c.rhs.range, "value '" + name + "' is an integer range; compare it with an integer");
    } else if (d.kind == strategy::Domain::Kind::Enum) {
      if (k.kind != model::Expr::Kind::Symbol && k.kind != model::Expr::Kind::String) {
        diags_.error(c.rhs.range, "value '" + name + "' is one of " + joined(d.values) + "; compare it with one of them");
      } else if (std::find(d.values.begin(), d.values.end(), k.text) == d.values.end()) {
        diags_.error(c.rhs.range, "'" + k.text + "' is not a value of '" + name + "' (values: " + joined(d.values) + ")");
      }
    } else if (k.kind != model::Expr::Kind::Bool) {
      diags_.error(c.rhs.range, "value '" + name + "' is boolean; compare it with true or false, or test it alone");
    }
  } else if (v.valueKind == model::ValueKind::Knowledge) {
    if (c.kind == ast::Cond::Kind::Compare && k.kind != model::Expr::Kind::Int) {
      diags_.error(c.rhs.range, "knowledge '" + name + "' is a set of facts; compare the number of facts held with an integer");
    }
  } else if (v.valueKind == model::ValueKind::Topic && v.topic != model::kNone) {
    const model::Topic& t = m_.topics[v.topic];
    if (c.kind == ast::Cond::Kind::Compare && (k.kind == model::Expr::Kind::Symbol || k.kind == model::Expr::Kind::String) &&
        !t.symbols.empty() && std::find(t.symbols.begin(), t.symbols.end(), k.text) == t.symbols.end()) {
      diags_.warning(c.rhs.range, "topic '" + name + "' never carries '" + k.text + "' (it carries " + joined(t.symbols) + ")");
    }
  }
  return out;
}

model::Expr Elaborator::lowerExpr(const ast::Expr& e, Index team) {
  model::Expr out;
  out.at = e.range;
  out.intValue = e.intValue;
  out.numberValue = e.numberValue;
  out.text = e.text;
  switch (e.kind) {
    case ast::Expr::Kind::Int: out.kind = model::Expr::Kind::Int; return out;
    case ast::Expr::Kind::Number: out.kind = model::Expr::Kind::Number; return out;
    case ast::Expr::Kind::String: out.kind = model::Expr::Kind::String; return out;
    case ast::Expr::Kind::Bool: out.kind = model::Expr::Kind::Bool; return out;
    case ast::Expr::Kind::Symbol: out.kind = model::Expr::Kind::Symbol; return out;
    case ast::Expr::Kind::Value: break;
  }
  out.kind = model::Expr::Kind::Value;
  out.var = e.var.text;
  out.owner = teamOrError(e.owner, "in value '" + e.owner.text + "." + e.var.text + "'");
  if (out.owner == model::kNone) {
    out.kind = model::Expr::Kind::Symbol;  // keep the model well-formed; the error is reported
    return out;
  }
  (void)team;
  if (m_.strategy.value(e.owner.text, e.var.text) != nullptr) {
    out.valueKind = model::ValueKind::Sensed;
    return out;
  }
  if (Index topic = m_.findTopic(out.owner, e.var.text); topic != model::kNone) {
    out.valueKind = model::ValueKind::Topic;
    out.topic = topic;
    m_.topics[topic].read = true;
    return out;
  }
  for (const strategy::Service& service : m_.strategy.services) {
    for (const strategy::Knowledge& k : service.knowledge) {
      if (k.name != e.var.text) continue;
      out.valueKind = model::ValueKind::Knowledge;
      return out;
    }
  }
  std::vector<std::string> candidates;
  for (const strategy::Value& v : m_.strategy.values) {
    if (v.team == e.owner.text) candidates.push_back(v.var);
  }
  for (const model::Topic& t : m_.topics) {
    if (t.owner == out.owner) candidates.push_back(t.var);
  }
  diags_.error(e.range, withHint("undefined value '" + e.owner.text + "." + e.var.text +
                                     "': declare it in the strategy (<value name=\"" + e.owner.text + "." + e.var.text +
                                     "\">) or publish it",
                                 e.var.text, candidates));
  out.kind = model::Expr::Kind::Symbol;
  return out;
}

}  // namespace semo::detail
