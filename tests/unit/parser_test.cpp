// One test per grammar construct of specs/language.md, plus recovery.
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace semo {
namespace {

using test::parse;

TEST(Parser, TeamDeclarationsWithArraysAndLists) {
  auto p = parse("MasterTeam: iRobotCreate irobot\nSlaveTeam: TurtlebotBurger burger[2], Ev3Robot ev3[3]\n");
  ASSERT_FALSE(p->diags.hasErrors()) << p->messages().front();
  ASSERT_EQ(p->mission.teams.size(), 2u);
  const ast::TeamDecl& slave = p->mission.teams[1];
  EXPECT_EQ(slave.team.text, "SlaveTeam");
  ASSERT_EQ(slave.robots.size(), 2u);
  EXPECT_EQ(slave.robots[0].type.text, "TurtlebotBurger");
  EXPECT_EQ(slave.robots[0].name.text, "burger");
  EXPECT_EQ(slave.robots[0].count, 2);
  EXPECT_EQ(slave.robots[1].count, 3);
  EXPECT_FALSE(p->mission.teams[0].robots[0].count.has_value());
  EXPECT_EQ(slave.robots[1].name.range.begin.line, 2u);
  EXPECT_EQ(slave.robots[1].name.range.begin.column, 48u);
}

TEST(Parser, CompositeServiceWithRepeatWhileCondition) {
  auto p = parse("T: A a\nT.Action.Go {\n  move(\"x\", 3)\n  throw done } repeat (T.not_arrived)\n");
  ASSERT_FALSE(p->diags.hasErrors());
  ASSERT_EQ(p->mission.services.size(), 1u);
  const ast::Service& s = p->mission.services[0];
  EXPECT_EQ(s.team.text, "T");
  EXPECT_EQ(s.plan.text, "Action");
  EXPECT_EQ(s.name.text, "Go");
  ASSERT_EQ(s.body.size(), 2u);
  EXPECT_EQ(s.body[0].kind, ast::Stmt::Kind::Call);
  EXPECT_EQ(s.body[0].name.text, "move");
  ASSERT_EQ(s.body[0].args.size(), 2u);
  EXPECT_EQ(s.body[0].args[0].kind, ast::Expr::Kind::String);
  EXPECT_EQ(s.body[0].args[0].text, "x");
  EXPECT_EQ(s.body[0].args[1].intValue, 3);
  EXPECT_EQ(s.body[1].kind, ast::Stmt::Kind::Throw);
  EXPECT_EQ(s.body[1].name.text, "done");
  ASSERT_TRUE(s.repeat.has_value());
  EXPECT_FALSE(s.repeat->isPeriod);
  EXPECT_EQ(s.repeat->cond->kind, ast::Cond::Kind::Test);
  EXPECT_EQ(s.repeat->cond->lhs.owner.text, "T");
  EXPECT_EQ(s.repeat->cond->lhs.var.text, "not_arrived");
}

TEST(Parser, RepeatWithPeriodAndDurationUnits) {
  auto p = parse("T: A a\nT.P.S { wait(500 MSEC); wait(2 SEC); wait(1 MIN) } repeat (10 SEC)\n");
  ASSERT_FALSE(p->diags.hasErrors());
  const ast::Service& s = p->mission.services[0];
  ASSERT_EQ(s.body.size(), 3u);
  EXPECT_EQ(s.body[0].duration.milliseconds(), 500);
  EXPECT_EQ(s.body[1].duration.milliseconds(), 2000);
  EXPECT_EQ(s.body[2].duration.milliseconds(), 60000);
  ASSERT_TRUE(s.repeat && s.repeat->isPeriod);
  EXPECT_EQ(s.repeat->period.milliseconds(), 10000);
}

TEST(Parser, EveryGeneralStatement) {
  auto p = parse(
      "T: A a\n"
      "T.P.S {\n"
      "  loop(2 SEC)\n"
      "  if (T.light < 200 and not T.dark or T.x == sym) beep() else { wait(1 SEC); throw e }\n"
      "  publish(T, T.Message = suggestHiding)\n"
      "  subscribe(T, T.Message)\n"
      "  send(U, T.report = 4.5)\n"
      "  receive(U, U.order);\n"
      "}\n");
  ASSERT_FALSE(p->diags.hasErrors()) << p->messages().front();
  const std::vector<ast::Stmt>& b = p->mission.services[0].body;
  ASSERT_EQ(b.size(), 6u);
  EXPECT_EQ(b[0].kind, ast::Stmt::Kind::Loop);
  EXPECT_EQ(b[0].duration.milliseconds(), 2000);
  ASSERT_EQ(b[1].kind, ast::Stmt::Kind::If);
  // `or` binds loosest, then `and`, then `not`.
  const ast::Cond& c = *b[1].cond;
  ASSERT_EQ(c.kind, ast::Cond::Kind::Or);
  ASSERT_EQ(c.left->kind, ast::Cond::Kind::And);
  EXPECT_EQ(c.left->left->kind, ast::Cond::Kind::Compare);
  EXPECT_EQ(c.left->left->op, ast::RelOp::Lt);
  EXPECT_EQ(c.left->right->kind, ast::Cond::Kind::Not);
  EXPECT_EQ(c.right->rhs.kind, ast::Expr::Kind::Symbol);
  ASSERT_EQ(b[1].thenBody.size(), 1u);
  EXPECT_TRUE(b[1].hasElse);
  ASSERT_EQ(b[1].elseBody.size(), 2u);
  EXPECT_EQ(b[1].elseBody[1].kind, ast::Stmt::Kind::Throw);
  EXPECT_EQ(b[2].kind, ast::Stmt::Kind::Publish);
  EXPECT_EQ(b[2].peer.text, "T");
  EXPECT_EQ(b[2].topicOwner.text, "T");
  EXPECT_EQ(b[2].topicVar.text, "Message");
  EXPECT_EQ(b[2].value.text, "suggestHiding");
  EXPECT_EQ(b[3].kind, ast::Stmt::Kind::Subscribe);
  EXPECT_EQ(b[4].kind, ast::Stmt::Kind::Send);
  EXPECT_EQ(b[4].value.kind, ast::Expr::Kind::Number);
  EXPECT_DOUBLE_EQ(b[4].value.numberValue, 4.5);
  EXPECT_EQ(b[5].kind, ast::Stmt::Kind::Receive);
  EXPECT_EQ(b[5].peer.text, "U");
}

TEST(Parser, PeerGroupsWithInstanceOfAndOthers) {
  auto p = parse(
      "T: A a\n"
      "T.P.S {\n"
      "  [[ group (instance of A, B) { beep() }\n"
      "     group (capable of Camera Lidar) { look() }\n"
      "     others { rest() } ]]\n"
      "}\n");
  ASSERT_FALSE(p->diags.hasErrors()) << p->messages().front();
  const ast::Stmt& g = p->mission.services[0].body[0];
  ASSERT_EQ(g.kind, ast::Stmt::Kind::GroupBlock);
  ASSERT_EQ(g.arms.size(), 3u);
  EXPECT_EQ(g.arms[0].kind, ast::GroupArm::Kind::Group);
  EXPECT_EQ(g.arms[0].condition->kind, ast::GroupCondition::Kind::InstanceOf);
  EXPECT_EQ(g.arms[0].condition->names.size(), 2u);
  EXPECT_EQ(g.arms[1].condition->kind, ast::GroupCondition::Kind::CapableOf);
  ASSERT_EQ(g.arms[1].condition->names.size(), 2u);  // space-separated, as in the paper's BNF
  EXPECT_EQ(g.arms[1].condition->names[1].text, "Lidar");
  EXPECT_EQ(g.arms[2].kind, ast::GroupArm::Kind::Others);
  EXPECT_FALSE(g.arms[2].condition.has_value());
}

TEST(Parser, LeaderGroup) {
  auto p = parse("T: A a\nT.P.S { [[ leader (capable of Radio) { report() } others { follow() } ]] }\n");
  ASSERT_FALSE(p->diags.hasErrors());
  const ast::Stmt& g = p->mission.services[0].body[0];
  ASSERT_EQ(g.arms.size(), 2u);
  EXPECT_EQ(g.arms[0].kind, ast::GroupArm::Kind::Leader);
  EXPECT_EQ(g.arms[0].keyword.begin.column, 12u);
}

TEST(Parser, ModeWithSets) {
  auto p = parse("T: A a\nT.AUTODRIVE_MODE {\n  set(Listen, CommOperator)\n  set(Action, ApproachDestination) }\n");
  ASSERT_FALSE(p->diags.hasErrors());
  ASSERT_EQ(p->mission.modes.size(), 1u);
  const ast::ModeDef& m = p->mission.modes[0];
  EXPECT_EQ(m.mode.text, "AUTODRIVE_MODE");
  ASSERT_EQ(m.sets.size(), 2u);
  EXPECT_EQ(m.sets[1].plan.text, "Action");
  EXPECT_EQ(m.sets[1].service.text, "ApproachDestination");
}

TEST(Parser, MainWithCatchAndDefault) {
  auto p = parse(
      "T: A a\nT.main {\n  case (A_MODE):\n    catch(e1): mode = B_MODE\n    catch(e2): mode = C_MODE\n"
      "  case (B_MODE):\n    default: mode = A_MODE }\n");
  ASSERT_FALSE(p->diags.hasErrors());
  ASSERT_EQ(p->mission.mains.size(), 1u);
  const ast::MainDef& m = p->mission.mains[0];
  ASSERT_EQ(m.cases.size(), 2u);
  EXPECT_EQ(m.cases[0].mode.text, "A_MODE");
  ASSERT_EQ(m.cases[0].transitions.size(), 2u);
  EXPECT_EQ(m.cases[0].transitions[1].event.text, "e2");
  EXPECT_EQ(m.cases[0].transitions[1].target.text, "C_MODE");
  EXPECT_TRUE(m.cases[1].transitions[0].isDefault);
}

TEST(Parser, VerifyBlockWithEveryItem) {
  auto p = parse(
      "T: A a\n"
      "verify {\n"
      "  assume crash <= 1 in T\n"
      "  assume crash <= 2\n"
      "  assume loss publish, events, knowledge\n"
      "  assume unfair loss\n"
      "  check group_formation, unique_leader, leader_reelection, knowledge_convergence,\n"
      "        mode_agreement, deadlock_freedom, buffer_bounds\n"
      "  property p1: always not (T.mode == SEARCH and T.Message == hide)\n"
      "  property p2: T.x == 1 implies next T.y until eventually a_0.alive\n"
      "}\n");
  ASSERT_FALSE(p->diags.hasErrors()) << p->messages().front();
  ASSERT_EQ(p->mission.verifies.size(), 1u);
  const ast::VerifyBlock& v = p->mission.verifies[0];
  ASSERT_EQ(v.crashes.size(), 2u);
  EXPECT_EQ(v.crashes[0].budget, 1);
  EXPECT_EQ(v.crashes[0].team->text, "T");
  EXPECT_FALSE(v.crashes[1].team.has_value());
  ASSERT_EQ(v.losses.size(), 3u);
  EXPECT_EQ(v.losses[0].text, "publish");
  EXPECT_EQ(v.fairness->text, "unfair");
  EXPECT_EQ(v.checks.size(), 7u);
  ASSERT_EQ(v.properties.size(), 2u);
  const ast::Ltl& f1 = *v.properties[0].formula;
  ASSERT_EQ(f1.kind, ast::Ltl::Kind::Always);
  ASSERT_EQ(f1.left->kind, ast::Ltl::Kind::Not);
  ASSERT_EQ(f1.left->left->kind, ast::Ltl::Kind::And);
  EXPECT_EQ(f1.left->left->left->op, ast::RelOp::Eq);
  // implies binds loosest, then until; next/eventually are unary.
  const ast::Ltl& f2 = *v.properties[1].formula;
  ASSERT_EQ(f2.kind, ast::Ltl::Kind::Implies);
  EXPECT_EQ(f2.left->kind, ast::Ltl::Kind::Atom);
  ASSERT_EQ(f2.right->kind, ast::Ltl::Kind::Until);
  EXPECT_EQ(f2.right->left->kind, ast::Ltl::Kind::Next);
  EXPECT_EQ(f2.right->right->kind, ast::Ltl::Kind::Eventually);
  EXPECT_EQ(f2.right->right->left->lhs.var.text, "alive");
}

TEST(Parser, TeamDeclarationsMayFollowDefinitions) {
  auto p = parse("T: A a\nT.P.S { beep() }\nU: B b\n");
  ASSERT_FALSE(p->diags.hasErrors());
  EXPECT_EQ(p->mission.teams.size(), 2u);
}

TEST(Parser, CommentsAndOptionalSemicolons) {
  auto p = parse("# header\nT: A a # trailing\nT.P.S { beep(); beep() ; # c\n wait(1 SEC); }\n");
  ASSERT_FALSE(p->diags.hasErrors());
  EXPECT_EQ(p->mission.services[0].body.size(), 3u);
}

TEST(Parser, RecoversAndReportsSeveralErrors) {
  auto p = parse(
      "T: A a\n"
      "T.P.S {\n"
      "  move(\"x\" 3)\n"   // missing ','
      "  beep()\n"
      "  publish(T T.m = 1)\n"  // missing ','
      "}\n"
      "T.M { set(P S) }\n"  // missing ','
      "T.main { case (M): default: mode = M }\n");
  std::vector<std::string> m = p->messages();
  ASSERT_EQ(m.size(), 3u) << ::testing::PrintToString(m);
  EXPECT_EQ(m[0], "3:12: expected ',' or ')' in the argument list, found an integer");
  EXPECT_EQ(m[1], "5:13: expected ',' after the team name, found 'T'");
  EXPECT_EQ(m[2], "7:13: expected ',' between plan and service in 'set', found 'S'");
  // What parsed is kept: the later main block is there.
  EXPECT_EQ(p->mission.mains.size(), 1u);
}

TEST(Parser, StopsAfterTooManyErrors) {
  std::string text = "T: A a\nT.P.S {\n";
  for (int i = 0; i < 80; ++i) text += "  x y()\n";  // one error per line
  text += "}\n";
  auto p = parse(text);
  EXPECT_LE(p->diags.errorCount(), 51u);
  EXPECT_EQ(p->messages().back().substr(p->messages().back().find(' ') + 1), "too many errors; stopping");
}

}  // namespace
}  // namespace semo
