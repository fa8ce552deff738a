// `replay TRACE.json`: a counterexample of `check --json` happening in the running team. The
// mission is built as the trace file records (input, strategy, robots, overrides: the fingerprint
// must match), projected onto its robots, and the simulator takes the counterexample's steps one for
// one (runtime/replay.hpp) while a monitor (checker/replay_monitor.hpp) checks each against the
// trace and finds the violation where the checker found it.
#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/checker/fingerprint.hpp"
#include "semo/checker/replay_monitor.hpp"
#include "semo/codegen/project.hpp"
#include "semo/frontend/json_text.hpp"
#include "semo/runtime/replay.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::cli {

namespace {

const char* kindWords(checker::ReplayedTrace::Kind k) {
  switch (k) {
    case checker::ReplayedTrace::Kind::Invariant: return "invariant";
    case checker::ReplayedTrace::Kind::Deadlock: return "deadlock";
    case checker::ReplayedTrace::Kind::ModelError: return "update out of range";
    case checker::ReplayedTrace::Kind::Lasso: return "lasso";
  }
  return "?";
}

}  // namespace

int runReplay(const ReplayOptions& options) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  auto fail = [&]() {
    diags.sortByPosition();
    diags.print(std::cerr);
    return kBadInput;
  };
  std::string why;
  const FileId file = sources.load(options.trace, why);
  if (file == kNoFile) {
    std::cerr << errorPrefix() << why << "\n";
    return kBadInput;
  }
  std::optional<nlohmann::json> root = parseJsonFile(sources, file, diags);
  if (!root) return fail();
  ModelInput in = options.model;
  if (std::string e = modelInputFromTrace(*root, in); !e.empty()) {
    std::cerr << options.trace << ": error: " << e << "\n";
    return kBadInput;
  }
  if (in.input.empty() || !in.strategy) {
    std::cerr << errorPrefix() << options.trace
              << " does not say which mission and strategy it was found on (a single counterexample object): give MISSION and --strategy\n";
    return kBadInput;
  }
  if (std::filesystem::path(in.input).extension() == ".ir") {
    std::cerr << errorPrefix() << in.input << " is an IR file: replay runs a mission's robots, and an IR file has none\n";
    return kBadInput;
  }
  std::optional<model::MissionModel> mission = loadMission({in.input, *in.strategy, in.robotsDir}, sources, diags);
  std::optional<Translation> translation;
  if (mission) translation = translateMission(*mission, TranslationOptions{in.crash, in.loss, in.fairLoss, in.crashPerTeam}, sources, diags);
  if (!translation) return fail();
  runtime::MissionTables tables = codegen::project(*mission, *translation, sources);
  tables.modelFingerprint = checker::modelFingerprint(translation->model);
  checker::TraceReadOptions readOptions;
  readOptions.property = options.property.value_or("");
  readOptions.checkFingerprint = options.checkFingerprint;
  std::optional<checker::ReplayedTrace> trace = checker::readTrace(sources, file, translation->model, diags, readOptions);
  if (!trace) return fail();
  diags.print(std::cerr);  // warnings, if any

  const auto pace = parseDuration(options.pace);
  const auto settle = parseDuration(options.settle);
  if (!pace || *pace <= 0 || *pace > 3600 || !settle || *settle > 86400) {
    std::cerr << errorPrefix() << "--pace and --settle take a time such as 500ms or 10s (--pace above 0, at most an hour)\n";
    return kBadInput;
  }
  if (options.loops == 0 || options.loops > 1000) {
    std::cerr << errorPrefix() << "--loops must be between 1 and 1000\n";
    return kBadInput;
  }

  runtime::World world;
  const std::string worldPath = options.world.value_or(defaultWorldPath(in.input));
  if (options.world || std::filesystem::exists(worldPath)) {
    std::vector<runtime::WorldError> errors;
    std::optional<runtime::World> read = runtime::readWorld(worldPath, errors);
    for (const runtime::WorldError& e : errors) std::cerr << runtime::formatWorldError(e);
    if (!read) return kBadInput;
    world = std::move(*read);
    const std::vector<std::string> problems = teamSourceProblems(*mission, world);
    for (const std::string& p : problems) std::cerr << worldPath << ": error: " << p << "\n";
    if (!problems.empty()) return kBadInput;
  }
  std::vector<Output> outputs;
  if (options.traceOut) outputs.push_back({"--save-trace", *options.traceOut});
  if (options.svg) outputs.push_back({"--svg", *options.svg});
  std::vector<std::string> inputs = filesRead(sources);
  inputs.insert(inputs.end(), {options.trace, in.robotsDir.value_or(""), worldPath});
  if (!outputsSpareInputs(outputs, inputs)) return kBadInput;

  const bool deadlock = trace->kind == checker::ReplayedTrace::Kind::Deadlock;
  checker::ReplayMonitor monitor(translation->model, tables, *trace, options.loops);
  const std::vector<runtime::Id> script = checker::ReplayMonitor::script(*trace, options.loops);
  runtime::SimulationOptions sim;
  sim.stopAtGoal = false;
  runtime::ReplayOptions how{*pace, deadlock ? *settle : 0.0};
  const runtime::TaskLibrary library = runtime::TaskLibrary::standard();
  runtime::SimTrace run = runtime::replay(tables, world, library, script, sim, how, &monitor);
  run.mission = in.input;
  run.strategy = *in.strategy;

  // The steps as the running team took them.
  const std::string name = trace->property.empty() ? "the model error" : trace->property;
  std::cout << fmt::format("replay of {} ({}, {} steps{}) on {}\n", name, kindWords(trace->kind), trace->rules.size(),
                           script.size() != trace->rules.size() ? fmt::format(", {} with the loop taken {} times", script.size(), options.loops) : "",
                           in.input);
  std::size_t k = 0;
  std::vector<double> stepTime;  // per step of the script the team took
  for (const runtime::TraceEvent& e : run.events) {
    if (e.kind != runtime::TraceEvent::Kind::Step || e.rule.empty() || k >= monitor.stepsTaken()) continue;
    ++k;
    stepTime.push_back(e.t);
    const std::string who = e.robot < tables.robots.size() ? tables.robots[e.robot].name : "the team";
    std::cout << fmt::format("  step {:>3}  {:>8.3f} s  {}: {}{}\n", k, e.t, who, e.label, e.origin.empty() ? "" : "  (" + e.origin + ")");
    if (trace->kind == checker::ReplayedTrace::Kind::Lasso && k == trace->loopStart && trace->loopStart < trace->rules.size()) std::cout << "  -- the loop starts here --\n";
  }

  const std::size_t n = trace->rules.size();
  bool reproduced = false;
  if (!monitor.failed() && monitor.stepsTaken() == script.size()) {
    switch (trace->kind) {
      case checker::ReplayedTrace::Kind::Invariant:
      case checker::ReplayedTrace::Kind::ModelError:
        reproduced = monitor.violatedAt() == n;
        if (reproduced) std::cout << fmt::format("violated at step {}, in the running team as in the counterexample: {}\n", n, monitor.violation());
        break;
      case checker::ReplayedTrace::Kind::Deadlock:
        reproduced = monitor.violatedAt() == n && monitor.freeSteps() == 0;
        if (monitor.violatedAt() == n) {
          std::cout << fmt::format("deadlock at step {}, in the running team as in the counterexample: no rule is enabled", n);
          if (*settle > 0) std::cout << fmt::format("; running on freely for {:g} s (no loss, no crash), the team took {} steps the model sees", *settle, monitor.freeSteps());
          std::cout << "\n";
        }
        break;
      case checker::ReplayedTrace::Kind::Lasso:
        if (trace->loopStart >= n) {
          reproduced = true;
          std::cout << fmt::format("the team is in the counterexample's last state after step {}; the run may stay there for ever, and {} never holds\n", n, name);
        } else {
          reproduced = monitor.loopClosedAt().size() == options.loops;
          std::string at;
          for (std::size_t s : monitor.loopClosedAt()) at += (at.empty() ? "" : ", ") + std::to_string(s);
          std::cout << fmt::format("the loop (steps {}..{}) taken {} times: after steps {} the running team is back where the loop starts, so it can go round for ever, and {} never holds\n",
                                   trace->loopStart + 1, n, monitor.loopClosedAt().size(), at, name);
        }
        break;
    }
  }
  // A deadlock or a lasso is no one robot's step: the picture marks it across every robot.
  const bool teamWide = trace->kind == checker::ReplayedTrace::Kind::Deadlock || trace->kind == checker::ReplayedTrace::Kind::Lasso;
  if (reproduced && teamWide && !stepTime.empty()) {
    runtime::TraceEvent mark;
    mark.t = stepTime.back();
    mark.kind = runtime::TraceEvent::Kind::Violation;
    mark.label = trace->kind == checker::ReplayedTrace::Kind::Deadlock ? "deadlock: no rule is enabled" : name + ": the run can go on like this for ever";
    auto at = std::upper_bound(run.events.begin(), run.events.end(), mark.t, [](double t, const runtime::TraceEvent& e) { return t < e.t; });
    run.events.insert(at, mark);
  }
  if (!reproduced) {
    std::cout << "NOT reproduced: the running team departed from the counterexample (a bug of semo; please report it with the trace)\n";
    if (monitor.failed()) std::cout << "  " << monitor.why() << "\n";
    for (const std::string& v : run.summary.violations) std::cout << "  " << v << "\n";
  }
  if (options.traceOut && !writeAtomically(*options.traceOut, runtime::simTraceToJson(run))) {
    std::cerr << errorPrefix() << "cannot write '" << *options.traceOut << "'\n";
    return kBadInput;
  }
  if (options.svg && !writeAtomically(*options.svg, runtime::renderSvg(run))) {
    std::cerr << errorPrefix() << "cannot write '" << *options.svg << "'\n";
    return kBadInput;
  }
  return reproduced ? kViolated : kDiverged;
}

}  // namespace semo::cli
