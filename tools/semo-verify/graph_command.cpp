// `graph MISSION --strategy S --modes|--groups|--tasks [-o FILE.dot]`: a mission drawn for Graphviz:
// each team's mode machine, each group block with its arms and candidate robots, or each robot's
// task graph clustered by scenario with execution times, rates and proven channel capacities.
#include <iostream>

#include <fmt/format.h>

#include "commands.hpp"
#include "semo/checker/verify.hpp"
#include "semo/sdf/task_graph_analysis.hpp"
#include "semo/semantics/load.hpp"

namespace semo::cli {

namespace {

std::string dotQuoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string modesDot(const model::MissionModel& m) {
  std::string out = "digraph modes {\n  rankdir=LR;\n  node [shape=box, style=rounded, fontname=\"sans-serif\"];\n"
                    "  edge [fontname=\"sans-serif\", fontsize=10];\n";
  for (std::size_t t = 0; t < m.teams.size(); ++t) {
    const model::Team& team = m.teams[t];
    out += fmt::format("  subgraph cluster_{} {{\n    label={};\n    fontname=\"sans-serif\";\n", t, dotQuoted(team.name));
    for (model::Index mi : team.modes) {
      const model::Mode& mode = m.modes[mi];
      std::string label = mode.name;
      for (const model::PlanSetting& s : mode.settings) {
        if (s.plan < team.plans.size() && s.service < m.services.size()) label += "\n" + team.plans[s.plan] + ": " + m.services[s.service].name;
      }
      std::string style = mi == team.initialMode ? ", penwidth=2.5" : "";
      if (!mode.reachable) style += ", color=gray60, fontcolor=gray40, style=\"rounded,dashed\"";
      out += fmt::format("    m{} [label={}{}];\n", mi, dotQuoted(label), style);
    }
    if (team.initialMode != model::kNone) {
      out += fmt::format("    start{0} [shape=point, width=0.12];\n    start{0} -> m{1};\n", t, team.initialMode);
    }
    for (model::Index mi : team.modes) {
      for (const model::Transition& tr : m.modes[mi].transitions) {
        if (tr.target == model::kNone) continue;
        if (tr.isDefault) {
          out += fmt::format("    m{} -> m{} [label=\"default\", style=dashed];\n", mi, tr.target);
        } else if (tr.event < team.events.size()) {
          out += fmt::format("    m{} -> m{} [label={}];\n", mi, tr.target, dotQuoted("catch " + team.events[tr.event].name));
        }
      }
    }
    out += "  }\n";
  }
  return out + "}\n";
}

std::string groupsDot(const model::MissionModel& m) {
  std::string out = "digraph groups {\n  rankdir=LR;\n  node [fontname=\"sans-serif\"];\n  edge [fontname=\"sans-serif\", fontsize=10];\n";
  std::vector<bool> robotDrawn(m.robots.size(), false);
  for (std::size_t b = 0; b < m.groupBlocks.size(); ++b) {
    const model::GroupBlock& block = m.groupBlocks[b];
    const std::string service = block.service < m.services.size() ? m.services[block.service].name : "?";
    const std::string team = block.team < m.teams.size() ? m.teams[block.team].name : "?";
    std::string label = service + " (" + team + ")\n" + (block.isLeaderBlock ? "leader block" : "group block");
    if (block.isLeaderBlock) {
      label += block.leader.detectsFailures
                   ? fmt::format("\nheartbeat {} ms, takeover after {} ms", block.leader.heartbeatMillis, block.leader.timeoutMillis)
                   : "\nnew leader when the group forms";
    }
    out += fmt::format("  b{} [shape=box3d, label={}];\n", b, dotQuoted(label));
    for (std::size_t a = 0; a < block.arms.size(); ++a) {
      const model::GroupArm& arm = block.arms[a];
      std::string what = arm.kind == model::GroupArm::Kind::Leader ? "leader" : arm.kind == model::GroupArm::Kind::Others ? "others" : "group";
      if (!arm.names.empty()) {
        std::string names;
        for (const std::string& n : arm.names) names += (names.empty() ? "" : ", ") + n;
        what += std::string(arm.byCapability ? " (capable of " : " (instance of ") + names + ")";
      }
      const std::int64_t demand = m.armDemand(arm);
      if (arm.kind != model::GroupArm::Kind::Others && demand > 1) what += fmt::format("\nneeds {} robots", demand);
      out += fmt::format("  b{}a{} [shape=ellipse, label={}];\n  b{} -> b{}a{};\n", b, a, dotQuoted(what), b, b, a);
      for (model::Index r : arm.candidates) {
        if (r >= m.robots.size()) continue;
        if (!robotDrawn[r]) {
          out += fmt::format("  r{} [shape=box, style=filled, fillcolor=\"#eef3fb\", label={}];\n", r, dotQuoted(m.robots[r].name + "\n" + m.robots[r].type));
          robotDrawn[r] = true;
        }
        out += fmt::format("  b{}a{} -> r{} [style=dotted, arrowhead=none];\n", b, a, r);
      }
    }
  }
  return out + "}\n";
}

std::string tasksDot(const checker::Report& report) {
  std::string out = "digraph tasks {\n  rankdir=LR;\n  compound=true;\n  node [fontname=\"sans-serif\", fontsize=10];\n"
                    "  edge [fontname=\"sans-serif\", fontsize=9];\n";
  for (std::size_t g = 0; g < report.taskGraphs.size(); ++g) {
    const sdf::TaskGraph& graph = report.taskGraphs[g].graph;
    const sdf::TaskGraphAnalysis& analysis = report.taskGraphs[g].analysis;
    out += fmt::format("  subgraph cluster_r{} {{\n    label={};\n    fontname=\"sans-serif\";\n", g,
                       dotQuoted("robot " + graph.robot + " (" + graph.robotType + ", " + graph.team + ")"));
    for (std::size_t s = 0; s < graph.scenarios.size(); ++s) {
      const sdf::Scenario& scenario = graph.scenarios[s];
      std::string label = "scenario " + scenario.name;
      if (s < analysis.scenarios.size()) {
        const sdf::ScenarioAnalysis& a = analysis.scenarios[s];
        const sdf::Period& p = a.unbounded.period;
        if (a.sound()) label += fmt::format(" (proven; period {}{} us)", p.num, p.den == 1 ? std::string() : fmt::format("/{}", p.den));
        else label += " (NOT proven)";
      }
      out += fmt::format("    subgraph cluster_r{}s{} {{\n      label={};\n      style=rounded;\n", g, s, dotQuoted(label));
      for (std::uint32_t t : scenario.tasks) {
        if (t >= graph.tasks.size()) continue;
        const sdf::Task& task = graph.tasks[t];
        out += fmt::format("      r{}s{}t{} [shape={}, label={}];\n", g, s, t, t == scenario.tasks.front() ? "doubleoctagon" : "box",
                           dotQuoted(fmt::format("{}\n{} us", task.name, task.execMicros)));
      }
      for (const sdf::ScenarioChannel& c : scenario.channels) {
        if (c.channel >= graph.channels.size()) continue;
        const sdf::TaskChannel& ch = graph.channels[c.channel];
        std::string label = fmt::format("{}:{}", c.production, c.consumption);
        if (c.initialTokens != 0) label += fmt::format(" \u2022{}", c.initialTokens);
        if (c.channel < analysis.capacities.size() && analysis.capacities[c.channel] > 0) label += fmt::format("\ncap {}", analysis.capacities[c.channel]);
        out += fmt::format("      r{0}s{1}t{2} -> r{0}s{1}t{3} [label={4}{5}];\n", g, s, ch.fromTask, ch.toTask, dotQuoted(label),
                           ch.control ? ", color=gray50" : "");
      }
      out += "    }\n";
    }
    out += "  }\n";
  }
  return out + "}\n";
}

}  // namespace

int runGraph(const GraphOptions& options) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::optional<model::MissionModel> mission = loadMission({options.mission, options.strategy, options.robotsDir}, sources, diags);
  diags.sortByPosition();
  diags.print(std::cerr);
  if (!mission) return kBadInput;
  if (options.output) {
    std::vector<std::string> inputs = filesRead(sources);
    inputs.insert(inputs.end(), {options.mission, options.strategy, options.robotsDir.value_or("")});
    if (!outputsSpareInputs({{"--output", *options.output}}, inputs)) return kBadInput;
  }
  std::string dot;
  if (options.what == "modes") {
    dot = modesDot(*mission);
  } else if (options.what == "groups") {
    if (mission->groupBlocks.empty()) {
      std::cerr << errorPrefix() << options.mission << " has no group block to draw\n";
      return kBadInput;
    }
    dot = groupsDot(*mission);
  } else {
    DiagnosticEngine taskDiags(sources);
    std::optional<std::vector<sdf::TaskGraph>> graphs = sdf::generateTaskGraphs(*mission, taskDiags);
    taskDiags.print(std::cerr);
    if (!graphs) return kBadInput;
    if (options.robot) {
      std::erase_if(*graphs, [&](const sdf::TaskGraph& g) { return g.robot != *options.robot; });
      if (graphs->empty()) {
        std::cerr << errorPrefix() << "no robot named '" << *options.robot << "'\n";
        return kBadInput;
      }
    }
    checker::Report report;  // the proven capacities go on the channels
    checker::addTaskGraphs(report, std::move(*graphs), sdf::BoundsOptions{});
    dot = tasksDot(report);
  }
  if (!options.output) {
    std::cout << dot;
  } else if (!writeAtomically(*options.output, dot)) {
    std::cerr << errorPrefix() << "cannot write '" << *options.output << "'\n";
    return kBadInput;
  }
  return kOk;
}

}  // namespace semo::cli
