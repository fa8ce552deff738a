// The mission-to-IR translation, checked through the explicit engine on small missions whose
// answers can be worked out by hand.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/semantics/ir_text.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo {
namespace {

const std::string kStrategy = SEMO_SOURCE_DIR "/tests/diagnostics/common/strategy.xml";

struct Translated {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  std::optional<ir::Model> model;
};

std::unique_ptr<Translated> translateText(const std::string& mission, const std::string& name) {
  auto t = std::make_unique<Translated>();
  std::string path = testing::TempDir() + "/" + name + ".semo";
  std::ofstream(path) << mission;
  auto m = loadMission({path, kStrategy, std::nullopt}, t->sources, t->diags);
  if (m) t->model = translate(*m, {}, t->sources, t->diags);
  return t;
}

std::unique_ptr<Translated> translateScouting() {
  auto t = std::make_unique<Translated>();
  auto m = loadMission({SEMO_SOURCE_DIR "/specs/examples/scouting/scouting.semo", SEMO_SOURCE_DIR "/specs/examples/scouting/strategy.xml", std::nullopt},
                       t->sources, t->diags);
  if (m) t->model = translate(*m, {}, t->sources, t->diags);
  return t;
}

const checker::PropertyResult* find(const checker::SearchResult& r, const std::string& prefix) {
  for (const checker::PropertyResult& p : r.properties) {
    if (p.name.rfind(prefix, 0) == 0) return &p;
  }
  return nullptr;
}

std::string stepLabel(const ir::Model& m, const checker::Step& s) { return m.rules[s.rule].label; }

const char* kLoneCandidate = R"(
Team: TurtlebotBurger burger, Ev3Robot ev3[2]
Team.Action.Go { [[ group (instance of TurtlebotBurger) { beep() } others { move("x") } ]] }
Team.GO { set(Action, Go) }
Team.main { case (GO): default: mode = GO }
verify { assume crash <= CRASH in Team  check group_formation }
)";

std::string withCrash(int n) {
  std::string text = kLoneCandidate;
  text.replace(text.find("CRASH"), 5, std::to_string(n));
  return text;
}

TEST(Translate, OneCrashBreaksAGroupWithOneCandidate) {
  auto t = translateText(withCrash(1), "lone1");
  ASSERT_TRUE(t->model.has_value());
  checker::SearchResult r = checker::checkSafety(*t->model, {});
  const checker::PropertyResult* p = find(r, "group_formation");
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->verdict, checker::Verdict::Violated);
  // Shortest: every robot starts about to form the block, and the only Burger crashes.
  ASSERT_EQ(p->counterexample->steps.size(), 1u);
  bool burgerCrashes = false;
  for (const checker::Step& s : p->counterexample->steps) {
    const ir::Rule& rule = t->model->rules[s.rule];
    burgerCrashes = burgerCrashes || (rule.kind == ir::RuleKind::Crash && t->model->robots[static_cast<std::size_t>(rule.robot)] == "burger");
  }
  EXPECT_TRUE(burgerCrashes);
}

TEST(Translate, WithoutCrashesTheGroupCanAlwaysBeFormed) {
  auto t = translateText(withCrash(0), "lone0");
  ASSERT_TRUE(t->model.has_value());
  checker::SearchResult r = checker::checkSafety(*t->model, {});
  EXPECT_TRUE(r.complete);
  ASSERT_NE(find(r, "group_formation"), nullptr);
  EXPECT_EQ(find(r, "group_formation")->verdict, checker::Verdict::Proven);
  EXPECT_EQ(t->model->assumptions.front(), "no crash");
}

TEST(Translate, AReceiveNobodyServesDeadlocksAtOnce) {
  auto t = translateText(R"(
Master: iRobotCreate boss
Team: TurtlebotBurger burger
Master.Listen.Collect { receive(Team, Team.report) }
Master.RUN { set(Listen, Collect) }
Master.main { case (RUN): default: mode = RUN }
Team.Action.Go { move("x") }
Team.GO { set(Action, Go) }
Team.main { case (GO): default: mode = GO }
verify { check deadlock_freedom }
)", "deadlock");
  ASSERT_TRUE(t->model.has_value());
  checker::SearchResult r = checker::checkSafety(*t->model, {});
  const checker::PropertyResult* p = find(r, "deadlock_freedom");
  ASSERT_NE(p, nullptr);
  // The burger's loop (move, default back to GO) always has a step, so no deadlock at all...
  EXPECT_EQ(p->verdict, checker::Verdict::Proven);
}

TEST(Translate, ABlockedReceiverWithEveryoneElseDoneIsADeadlock) {
  auto t = translateText(R"(
Master: iRobotCreate boss
Team: TurtlebotBurger burger
Master.Listen.Collect { receive(Team, Team.report) receive(Team, Team.report) }
Master.RUN { set(Listen, Collect) }
Master.main { case (RUN): default: mode = RUN }
Team.Action.Go { send(Master, Team.report = 1) }
Team.GO { set(Action, Go) }
Team.main { case (GO): catch(never): mode = GO }
verify { check deadlock_freedom }
)", "deadlock2");
  ASSERT_TRUE(t->model.has_value()) << (t->diags.diagnostics().empty() ? "" : t->diags.format(t->diags.diagnostics().front()));
  checker::SearchResult r = checker::checkSafety(*t->model, {});
  const checker::PropertyResult* p = find(r, "deadlock_freedom");
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->verdict, checker::Verdict::Violated);
  // The burger sends once, the master takes it and waits for a second report that never comes.
  ASSERT_EQ(p->counterexample->steps.size(), 2u);
  EXPECT_EQ(stepLabel(*t->model, p->counterexample->steps[0]), "sends report");
  EXPECT_EQ(stepLabel(*t->model, p->counterexample->steps[1]), "receives report");
}

TEST(Translate, KnowledgeIsCountedAndShared) {
  auto t = translateText(R"(
Team: Ev3Robot ev3[2]
Team.Action.Search { searchPaper() }
Team.SEARCH { set(Action, Search) }
Team.DONE { set(Action, Search) }
Team.main { case (SEARCH): default: mode = DONE }
)", "knowledge");
  ASSERT_TRUE(t->model.has_value());
  auto knows = t->model->find("ev3_0.knows.papers");
  ASSERT_TRUE(knows.has_value());
  EXPECT_EQ(t->model->variables[*knows].max, 3);  // red, yellow, blue
  std::size_t learns = 0;
  for (const ir::Rule& r : t->model->rules) learns += r.label.rfind("learns papers", 0) == 0 ? 1 : 0;
  EXPECT_EQ(learns, 2u * 3u);  // each robot from the other, to 1, 2 or 3 facts
  checker::SearchResult r = checker::checkSafety(*t->model, {});
  EXPECT_TRUE(r.complete);
}

// The operands of a chain of one connective, whatever its bracketing.
void flatten(const ir::Expr& e, ir::Op op, std::vector<const ir::Expr*>& out) {
  if (e.op == op) {
    for (const ir::Expr& a : e.args) flatten(a, op, out);
  } else {
    out.push_back(&e);
  }
}

std::size_t nodes(const ir::Expr& e) {
  std::size_t n = 1;
  for (const ir::Expr& a : e.args) n += nodes(a);
  return n;
}

std::string searchingTeam(int robots) {
  return "Team: Ev3Robot ev3[" + std::to_string(robots) + R"(]
Team.Action.Search { searchPaper() }
Team.SEARCH { set(Action, Search) }
Team.DONE { set(Action, Search) }
Team.main { case (SEARCH): default: mode = DONE }
verify { check knowledge_convergence }
)";
}

const ir::Expr& convergenceAtom(const ir::Model& m) {
  for (const ir::Property& p : m.properties) {
    if (p.name == "knowledge_convergence[searchPaper.papers]") {
      // always eventually ATOM
      return p.formula.args.at(0).args.at(0).atom;
    }
  }
  throw std::runtime_error("no knowledge_convergence");
}

// A large team's knowledge_convergence says "some count is held by every robot working in the
// service" (linear in the team), a small team's "any two working robots hold as many" (one term per
// pair). The two must be the same condition: on random states, the large team's formula agrees with
// the pairwise one built from its own "working in the service" conditions.
TEST(Translate, KnowledgeConvergenceOfALargeTeamIsThePairwiseConditionInLinearSize) {
  auto small = translateText(searchingTeam(3), "converge3");
  ASSERT_TRUE(small->model.has_value());
  EXPECT_NE(convergenceAtom(*small->model).op, ir::Op::Or) << "3 robots, 3 facts: the pairs (3 terms) are fewer than 4 counts x 3";

  const int n = 12;  // more than 2 * 3 facts + 3
  auto large = translateText(searchingTeam(n), "converge12");
  ASSERT_TRUE(large->model.has_value());
  const ir::Model& m = *large->model;
  const ir::Expr& atom = convergenceAtom(m);
  std::vector<const ir::Expr*> counts;
  flatten(atom, ir::Op::Or, counts);
  ASSERT_EQ(counts.size(), 4u);  // 0, 1, 2 or 3 papers
  std::vector<const ir::Expr*> held;
  flatten(*counts[0], ir::Op::And, held);
  ASSERT_EQ(held.size(), static_cast<std::size_t>(n));
  std::vector<ir::Expr> working, knows;
  for (const ir::Expr* h : held) {
    ASSERT_EQ(h->op, ir::Op::Implies);
    ASSERT_EQ(h->args[1].op, ir::Op::Eq);
    working.push_back(h->args[0]);
    knows.push_back(h->args[1].args[0]);
  }
  std::vector<ir::Expr> pairs;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      pairs.push_back(ir::Expr::binary(ir::Op::Implies, ir::conjunction({working[i], working[j]}), ir::Expr::binary(ir::Op::Eq, knows[i], knows[j])));
    }
  }
  const ir::Expr pairwise = ir::conjunction(std::move(pairs));
  EXPECT_LT(nodes(atom) * 2, nodes(pairwise)) << "linear against quadratic in the team";

  const checker::Program linear(atom), reference(pairwise);
  std::mt19937 rng(7);
  std::vector<checker::Value> values(m.variables.size());
  int agreed = 0, disagreed = 0;
  for (int sample = 0; sample < 20000; ++sample) {
    // Each condition of working in the service holds half of the time, so that several robots work
    // in it at once; every other variable anywhere in its range.
    for (ir::VarId v = 0; v < m.variables.size(); ++v) {
      values[v] = std::uniform_int_distribution<checker::Value>(m.variables[v].min, m.variables[v].max)(rng);
    }
    // Most robots hold one count, so that the working ones often agree.
    const checker::Value common = static_cast<checker::Value>(rng() % 4);
    for (const ir::Expr& k : knows) {
      if (k.op == ir::Op::Var && rng() % 4 != 0) values[static_cast<std::size_t>(k.value)] = common;
    }
    for (const ir::Expr& w : working) {
      std::vector<const ir::Expr*> parts;
      flatten(w, ir::Op::And, parts);
      for (const ir::Expr* c : parts) {
        if (rng() % 2 == 0) continue;
        if (c->op == ir::Op::Var) values[static_cast<std::size_t>(c->value)] = 1;
        if (c->op == ir::Op::Eq && c->args[0].op == ir::Op::Var && c->args[1].op == ir::Op::Const) {
          values[static_cast<std::size_t>(c->args[0].value)] = c->args[1].value;
        }
      }
    }
    const checker::Value a = linear.eval(values.data()), b = reference.eval(values.data());
    ASSERT_EQ(a != 0, b != 0) << "sample " << sample;
    (a != 0 ? agreed : disagreed) += 1;
  }
  // Both outcomes were met often: the comparison is not vacuous.
  EXPECT_GT(agreed, 500);
  EXPECT_GT(disagreed, 500);
}

TEST(Translate, TextFormRoundTripsAndExploresTheSameStates) {
  auto t = translateText(withCrash(1), "roundtrip");
  ASSERT_TRUE(t->model.has_value());
  std::string text = ir::toText(*t->model);
  SourceManager sources;
  DiagnosticEngine diags(sources);
  auto again = ir::parseText(sources, sources.add("m.ir", text), diags);
  ASSERT_TRUE(again.has_value()) << (diags.diagnostics().empty() ? "" : diags.format(diags.diagnostics().front()));
  EXPECT_EQ(ir::toText(*again), text);
  EXPECT_EQ(checker::checkSafety(*again, {}).states, checker::checkSafety(*t->model, {}).states);
}

TEST(Translate, ALeaderThatLeavesItsBlockStopsLeading) {
  // Scouting: the ev3s elect a reporting leader (ReportPapers); a robot whose mode changes, or
  // that leaves the block, no longer leads (no more heartbeats), so the other can take over.
  const auto scouting = translateScouting();
  const std::optional<ir::Model>& model = scouting->model;
  ASSERT_TRUE(model.has_value());
  std::optional<ir::VarId> leads;
  for (ir::VarId v = 0; v < model->variables.size(); ++v) {
    if (model->variables[v].name.rfind("ev3_0.leads.ReportPapers", 0) == 0) leads = v;
  }
  ASSERT_TRUE(leads.has_value());
  // Whether the rule sets `leads` to 0 in every state where it is taken (a mode change is written
  // as a choice over the current mode, which leaves `leads` alone where the mode does not change).
  auto clears = [&](const ir::Rule& r, bool always) {
    for (const ir::Branch& b : r.branches) {
      for (const ir::Assignment& a : b.assignments) {
        if (a.var != *leads) continue;
        if (a.value.op == ir::Op::Const) return a.value.value == 0;
        return !always;
      }
    }
    return false;
  };
  std::size_t modeChanges = 0, exits = 0;
  for (const ir::Rule& r : model->rules) {
    if (r.robot < 0 || model->robots[static_cast<std::size_t>(r.robot)] != "ev3_0") continue;
    bool changesMode = false;
    for (const ir::Branch& b : r.branches) {
      for (const ir::Assignment& a : b.assignments) changesMode = changesMode || model->variables[a.var].name == "ev3_0.mode";
    }
    if (changesMode) {
      ++modeChanges;
      EXPECT_TRUE(clears(r, false)) << r.name << ": " << r.label;
    }
    if (r.label.find("leaves the group block") != std::string::npos && r.name.rfind("ev3_0.Report.", 0) == 0) {
      ++exits;
      EXPECT_TRUE(clears(r, true)) << r.name;
    }
  }
  EXPECT_GT(modeChanges, 3u);
  EXPECT_EQ(exits, 1u);
}

TEST(Translate, ALeaderKeptAcrossModesGoesOnLeadingWhereItsServiceRunsAgain) {
  // Scouting's strategy keeps the light watch's leader across modes (on-mode-change="keep"): a
  // Burger entering SEARCH_MODE or HIDE_MODE, which both set WatchLight, keeps its `leads`; one
  // entering a mode without the Light plan (RETURN_MODE, RC_MODE, AUTODRIVE_MODE) or crashing
  // stops leading.
  const auto scouting = translateScouting();
  const std::optional<ir::Model>& model = scouting->model;
  ASSERT_TRUE(model.has_value());
  std::optional<ir::VarId> leads, mode;
  for (ir::VarId v = 0; v < model->variables.size(); ++v) {
    if (model->variables[v].name.rfind("burger_0.leads.WatchLight", 0) == 0) leads = v;
    if (model->variables[v].name == "burger_0.mode") mode = v;
  }
  ASSERT_TRUE(leads.has_value() && mode.has_value());
  const std::vector<std::string>& modes = model->variables[*mode].valueNames;
  std::size_t kept = 0, released = 0;
  for (const ir::Rule& r : model->rules) {
    for (const ir::Branch& b : r.branches) {
      std::optional<std::int32_t> target;
      bool assignsLeads = false;
      for (const ir::Assignment& a : b.assignments) {
        if (a.var == *mode && a.value.op == ir::Op::Const) target = a.value.value;
        if (a.var == *leads) assignsLeads = true;
      }
      if (!target || r.label.find("leads the group") != std::string::npos) continue;
      const std::string& name = modes.at(static_cast<std::size_t>(*target));
      if (name == "SEARCH_MODE" || name == "HIDE_MODE") {
        ++kept;
        EXPECT_FALSE(assignsLeads) << r.name << ": " << r.label;
      } else {
        ++released;
        EXPECT_TRUE(assignsLeads) << r.name << ": " << r.label;
      }
    }
  }
  EXPECT_GE(kept, 3u);  // into SEARCH_MODE after the approach, and both ways by its own light events
  EXPECT_GE(released, 2u);
}

TEST(Translate, ALeaderIsElectedOnlyAmongTheRobotsFormingTheBlock) {
  // scout_0 reaches the relay block while scout_1 still drives. Electing scout_1 then (the best
  // candidate, but not there) made a leader that its own mode change cleared a moment later;
  // scout_0 timed out, scout_1 formed the block anew and led, and scout_0 took over: two leaders.
  auto t = translateText(R"(
Scouts: Ev3Robot scout[2]
Scouts.Drive.Go { move("x") }
Scouts.Report.Relay {
  [[ leader (capable of ColorSensor) { loop(5 SEC) move("north") }
     others { loop(1 SEC) move("south") } ]]
}
Scouts.DRIVE { set(Drive, Go) }
Scouts.RELAY { set(Report, Relay) }
Scouts.main { case (DRIVE): default: mode = RELAY  case (RELAY): default: mode = RELAY }
verify { assume crash <= 1 in Scouts  check unique_leader }
)", "late_member");
  ASSERT_TRUE(t->model.has_value());
  checker::SearchResult r = checker::checkSafety(*t->model, {});
  const checker::PropertyResult* unique = find(r, "unique_leader");
  ASSERT_NE(unique, nullptr);
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(unique->verdict, checker::Verdict::Proven);
}

}  // namespace
}  // namespace semo
