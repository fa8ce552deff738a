// `sdf --sdf3 graph.xml`: consistency, repetition vector, deadlock freedom and one iteration's
// sequential schedule of a dataflow graph (sdf/consistency.hpp).
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/sdf/buffers.hpp"
#include "semo/sdf/consistency.hpp"
#include "semo/sdf/sdf3_xml.hpp"
#include "semo/sdf/throughput.hpp"

namespace semo::cli {

std::string periodText(const sdf::Period& p) { return std::to_string(p.num) + (p.den == 1 ? "" : "/" + std::to_string(p.den)); }

namespace {

void printFront(const sdf::Graph& g, const sdf::ParetoFront& front) {
  std::cout << "buffers:     throughput-buffer Pareto front (" << front.distributions << " distributions explored"
            << (front.error.empty() ? "" : "; NOT complete: " + front.error) << ")\n";
  for (const sdf::BufferPoint& p : front.points) {
    std::cout << "  total " << p.total << ": " << (p.deadlock ? "deadlock" : "period " + periodText(p.period)) << "  (";
    bool firstChannel = true;
    for (std::size_t c = 0; c < g.channels.size(); ++c) {
      if (g.channels[c].selfLoop()) continue;
      std::cout << (firstChannel ? "" : " ") << g.channels[c].name << " " << p.capacities[c];
      firstChannel = false;
    }
    std::cout << ")\n";
  }
}

}  // namespace

int runSdf(const SdfOptions& options) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::string error;
  FileId file = sources.load(options.sdf3, error);
  if (!error.empty()) {
    std::cerr << errorPrefix() << error << "\n";
    return kBadInput;
  }
  std::optional<sdf::Graph> g = sdf::readSdf3(sources, file, diags);
  for (const Diagnostic& d : diags.diagnostics()) std::cerr << diags.format(d);
  if (!g) return kBadInput;
  std::vector<Output> outputs;
  if (options.dotOut) outputs.push_back({"--dot", *options.dotOut});
  if (options.sdf3Out) outputs.push_back({"--write-sdf3", *options.sdf3Out});
  if (!outputsSpareInputs(outputs, {options.sdf3})) return kBadInput;
  // Each rendered only when asked for.
  for (const auto& [path, render] : {std::pair{options.dotOut, &sdf::toGraphviz}, std::pair{options.sdf3Out, &sdf::writeSdf3}}) {
    if (path && !writeAtomically(*path, render(*g))) {
      std::cerr << errorPrefix() << "cannot write '" << *path << "'\n";
      return kBadInput;
    }
  }

  sdf::RepetitionVector q = sdf::repetitionVector(*g);
  sdf::Iteration it;
  if (q.consistent()) it = sdf::runIteration(*g, q.firings);
  const bool sound = q.consistent() && it.deadlockFree;
  sdf::ThroughputResult tp;
  if (sound) tp = sdf::throughput(*g, q.firings);
  std::optional<sdf::ParetoFront> front;
  if (sound && tp.error.empty() && options.buffers) front = sdf::bufferParetoFront(*g, q.firings, options.maxDistributions);
  const bool partial = !it.error.empty() || (sound && !tp.error.empty()) || (front && !front->error.empty());
  const int code = sound ? (partial ? kLimit : kOk) : it.error.empty() ? kViolated : kLimit;

  if (options.json) {
    nlohmann::json root = {{"schemaVersion", 1}, {"tool", std::string("semo-verify ") + kToolVersion}, {"input", options.sdf3}, {"graph", g->name}, {"actors", g->actors.size()},
                           {"channels", g->channels.size()}, {"consistent", q.consistent()}, {"exitCode", code}};
    if (!q.consistent()) {
      root["error"] = q.error;
      if (q.conflictChannel) root["conflictChannel"] = g->channels[*q.conflictChannel].name;
    } else {
      nlohmann::json rep = nlohmann::json::object();
      for (std::size_t a = 0; a < g->actors.size(); ++a) rep[g->actors[a].name] = q.firings[a];
      root["repetitionVector"] = rep;
      root["deadlockFree"] = it.deadlockFree;
      if (!it.error.empty()) root["error"] = it.error;
      nlohmann::json schedule = nlohmann::json::array();
      for (const sdf::FiringRun& run : it.schedule) schedule.push_back({{"actor", g->actors[run.actor].name}, {"times", run.times}});
      root["schedule"] = schedule;
      if (sound && tp.error.empty()) root["period"] = {{"num", tp.period.num}, {"den", tp.period.den}, {"states", tp.states}};
      else if (sound) root["periodError"] = tp.error;
      if (front) {
        nlohmann::json points = nlohmann::json::array();
        for (const sdf::BufferPoint& p : front->points) {
          nlohmann::json caps = nlohmann::json::object();
          for (std::size_t c = 0; c < g->channels.size(); ++c) {
            if (!g->channels[c].selfLoop()) caps[g->channels[c].name] = p.capacities[c];
          }
          nlohmann::json point = {{"total", p.total}, {"deadlock", p.deadlock}, {"capacities", caps}};
          if (!p.deadlock) point["period"] = {{"num", p.period.num}, {"den", p.period.den}};
          points.push_back(point);
        }
        root["paretoFront"] = {{"points", points}, {"distributions", front->distributions}, {"complete", front->error.empty()}};
        if (!front->error.empty()) root["paretoFront"]["error"] = front->error;
      }
    }
    std::cout << root.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return code;
  }
  std::cout << "graph:       " << options.sdf3 << " (" << g->name << ": " << g->actors.size() << " actors, " << g->channels.size()
            << " channels)\n";
  if (!q.consistent()) {
    std::cout << "  VIOLATED  consistency  (" << q.error << ")\n";
    return code;
  }
  std::cout << "  proven  consistency  (repetition vector:";
  for (std::size_t a = 0; a < g->actors.size(); ++a) std::cout << " " << g->actors[a].name << " " << q.firings[a];
  std::cout << ")\n";
  if (!it.error.empty()) {
    std::cout << "  unknown  deadlock_freedom  (" << it.error << ")\n";
  } else if (it.deadlockFree) {
    std::cout << "  proven  deadlock_freedom  (one iteration runs from the initial tokens: " << sdf::scheduleText(*g, it.schedule) << ")\n";
    if (tp.error.empty()) {
      std::cout << "period:      " << periodText(tp.period) << " time units per iteration, self-timed with unbounded channels ("
                << tp.states << " states)\n";
    } else {
      std::cout << "period:      not computed (" << tp.error << ")\n";
    }
    if (front) printFront(*g, *front);
  } else {
    std::cout << "  VIOLATED  deadlock_freedom  ("
              << (it.schedule.empty() ? "no actor can fire from the initial tokens"
                                      : "no actor can fire after " + sdf::scheduleText(*g, it.schedule) + ", before the iteration ends")
              << ")\n";
  }
  return code;
}

}  // namespace semo::cli
