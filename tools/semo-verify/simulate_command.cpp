// `simulate MISSION --strategy S [--world W]`: runs the verified mission's step tables in the
// simulator (runtime/simulator.hpp), with crashes and message loss injected, and prints what
// happened; --check-conformance replays every step on the IR as it happens.
#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <iostream>
#include <limits>
#include <unistd.h>

#include "commands.hpp"
#include "semo/checker/conformance.hpp"
#include "semo/checker/fingerprint.hpp"
#include "semo/codegen/project.hpp"
#include "semo/codegen/project_dataflow.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::cli {

namespace {

// The closest any robot came to an obstacle over the run (metres; 0: it reached one), from the
// trace's pose samples.
// A robot whose centre is this close has its front on the obstacle: it has reached it.
constexpr double kTouching = 0.12;

// --trace and --svg name one file per run with {seed} in them (required with --seeds).
constexpr std::string_view kSeedField = "{seed}";
std::string perSeed(std::string path, std::uint64_t seed) {
  for (auto at = path.find(kSeedField); at != std::string::npos; at = path.find(kSeedField, at)) {
    path.replace(at, kSeedField.size(), std::to_string(seed));
  }
  return path;
}

double closestToObstacle(const runtime::SimTrace& trace) {
  double closest = std::numeric_limits<double>::infinity();
  for (const runtime::PoseSample& s : trace.poses) {
    for (const runtime::Pose& p : s.poses) {
      for (const runtime::Obstacle& o : trace.world.obstacles) closest = std::min(closest, o.shape.distance({p.x, p.y}));
    }
  }
  return closest;
}

std::string robotName(const runtime::MissionTables& t, std::uint32_t r) { return r < t.robots.size() ? t.robots[r].name : "none"; }

// The robots' dataflow in one line (specs/runtime.md, "Dataflow"), and the scenarios not run.
void printDataflow(const runtime::MissionTables& t, const std::vector<runtime::DataflowRunSummary>& robots) {
  std::uint64_t iterations = 0, scenarios = 0, stalls = 0, overflows = 0, channels = 0, full = 0, running = 0;
  std::int64_t fill = -1, capacity = 0;
  std::string fullest;
  std::vector<std::string> notRun;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const runtime::DataflowRunSummary& d = robots[r];
    std::uint64_t mine = 0;
    for (std::uint64_t n : d.iterations) mine += n, scenarios += n > 0 ? 1 : 0;
    iterations += mine;
    running += mine > 0 ? 1 : 0;
    stalls += d.stalls, overflows += d.overflows;
    for (std::size_t c = 0; c < d.capacity.size(); ++c) {
      if (d.capacity[c] <= 0) continue;  // in no scenario with bounds
      ++channels;
      full += d.maxFill[c] >= d.capacity[c] ? 1 : 0;
      if (d.maxFill[c] <= fill) continue;
      fill = d.maxFill[c], capacity = d.capacity[c];
      fullest = robotName(t, static_cast<std::uint32_t>(r)) + " " + d.channels[c];
    }
    for (const std::string& n : d.notRun) notRun.push_back(robotName(t, static_cast<std::uint32_t>(r)) + " " + n);
  }
  std::cout << fmt::format("  dataflow: {} iterations of {} scenarios on {} robots", withThousands(iterations), scenarios, running);
  if (fill >= 0) std::cout << fmt::format(", largest fill {}/{} tokens ({})", fill, capacity, fullest);
  std::cout << fmt::format(", {} of {} channels reached their proven capacity, {} stalls, {} overflows\n", full, channels, stalls, overflows);
  if (!notRun.empty()) {
    std::cout << fmt::format("  dataflow: {} scenarios not run, their schedule not proven safe (no bounds claimed): {}", notRun.size(),
                             notRun.front());
    if (notRun.size() > 1) std::cout << fmt::format("; ... ({} in all)", notRun.size());
    std::cout << "\n";
  }
}

void printSummary(const runtime::MissionTables& t, const runtime::SimTrace& trace, bool checked) {
  const runtime::TraceSummary& s = trace.summary;
  std::cout << fmt::format("simulated {:.3f} s, seed {}; faults: {}\n", trace.duration, trace.seed, trace.faults);
  if (s.completed) std::cout << fmt::format("  mission: completed at {:.3f} s{}\n", s.completedAt, s.goalStated ? " (the world's goal)" : " (every live robot finished)");
  else std::cout << "  mission: not completed" << (s.goalStated ? " (the world's goal was not reached)" : "") << "\n";
  std::cout << "  mode changes:";
  std::size_t shown = 0;
  for (const auto& [at, what] : s.modeChanges) {
    if (shown++ == 12) {
      std::cout << fmt::format(" ... ({} in all)", s.modeChanges.size());
      break;
    }
    std::cout << fmt::format("{} {} at {:.3f} s", shown == 1 ? "" : ";", what, at);
  }
  std::cout << (s.modeChanges.empty() ? " none\n" : "\n");
  for (const runtime::LeaderChange& c : s.leaderChanges) {
    std::cout << fmt::format("  leader of {}: {} at {:.3f} s", c.block, robotName(t, c.to), c.t);
    if (c.from != runtime::kNoRobot) std::cout << " (after " << robotName(t, c.from) << ")";
    if (c.sinceCrash >= 0) std::cout << fmt::format(", {:.3f} s after {} crashed", c.sinceCrash, robotName(t, c.from));
    std::cout << "\n";
  }
  for (const auto& [item, at] : s.convergedAt) {
    if (at >= 0) std::cout << fmt::format("  knowledge {}: every live robot holds the same facts from {:.3f} s to the end\n", item, at);
    else std::cout << fmt::format("  knowledge {}: not the same at every live robot at the end\n", item);
  }
  std::cout << fmt::format("  messages: {} sent, {} lost\n", s.messagesSent, s.messagesLost);
  if (!trace.world.obstacles.empty()) std::cout << fmt::format("  closest to an obstacle: {:.3f} m\n", closestToObstacle(trace));
  if (!s.dataflow.empty()) printDataflow(t, s.dataflow);
  if (!s.outsideAssumptions.empty()) std::cout << "  outside the model's assumptions: " << s.outsideAssumptions << " (conformance no longer claimed from there)\n";
  if (checked) {
    std::cout << fmt::format("  conformance: {} steps replayed on the model, {}\n", s.stepsChecked,
                             s.mismatches == 0 && s.violations.empty() ? "every one a step the model allows" : "MISMATCH");
  }
  for (const std::string& v : s.violations) std::cout << "  " << v << "\n";
}

}  // namespace

namespace {

// Why `who` names no robot that --crash can crash: a robot of the mission, `leader` (whoever leads
// the first leader block that has a leader then) or `leader:BLOCK` (a leader block whose name holds
// BLOCK). Empty when it does.
std::string crashTargetProblem(const runtime::MissionTables& tables, const std::string& who) {
  std::vector<std::string> blocks;
  for (const runtime::LeaderBlockTable& l : tables.leaderBlocks) blocks.push_back(l.name);
  const std::string listed = blocks.empty() ? std::string("the mission has no leader block") : "its leader blocks: " + fmt::format("{}", fmt::join(blocks, ", "));
  if (who == "leader") return blocks.empty() ? "there is no leader to crash: " + listed : std::string();
  if (who.rfind("leader:", 0) == 0) {
    const std::string block = who.substr(7);
    const bool found = !block.empty() && std::any_of(blocks.begin(), blocks.end(), [&](const std::string& b) { return b.find(block) != std::string::npos; });
    return found ? std::string() : "no leader block is named like '" + block + "' (" + listed + ")";
  }
  std::vector<std::string> robots;
  for (const runtime::RobotTable& r : tables.robots) {
    if (r.name == who) return {};
    robots.push_back(r.name);
  }
  return "the mission has no robot '" + who + "' (its robots: " + fmt::format("{}", fmt::join(robots, ", ")) +
         "; or leader, leader:BLOCK)";
}

}  // namespace

int runSimulate(const SimulateOptions& options) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::optional<model::MissionModel> mission = loadMission({options.mission, options.strategy, options.robotsDir}, sources, diags);
  // A generated project's tables were projected from the model as emit built it (--crash, --loss, ...):
  // its certificate says how, and the same model is built here.
  TranslationOptions modelOptions;
  if (options.generated) {
    if (const std::optional<std::string> certificate = generatedCertificate(*options.generated)) {
      std::string error;
      if (!modelOptionsOf(*certificate, modelOptions, error)) {
        std::cerr << errorPrefix() << "--generated: " << error << "\n";
        return kBadInput;
      }
    }
  }
  std::optional<Translation> translation;
  if (mission) translation = translateMission(*mission, modelOptions, sources, diags);
  for (const Diagnostic& d : diags.diagnostics()) std::cerr << diags.format(d);
  if (!translation) return kBadInput;
  runtime::MissionTables tables = codegen::project(*mission, *translation, sources);
  tables.modelFingerprint = checker::modelFingerprint(translation->model);

  std::string worldPath = options.world.value_or("");
  if (worldPath.empty()) {
    worldPath = defaultWorldPath(options.mission);
    if (!std::filesystem::exists(worldPath)) {
      std::cerr << errorPrefix() << "no world given and no " << worldPath << " next to the mission; give one with --world (runtime/WORLD.md),\n"
                << "  or write a starting one to edit: semo-verify world " << options.mission << " --strategy " << options.strategy << " -o "
                << worldPath << "\n";
      return kBadInput;
    }
  }
  std::vector<runtime::WorldError> worldErrors;
  std::optional<runtime::World> world = runtime::readWorld(worldPath, worldErrors);
  for (const runtime::WorldError& e : worldErrors) std::cerr << runtime::formatWorldError(e);
  if (!world) return kBadInput;
  std::vector<std::string> problems = runtime::checkWorld(tables, *world);
  if (mission) {
    for (std::string& p : teamSourceProblems(*mission, *world)) problems.push_back(std::move(p));
  }
  for (const std::string& p : problems) std::cerr << worldPath << ": error: " << p << "\n";
  if (!problems.empty()) return kBadInput;

  runtime::SimulationOptions sim;
  auto duration = parseDuration(options.duration);
  if (!duration || *duration <= 0 || *duration > 86400) {
    std::cerr << errorPrefix() << "--duration '" << options.duration << "': expected a time such as 60s, 500ms or 2min (at most a day)\n";
    return kBadInput;
  }
  sim.duration = *duration;
  sim.stopAtGoal = !options.keepRunning;
  sim.loss = options.loss;
  std::string error;
  std::optional<runtime::LossModel> lossModel = runtime::LossModel::parse(options.lossModel, error);
  if (!lossModel) {
    std::cerr << errorPrefix() << error << "\n";
    return kBadInput;
  }
  sim.lossModel = *lossModel;
  for (const std::string& c : options.crashes) {
    const auto at = c.rfind('@');
    std::optional<double> when = at == std::string::npos ? std::nullopt : parseDuration(std::string_view(c).substr(at + 1));
    const std::string who = at == std::string::npos ? c : c.substr(0, at);
    if (!when) {
      std::cerr << errorPrefix() << "--crash '" << c << "': expected ROBOT@TIME (a robot of the mission, or leader, or leader:BLOCK; e.g. ev3_1@5s)\n";
      return kBadInput;
    }
    if (const std::string why = crashTargetProblem(tables, who); !why.empty()) {
      std::cerr << errorPrefix() << "--crash '" << c << "': " << why << "\n";
      return kBadInput;
    }
    sim.crashes.push_back({who, *when});
  }
  // With --seeds, one trace and one picture per run: {seed} in the file name says where.
  const std::uint64_t lastSeed = options.seedsTo.value_or(options.seed);
  for (const auto& [flag, path] : {std::pair{"--trace", options.trace}, std::pair{"--svg", options.svg}}) {
    if (path && options.seedsTo && path->find(kSeedField) == std::string::npos) {
      std::cerr << errorPrefix() << flag << " '" << *path << "': with --seeds, one file per run: put " << kSeedField
                << " in the name (e.g. runs/seed" << kSeedField << ".json)\n";
      return kBadInput;
    }
  }
  std::vector<Output> outputs;
  for (std::uint64_t seed = options.seed; seed <= lastSeed; ++seed) {
    if (options.trace) outputs.push_back({"--trace", perSeed(*options.trace, seed)});
    if (options.svg) outputs.push_back({"--svg", perSeed(*options.svg, seed)});
  }
  std::vector<std::string> inputs = filesRead(sources);
  inputs.insert(inputs.end(), {options.robotsDir.value_or(""), worldPath});
  if (!outputsSpareInputs(outputs, inputs)) return kBadInput;
  // Last before running, as it takes a while (the schedules' safety proofs). Its own diagnostics: a strategy
  // whose task graphs do not fit together still simulates, without dataflow.
  if (options.dataflow) {
    DiagnosticEngine dataflowDiags(sources);
    if (!codegen::projectDataflow(*mission, tables, dataflowDiags)) {
      for (const Diagnostic& d : dataflowDiags.diagnostics()) std::cerr << dataflowDiags.format(d);
      std::cerr << notePrefix() << "the robots' task graphs have errors (above): simulating without their dataflow\n";
    }
  }
  if (options.generated) {
    // The generated code's own tables run, once known to be the projection of the verified model.
    std::string loadError;
    std::optional<runtime::MissionTables> generated = loadGeneratedTables(*options.generated, loadError);
    if (!generated) {
      std::cerr << errorPrefix() << "--generated: " << loadError << "\n";
      return kBadInput;
    }
    if (!options.dataflow) {
      for (runtime::RobotTable& r : generated->robots) r.dataflow = {};
    }
    if (const std::string diff = firstTableDifference(tables, *generated); !diff.empty()) {
      std::cerr << errorPrefix() << "--generated: the module's tables are not the verified model's projection: " << diff
                << " (they were emitted from other inputs, or the module was not built again since: emit from these inputs, and build)\n";
      return kViolated;
    }
    tables = std::move(*generated);
    std::cout << "running the generated tables of " << *options.generated << " (equal to the verified model's projection)\n";
  }
  const runtime::TaskLibrary library = runtime::TaskLibrary::standard();
  auto runOne = [&](std::uint64_t seed) {
    sim.seed = seed;
    std::optional<checker::ConformanceMonitor> monitor;
    if (options.checkConformance) monitor.emplace(translation->model, tables);
    runtime::SimTrace trace = runtime::simulate(tables, *world, library, sim, monitor ? &*monitor : nullptr);
    trace.mission = options.mission;
    trace.strategy = options.strategy;
    return trace;
  };

  // The run's trace and picture, when asked for (false: one could not be written).
  auto write = [&](const runtime::SimTrace& trace) {
    for (const auto& [path, render] : {std::pair{options.trace, &runtime::simTraceToJson}, std::pair{options.svg, &runtime::renderSvg}}) {
      if (!path) continue;
      const std::string file = perSeed(*path, trace.seed);
      if (!writeAtomically(file, render(trace))) {
        std::cerr << errorPrefix() << "cannot write '" << file << "'\n";
        return false;
      }
    }
    return true;
  };

  if (!options.seedsTo) {
    runtime::SimTrace trace = runOne(options.seed);
    printSummary(tables, trace, options.checkConformance);
    if (!write(trace)) return kBadInput;
    return trace.summary.violations.empty() ? kOk : kViolated;
  }

  // Many seeds: one line of statistics per measure.
  std::uint64_t completed = 0, mismatched = 0, outside = 0, runs = 0, sent = 0, lost = 0;
  std::uint64_t dataflowIterations = 0, dataflowStalls = 0, dataflowOverflows = 0;
  double completionSum = 0, completionMax = 0, takeoverMax = -1;
  double closestMin = std::numeric_limits<double>::infinity(), closestMax = 0;
  std::uint64_t reachedObstacle = 0;
  const bool progress = isatty(STDERR_FILENO) != 0;
  for (std::uint64_t seed = options.seed; seed <= *options.seedsTo; ++seed, ++runs) {
    runtime::SimTrace trace = runOne(seed);
    if (!write(trace)) return kBadInput;
    const runtime::TraceSummary& s = trace.summary;
    if (s.completed) ++completed, completionSum += s.completedAt, completionMax = std::max(completionMax, s.completedAt);
    if (!s.violations.empty()) {
      ++mismatched;
      std::cout << "seed " << seed << ": " << s.violations.front() << "\n";
    }
    if (!s.outsideAssumptions.empty()) ++outside;
    sent += s.messagesSent, lost += s.messagesLost;
    for (const runtime::DataflowRunSummary& d : s.dataflow) {
      for (std::uint64_t n : d.iterations) dataflowIterations += n;
      dataflowStalls += d.stalls, dataflowOverflows += d.overflows;
    }
    if (!trace.world.obstacles.empty()) {
      const double closest = closestToObstacle(trace);
      closestMin = std::min(closestMin, closest), closestMax = std::max(closestMax, closest);
      if (closest <= kTouching) ++reachedObstacle;
    }
    for (const runtime::LeaderChange& c : s.leaderChanges) takeoverMax = std::max(takeoverMax, c.sinceCrash);
    if (progress) std::cerr << "\rseed " << seed << " (" << runs + 1 << " of " << *options.seedsTo - options.seed + 1 << ")" << std::flush;
  }
  if (progress) std::cerr << "\n";
  std::cout << fmt::format("{} runs (seeds {}..{}), {:g} s each at most\n", runs, options.seed, *options.seedsTo, sim.duration);
  std::cout << fmt::format("  mission completed: {} of {}", completed, runs);
  if (completed > 0) std::cout << fmt::format(" (mean {:.3f} s, latest {:.3f} s)", completionSum / static_cast<double>(completed), completionMax);
  std::cout << "\n";
  if (takeoverMax >= 0) std::cout << fmt::format("  a crashed leader was replaced within {:.3f} s at worst\n", takeoverMax);
  if (closestMax > 0 || reachedObstacle > 0) {
    std::cout << fmt::format("  closest to an obstacle: {:.3f} m at worst, {:.3f} m at best; {} runs where a robot reached one\n", closestMin,
                             closestMax, reachedObstacle);
  }
  std::cout << fmt::format("  messages: {} sent, {} lost in all\n", withThousands(sent), withThousands(lost));
  if (outside > 0) std::cout << fmt::format("  {} runs left the model's assumptions\n", outside);
  if (std::any_of(tables.robots.begin(), tables.robots.end(), [](const runtime::RobotTable& r) { return !r.dataflow.tasks.empty(); })) {
    std::cout << fmt::format("  dataflow: {} iterations in all, {} stalls, {} overflows\n", withThousands(dataflowIterations), dataflowStalls,
                             dataflowOverflows);
  }
  if (options.checkConformance) std::cout << fmt::format("  conformance: {} runs with a mismatch or a violated property\n", mismatched);
  return mismatched == 0 ? kOk : kViolated;
}

}  // namespace semo::cli
