#include <gtest/gtest.h>

#include "semo/frontend/strategy.hpp"

namespace semo {
namespace {

struct Read {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  strategy::Strategy strategy;
};

std::unique_ptr<Read> read(const std::string& xml) {
  auto r = std::make_unique<Read>();
  FileId f = r->sources.add("/tmp/s/strategy.xml", xml);
  r->strategy = strategy::readStrategy(r->sources, f, r->diags);
  return r;
}

std::string firstError(const Read& r) {
  for (const Diagnostic& d : r.diags.diagnostics()) {
    if (d.severity == Severity::Error) {
      return std::to_string(d.range.begin.line) + ":" + std::to_string(d.range.begin.column) + ": " + d.message;
    }
  }
  return "";
}

TEST(Strategy, ReadsEveryElement) {
  auto r = read(R"(<?xml version="1.0"?>
<strategy version="1">
  <robot urdf="robots/b.urdf" type="B"><capability name="Led" link="led_link"/></robot>
  <service name="move">
    <param name="where"/>
    <implementation robot="B">
      <task name="plan" exec="20 MSEC"><port name="goal" dir="in" rate="1"/><port name="cmd" dir="out" rate="2"/></task>
      <task name="drive" exec="250us"><port name="cmd" dir="in" rate="1"/></task>
      <channel from="plan.cmd" to="drive.cmd" initial="3"/>
    </implementation>
  </service>
  <service name="search" kind="group" min-robots="2">
    <implementation robot="B"><task name="t" exec="1 SEC"/></implementation>
    <knowledge name="papers" values="red, yellow blue" merge="union"/>
    <dissemination via="broadcast" period="2 SEC" retransmissions="3"/>
    <goal knowledge="papers" count="2"/>
  </service>
  <value name="T.light"><domain kind="threshold" thresholds="100 200.5"/></value>
  <value name="T.state"><domain kind="enum" values="a b"/></value>
  <value name="T.level"><domain kind="range" min="0" max="3"/></value>
  <topic name="T.msg" values="x y" buffer="4"/>
  <leader-selection service="T.Plan.S" algorithm="bully" heartbeat="500 MSEC" timeout="2s"/>
  <events delivery="broadcast" retransmissions="2"/>
  <event name="e" delivery="reliable"/>
</strategy>)");
  ASSERT_FALSE(r->diags.hasErrors()) << firstError(*r);
  const strategy::Strategy& s = r->strategy;
  EXPECT_EQ(s.folder, "/tmp/s");
  ASSERT_EQ(s.robots.size(), 1u);
  EXPECT_EQ(s.robots[0].urdf, "robots/b.urdf");
  EXPECT_EQ(s.robots[0].type, "B");
  EXPECT_EQ(s.robots[0].capabilities[0].link, "led_link");
  const strategy::Service* move = s.service("move");
  ASSERT_NE(move, nullptr);
  EXPECT_EQ(move->kind, strategy::Service::Kind::Primitive);
  EXPECT_EQ(move->params, std::vector<std::string>{"where"});
  const strategy::Implementation* impl = move->implementationFor("B");
  ASSERT_NE(impl, nullptr);
  EXPECT_EQ(impl->tasks[0].execMicros, 20000);
  EXPECT_EQ(impl->tasks[1].execMicros, 250);
  EXPECT_EQ(impl->tasks[0].port("cmd")->rate, 2);
  EXPECT_FALSE(impl->tasks[0].port("cmd")->input);
  ASSERT_EQ(impl->channels.size(), 1u);
  EXPECT_EQ(impl->channels[0].initialTokens, 3);
  const strategy::Service* search = s.service("search");
  ASSERT_NE(search, nullptr);
  EXPECT_EQ(search->kind, strategy::Service::Kind::Group);
  EXPECT_EQ(search->minRobots, 2);
  EXPECT_EQ(search->knowledge[0].values, (std::vector<std::string>{"red", "yellow", "blue"}));
  EXPECT_EQ(search->knowledge[0].merge, strategy::Knowledge::Merge::Union);
  EXPECT_EQ(search->dissemination->periodMillis, 2000);
  EXPECT_EQ(search->dissemination->retransmissions, 3);
  EXPECT_EQ(search->goal->count, 2);
  EXPECT_EQ(s.value("T", "light")->domain.thresholds, (std::vector<double>{100, 200.5}));
  EXPECT_EQ(s.value("T", "state")->domain.values.size(), 2u);
  EXPECT_EQ(s.value("T", "level")->domain.max, 3);
  EXPECT_EQ(s.topic("T", "msg")->buffer, 4);
  const strategy::LeaderSelection* ls = s.leaderSelection("T", "Plan", "S");
  ASSERT_NE(ls, nullptr);
  EXPECT_EQ(ls->algorithm, strategy::LeaderSelection::Algorithm::Bully);
  EXPECT_EQ(ls->heartbeatMillis, 500);
  EXPECT_EQ(ls->timeoutMillis, 2000);
  EXPECT_EQ(s.eventDelivery("other").retransmissions, 2);
  EXPECT_TRUE(s.eventDelivery("e").reliable);
}

TEST(Strategy, DefaultsWhenOmitted) {
  auto r = read("<strategy/>");
  ASSERT_FALSE(r->diags.hasErrors());
  EXPECT_FALSE(r->strategy.events.reliable);
  EXPECT_EQ(r->strategy.events.retransmissions, 0);
}

TEST(Strategy, MalformedXmlIsReportedWithItsLine) {
  auto r = read("<strategy>\n  <service name=\"a\">\n</strategy>\n");
  EXPECT_EQ(firstError(*r), "2:3: malformed XML: element <service> is not closed, or is closed by the wrong tag");
}

TEST(Strategy, ErrorsPointAtTheAttributeValue) {
  auto r = read("<strategy>\n  <topic name=\"T.m\" buffer=\"lots\"/>\n</strategy>\n");
  EXPECT_EQ(firstError(*r), "2:28: attribute 'buffer' must be an integer, not 'lots'");
}

TEST(Strategy, ChannelDirectionsAreChecked) {
  auto r = read(R"(<strategy><service name="s"><implementation robot="B">
  <task name="a" exec="1ms"><port name="o" dir="out"/></task>
  <task name="b" exec="1ms"><port name="i" dir="in"/></task>
  <channel from="b.i" to="a.o"/>
</implementation></service></strategy>)");
  EXPECT_EQ(r->diags.errorCount(), 2u);
  EXPECT_EQ(firstError(*r), "4:17: channel must start at an output port, but 'b.i' is an input");
}

TEST(Strategy, TimeoutNotLongerThanHeartbeatIsAWarning) {
  auto r = read(R"(<strategy><leader-selection service="T.P.S" heartbeat="1 SEC" timeout="1 SEC"/></strategy>)");
  EXPECT_FALSE(r->diags.hasErrors());
  ASSERT_EQ(r->diags.warningCount(), 1u);
  EXPECT_NE(r->diags.diagnostics().front().message.find("suspected between two heartbeats"), std::string::npos);
}

TEST(Strategy, ReelectionOnTimeoutByDefaultOrAtFormation) {
  auto r = read(R"(<strategy><leader-selection service="T.P.S"/><leader-selection service="T.P.F" reelection="formation"/></strategy>)");
  ASSERT_FALSE(r->diags.hasErrors());
  EXPECT_EQ(r->strategy.leaderSelection("T", "P", "S")->reelection, strategy::LeaderSelection::Reelection::Timeout);
  EXPECT_EQ(r->strategy.leaderSelection("T", "P", "F")->reelection, strategy::LeaderSelection::Reelection::Formation);
}

TEST(Strategy, LeadershipReleasedOnAModeChangeByDefaultOrKept) {
  auto r = read(R"(<strategy><leader-selection service="T.P.S"/><leader-selection service="T.P.K" on-mode-change="keep"/></strategy>)");
  ASSERT_FALSE(r->diags.hasErrors());
  EXPECT_EQ(r->strategy.leaderSelection("T", "P", "S")->onModeChange, strategy::LeaderSelection::OnModeChange::Release);
  EXPECT_EQ(r->strategy.leaderSelection("T", "P", "K")->onModeChange, strategy::LeaderSelection::OnModeChange::Keep);
  auto bad = read(R"(<strategy><leader-selection service="T.P.S" on-mode-change="stay"/></strategy>)");
  ASSERT_TRUE(bad->diags.hasErrors());
  EXPECT_NE(bad->diags.diagnostics().front().message.find("on-mode-change must be 'release' or 'keep', not 'stay'"), std::string::npos);
}

}  // namespace
}  // namespace semo
