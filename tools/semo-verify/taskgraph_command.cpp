// `sdf MISSION --strategy S` (a task graph per robot) and `sdf --graph G.json` (one task graph):
// every scenario analysed, buffer bounds chosen and proven (sdf/task_graph_analysis.hpp).
#include <chrono>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/checker/verify.hpp"
#include "semo/semantics/load.hpp"
#include "semo/sdf/task_graph_analysis.hpp"
#include "semo/sdf/task_graph_io.hpp"

namespace semo::cli {

namespace {

using nlohmann::json;


const char* outcomeName(sdf::ChannelMinimality::Outcome o) {
  switch (o) {
    case sdf::ChannelMinimality::Outcome::Deadlocks: return "deadlocks";
    case sdf::ChannelMinimality::Outcome::SlowerPeriod: return "slower";
    case sdf::ChannelMinimality::Outcome::NotMinimal: return "not-minimal";
    case sdf::ChannelMinimality::Outcome::Unknown: return "unknown";
  }
  return "unknown";
}

json boundsJson(const sdf::Graph& g, const sdf::ChosenBounds& b) {
  json caps = json::object();
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    if (!g.channels[c].selfLoop()) caps[g.channels[c].name] = b.capacities[c];
  }
  json channels = json::array();
  for (const sdf::ChannelMinimality& m : b.channels) {
    json one = {{"channel", g.channels[m.channel].name}, {"oneLess", outcomeName(m.outcome)}};
    if (m.outcome == sdf::ChannelMinimality::Outcome::SlowerPeriod) one["period"] = {{"num", m.periodWithOneLess.num}, {"den", m.periodWithOneLess.den}};
    if (!m.note.empty()) one["note"] = m.note;
    channels.push_back(one);
  }
  json schedule = json::array();
  for (const sdf::FiringRun& run : b.schedule) schedule.push_back({{"actor", g.actors[run.actor].name}, {"times", run.times}});
  json out = {{"total", b.total}, {"period", {{"num", b.period.num}, {"den", b.period.den}}}, {"capacities", caps},
              {"schedule", schedule}, {"safety", sdf::proofStatusName(b.safety)}, {"minimality", sdf::proofStatusName(b.minimality)},
              {"channels", channels}};
  if (!b.safetyNote.empty()) out["safetyNote"] = b.safetyNote;
  return out;
}

json scenarioJson(const sdf::ScenarioAnalysis& a) {
  const sdf::Graph& g = a.graph;
  json out = {{"scenario", a.scenario}, {"actors", g.actors.size()}, {"consistent", a.repetition.consistent()}, {"sound", a.sound()}};
  if (!a.repetition.consistent()) {
    out["error"] = a.repetition.error;
    if (a.repetition.conflictChannel) out["conflictChannel"] = g.channels[*a.repetition.conflictChannel].name;
    return out;
  }
  json rep = json::object();
  for (std::size_t i = 0; i < g.actors.size(); ++i) rep[g.actors[i].name] = a.repetition.firings[i];
  out["repetitionVector"] = rep;
  out["deadlockFree"] = a.iteration.deadlockFree;
  json schedule = json::array();
  for (const sdf::FiringRun& run : a.iteration.schedule) schedule.push_back({{"actor", g.actors[run.actor].name}, {"times", run.times}});
  out["schedule"] = schedule;
  if (!a.iteration.deadlockFree) return out;
  if (!a.unbounded.error.empty()) {
    out["periodError"] = a.unbounded.error;
    return out;
  }
  out["periodMicros"] = {{"num", a.unbounded.period.num}, {"den", a.unbounded.period.den}};
  if (!a.bounds.haveBounds) {
    out["boundsError"] = a.bounds.error;
    return out;
  }
  out["front"] = {{"points", a.bounds.front.points.size()}, {"distributions", a.bounds.front.distributions}};
  out["deadlockFreeBounds"] = boundsJson(g, a.bounds.deadlockFree);
  out["maxThroughputBounds"] = boundsJson(g, a.bounds.maxThroughput);
  return out;
}

std::string boundsLines(const char* what, const sdf::Graph& g, const sdf::ChosenBounds& b) {
  std::size_t deadlocks = 0, slower = 0;
  for (const sdf::ChannelMinimality& m : b.channels) {
    deadlocks += m.outcome == sdf::ChannelMinimality::Outcome::Deadlocks;
    slower += m.outcome == sdf::ChannelMinimality::Outcome::SlowerPeriod;
  }
  std::string line = std::string("    ") + what + ": total " + std::to_string(b.total) + ", period " + periodText(b.period) +
                     " us; no overflow/underflow " + sdf::proofStatusName(b.safety) + " (Z3, any number of iterations)";
  line += "; minimal " + std::string(sdf::proofStatusName(b.minimality)) + " (one token less: " + std::to_string(deadlocks) +
          " channels deadlock (Z3)";
  if (slower != 0) line += ", " + std::to_string(slower) + " lose throughput (exact period)";
  std::string capacities = "      capacities:\n";
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    if (!g.channels[c].selfLoop()) capacities += "        " + std::to_string(b.capacities[c]) + "  " + g.channels[c].name + "\n";
  }
  return wrapText(line + ")", 6) + capacities;
}

// Everything known of one scenario (--verbose), or the first line that is not proven.
struct ScenarioText {
  std::string verbose;
  std::string defect;  // empty when sound
};

ScenarioText scenarioText(const sdf::ScenarioAnalysis& a) {
  const sdf::Graph& g = a.graph;
  ScenarioText out;
  out.verbose = "  scenario " + a.scenario + " (" + std::to_string(g.actors.size()) + " tasks)\n";
  auto add = [&](const std::string& line, bool isDefect = false) {
    out.verbose += wrapText(line, 6);
    if (isDefect && out.defect.empty()) out.defect = line.substr(line.find_first_not_of(' '));
  };
  if (!a.repetition.consistent()) {
    add("    VIOLATED  consistency  (" + a.repetition.error + ")", true);
    return out;
  }
  std::string repetition = "    proven  consistency  (repetition vector:";
  for (std::size_t i = 0; i < g.actors.size(); ++i) repetition += " " + g.actors[i].name + " " + std::to_string(a.repetition.firings[i]);
  add(repetition + ")");
  if (!a.iteration.error.empty()) {
    add("    unknown  deadlock_freedom  (" + a.iteration.error + ")", true);
    return out;
  }
  if (!a.iteration.deadlockFree) {
    add("    VIOLATED  deadlock_freedom  (" +
            (a.iteration.schedule.empty() ? std::string("no task can fire from the initial tokens")
                                          : "no task can fire after " + sdf::scheduleText(g, a.iteration.schedule) + ", before the iteration ends") +
            ")",
        true);
    return out;
  }
  add("    proven  deadlock_freedom  (schedule: " + sdf::scheduleText(g, a.iteration.schedule) + ")");
  if (!a.unbounded.error.empty()) {
    add("    unknown  period  (" + a.unbounded.error + ")", true);
    return out;
  }
  add("    period: " + periodText(a.unbounded.period) + " us per iteration with unbounded channels");
  if (!a.bounds.haveBounds) {
    add("    unknown  buffer_bounds  (" + a.bounds.error + ")", true);
    return out;
  }
  out.verbose += boundsLines("deadlock-free bounds", g, a.bounds.deadlockFree) + boundsLines("max-throughput bounds", g, a.bounds.maxThroughput);
  for (const sdf::ChosenBounds* b : {&a.bounds.deadlockFree, &a.bounds.maxThroughput}) {
    if (out.defect.empty() && b->safety != sdf::ProofStatus::Proven) {
      out.defect = std::string(b->safety == sdf::ProofStatus::Refuted ? "REFUTED" : "unknown") + "  buffer_bounds  (total " +
                   std::to_string(b->total) + ": no overflow/underflow " + sdf::proofStatusName(b->safety) + ")";
    }
    if (out.defect.empty() && b->minimality != sdf::ProofStatus::Proven) {
      out.defect = std::string(b->minimality == sdf::ProofStatus::Refuted ? "NOT minimal" : "unknown") + "  buffer_minimality  (total " +
                   std::to_string(b->total) + ")";
    }
  }
  return out;
}

// One line per scenario: what was proven and the figures a user needs (the rest under --verbose).
std::string compactLine(const sdf::ScenarioAnalysis& a, const ScenarioText& t, std::size_t nameWidth) {
  std::string line = "  " + a.scenario + std::string(nameWidth - a.scenario.size(), ' ') + "  " +
                     (a.graph.actors.size() < 10 ? " " : "") + std::to_string(a.graph.actors.size()) + " tasks  ";
  if (!t.defect.empty()) return wrapText(line + t.defect, nameWidth + 14);
  return line + "proven  period " + periodText(a.unbounded.period) + " us; buffers " + std::to_string(a.bounds.deadlockFree.total) +
         " at " + periodText(a.bounds.deadlockFree.period) + " us, " + std::to_string(a.bounds.maxThroughput.total) + " at full rate\n";
}

}  // namespace

int runTaskGraphs(const SdfOptions& options) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::vector<sdf::TaskGraph> graphs;
  if (options.mission) {
    std::optional<model::MissionModel> mission = loadMission({*options.mission, *options.strategy, options.robotsDir}, sources, diags);
    if (mission) {
      if (auto generated = sdf::generateTaskGraphs(*mission, diags)) graphs = std::move(*generated);
    }
  } else {
    std::string error;
    const FileId file = sources.load(*options.graphJson, error);
    if (!error.empty()) {
      std::cerr << errorPrefix() << error << "\n";
      return kBadInput;
    }
    if (auto g = sdf::readTaskGraphJson(sources, file, diags)) graphs.push_back(std::move(*g));
  }
  diags.sortByPosition();
  diags.print(std::cerr);
  if (diags.hasErrors()) return kBadInput;
  if (options.robot) {
    std::erase_if(graphs, [&](const sdf::TaskGraph& g) { return g.robot != *options.robot; });
    if (graphs.empty()) {
      std::cerr << errorPrefix() << "no robot named '" << *options.robot << "'\n";
      return kBadInput;
    }
  }
  if (options.outDir) {
    std::vector<Output> outputs;
    for (const sdf::TaskGraph& g : graphs) {
      const std::string base = (std::filesystem::path(*options.outDir) / g.robot).string();
      outputs.push_back({"--out", base + ".json", true});
      outputs.push_back({"--out", base + ".dot", true});
    }
    std::vector<std::string> inputs = filesRead(sources);
    if (options.robotsDir) inputs.push_back(*options.robotsDir);
    if (!outputsSpareInputs(outputs, inputs)) return kBadInput;
    std::error_code ec;
    std::filesystem::create_directories(*options.outDir, ec);
    for (const sdf::TaskGraph& g : graphs) {
      const std::string base = (std::filesystem::path(*options.outDir) / g.robot).string();
      if (ec || !writeAtomically(base + ".json", sdf::taskGraphToJson(g)) || !writeAtomically(base + ".dot", sdf::taskGraphToGraphviz(g))) {
        std::cerr << errorPrefix() << "cannot write the task graphs into '" << *options.outDir << "'\n";
        return kBadInput;
      }
    }
  }

  sdf::BoundsOptions bo;
  bo.maxDistributions = options.maxDistributions;
  bo.timeoutMs = options.proofTimeoutMs;
  if (!options.json) {
    // A robot's analysis said as it starts, once the run has taken two seconds.
    bo.onPhase = [started = std::chrono::steady_clock::now()](const std::string& what) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      if (seconds >= 2.0) std::cerr << "[" << static_cast<long long>(seconds) << " s] " << what << "\n";
    };
  }
  checker::Report report;
  checker::addTaskGraphs(report, std::move(graphs), bo);
  json robots = json::array();
  std::vector<std::pair<std::vector<std::string>, std::string>> texts;  // robots with the same text, and it
  for (const checker::TaskGraphReport& r : report.taskGraphs) {
    const sdf::TaskGraph& g = r.graph;
    const sdf::TaskGraphAnalysis& analysis = r.analysis;
    if (options.json) {
      json scenarios = json::array();
      for (const sdf::ScenarioAnalysis& a : analysis.scenarios) scenarios.push_back(scenarioJson(a));
      json caps = json::object();
      for (std::size_t c = 0; c < g.channels.size(); ++c) {
        if (analysis.capacities[c] > 0) caps[g.channels[c].name] = analysis.capacities[c];
      }
      robots.push_back({{"robot", g.robot}, {"robotType", g.robotType}, {"team", g.team}, {"tasks", g.tasks.size()},
                        {"channels", g.channels.size()}, {"remotePorts", g.remotePorts.size()}, {"scenarios", scenarios},
                        {"capacities", caps}});
      continue;
    }
    // A robot's text without its name: robots whose texts are the same are printed once.
    std::string body = g.robotType + ", " + g.team + "): " + std::to_string(g.tasks.size()) + " tasks, " +
                       std::to_string(g.channels.size()) + " channels, " + std::to_string(g.remotePorts.size()) + " remote ports" +
                       (options.verbose ? ", " + std::to_string(g.scenarios.size()) + " scenarios" : "") + "\n";
    std::size_t nameWidth = 0;
    for (const sdf::ScenarioAnalysis& a : analysis.scenarios) nameWidth = std::max(nameWidth, a.scenario.size());
    for (const sdf::ScenarioAnalysis& a : analysis.scenarios) {
      const ScenarioText t = scenarioText(a);
      body += options.verbose ? t.verbose : compactLine(a, t, nameWidth);
    }
    auto same = std::find_if(texts.begin(), texts.end(), [&](const auto& e) { return e.second == body; });
    if (same != texts.end()) same->first.push_back(g.robot);
    else texts.push_back({{g.robot}, body});
  }
  for (const auto& [names, body] : texts) {
    std::string all;
    for (const std::string& n : names) all += (all.empty() ? "" : ", ") + n;
    const std::size_t firstLine = body.find('\n');
    std::cout << wrapText((names.size() > 1 ? "robots " : "robot ") + all + (names.size() > 1 ? " (identical graphs; " : " (") +
                             body.substr(0, firstLine),
                         6)
              << body.substr(firstLine + 1);
  }
  // Sound everywhere: 0; a real defect (inconsistent, deadlocking, a bound refuted): 1; else 3.
  if (options.json) {
    std::cout << json{{"schemaVersion", 1},
                      {"tool", std::string("semo-verify ") + kToolVersion},
                      {"robots", robots},
                      {"assumptions", report.taskGraphAssumptions},
                      {"exitCode", report.exitCode}}
                     .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
  } else {
    std::cout << wrapText("assumptions: " + report.taskGraphAssumptions, 13);
    std::size_t scenarios = 0, sound = 0;
    for (const checker::TaskGraphReport& r : report.taskGraphs) {
      for (const sdf::ScenarioAnalysis& a : r.analysis.scenarios) scenarios += 1, sound += a.sound() ? 1 : 0;
    }
    const char* meaning = report.exitCode == 0 ? "every scenario proven" : report.exitCode == 1 ? "a defect" : "partial";
    std::cout << "\nresult: " << sound << " of " << scenarios << " scenarios proven (" << report.taskGraphs.size()
              << (report.taskGraphs.size() == 1 ? " robot" : " robots") << ") \u2014 exit " << report.exitCode << " (" << meaning << ")\n";
  }
  return report.exitCode;
}

}  // namespace semo::cli
