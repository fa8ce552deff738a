// semo-verify: command-line entry point. Only wires options to the commands.
#include <CLI/CLI.hpp>
#include <malloc.h>

#include <iostream>
#include <new>

#include "commands.hpp"

// A seed is a whole number from 0 up: CLI11 would read "-1" into an unsigned seed as 2^64 - 1.
const CLI::Validator kSeed(
    [](std::string& text) {
      return !text.empty() && text[0] != '-' ? std::string() : "a seed is a whole number from 0 up, not " + text;
    },
    "SEED");

namespace {

// Every command with an example that runs from the repository's top folder: `--help` shows them,
// and an error in a command's options ends with its example.
struct CommandExample {
  const char* name;
  const char* example;
};
constexpr CommandExample kExamples[] = {
    {"parse", "semo-verify parse specs/fig2.semo"},
    {"lint", "semo-verify lint specs/examples/swarm/swarm3.semo --strategy specs/examples/swarm/strategy.xml"},
    {"check", "semo-verify check specs/examples/swarm/swarm3.semo --strategy specs/examples/swarm/strategy.xml"},
    {"show", "semo-verify show cex.json --robot mapper   (cex.json from check --trace-out cex.json)"},
    {"replay", "semo-verify replay cex.json --svg cex.svg   (cex.json from check --trace-out cex.json)"},
    {"graph", "semo-verify graph specs/examples/swarm/swarm3.semo --strategy specs/examples/swarm/strategy.xml --modes -o modes.dot"},
    {"sdf", "semo-verify sdf specs/examples/swarm/swarm3.semo --strategy specs/examples/swarm/strategy.xml"},
    {"analyze", "semo-verify analyze specs/examples/swarm/swarm3.semo --strategy specs/examples/swarm/strategy.xml --loss-prob 0.2"},
    {"simulate", "semo-verify simulate specs/examples/scouting/scouting.semo --strategy specs/examples/scouting/strategy.xml --crash leader@5s"},
    {"emit", "semo-verify emit specs/examples/swarm/swarm3.semo --strategy specs/examples/swarm/strategy.xml --out robots"},
    {"certify", "semo-verify certify robots"},
    {"export", "semo-verify export specs/examples/swarm/swarm3.semo --strategy specs/examples/swarm/strategy.xml --promela -o swarm3.pml"},
    {"world", "semo-verify world specs/examples/swarm/swarm1000.semo --strategy specs/examples/swarm/strategy.xml -o swarm1000.world.json"},
};

const char* exampleOf(const std::string& command) {
  for (const CommandExample& e : kExamples) {
    if (command == e.name) return e.example;
  }
  return nullptr;
}

// The command a failed parse was in ("" before one was named).
std::string commandOf(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) return sub->get_name();
  return {};
}

int run(int argc, char** argv) {
  CLI::App app{"semo-verify: check a multi-robot mission (SeMo language) before it is deployed"};
  app.set_version_flag("--version", std::string("semo-verify ") + semo::cli::kToolVersion);
  app.require_subcommand(1);


  semo::cli::ParseOptions parse;
  CLI::App* parseCmd = app.add_subcommand("parse", "Syntax check: a summary of the mission, or its AST as JSON");
  parseCmd->add_option("MISSION", parse.mission, "Mission file (.semo)")->required();
  parseCmd->add_flag("--json", parse.json, "Print the whole AST as JSON");

  semo::cli::LintOptions lint;
  CLI::App* lintCmd = app.add_subcommand("lint", "Resolve every name against the strategy and the robots; every mistake with its position");
  lintCmd->add_option("MISSION", lint.mission, "Mission file (.semo)")->required();
  lintCmd->add_option("--strategy,-s", lint.strategy, "Strategy file (.xml)")->required();
  lintCmd->add_option("--robots,-r", lint.robotsDir,
                      "Folder of URDF files; strategy URDF paths are resolved against it (default: the strategy's folder)");
  lintCmd->add_flag("--warnings-as-errors,-W", lint.warningsAsErrors, "Exit 2 when there is any warning");
  lintCmd->add_flag("--json", lint.json, "Print the diagnostics and the summary as JSON");
  lintCmd->add_option("--sarif", lint.sarif, "Also write the diagnostics as SARIF 2.1.0 to this file (for code-scanning tools)");

  // --loss: a kind, or a comma-separated list of kinds (none and all stand alone).
  const CLI::Validator lossKinds(
      [](std::string& text) -> std::string {
        if (text == "none" || text == "all") return {};
        for (std::size_t start = 0; start <= text.size();) {
          const std::size_t end = std::min(text.find(',', start), text.size());
          const std::string kind = text.substr(start, end - start);
          if (kind != "publish" && kind != "events" && kind != "knowledge" && kind != "heartbeats") {
            return "'" + kind + "' is not a kind of message that may be lost (publish, events, knowledge, heartbeats; or none, all alone)";
          }
          start = end + 1;
        }
        return {};
      },
      "KIND[,KIND...]");
  auto addModelOptions = [&lossKinds](CLI::App* cmd, semo::cli::ModelInput& in) {
    cmd->add_option("MISSION", in.input, "Mission file (.semo, with --strategy) or IR model (.ir)")->required();
    cmd->add_option("--strategy,-s", in.strategy, "Strategy file (.xml), for a mission");
    cmd->add_option("--robots,-r", in.robotsDir, "Folder of URDF files");
    // --crash N (every team) or N:TEAM (that team), repeatable.
    cmd->add_option_function<std::vector<std::string>>(
           "--crash",
           [&in](const std::vector<std::string>& specs) {
             for (const std::string& spec : specs) {
               const std::size_t colon = spec.find(':');
               const int n = std::stoi(spec.substr(0, colon));
               if (colon == std::string::npos) in.crash = n;
               else in.crashPerTeam[spec.substr(colon + 1)] = n;
             }
           },
           "Up to N robots of each team may crash; N:TEAM for one team (repeatable); overrides the verify block")
        ->check(CLI::Validator(
            [](std::string& spec) -> std::string {
              const std::size_t colon = spec.find(':');
              const std::string n = spec.substr(0, colon);
              if (n.empty() || n.size() > 6 || n.find_first_not_of("0123456789") != std::string::npos) return "'" + spec + "': give N or N:TEAM (N from 0 to 100000)";
              if (std::stoi(n) > 100000) return "'" + spec + "': at most 100000";
              if (colon != std::string::npos && colon + 1 == spec.size()) return "'" + spec + "': a team name after ':'";
              return {};
            },
            "N[:TEAM]"));
    cmd->add_option("--loss", in.loss,
                    "Which messages may be lost: none, all, or publish, events, knowledge, heartbeats, one or a list (events,publish); "
                    "overrides the verify block")
        ->check(lossKinds);
    auto* fair = cmd->add_flag_callback("--fair-loss", [&in] { in.fairLoss = true; },
                                        "A message sent again and again eventually gets through (overrides the verify block)");
    auto* unfair = cmd->add_flag_callback("--unfair-loss", [&in] { in.fairLoss = false; },
                                          "Messages that may be lost may be lost for ever (overrides the verify block)");
    fair->excludes(unfair);
  };

  // The engines' options, shared by check and emit.
  auto addEngineOptions = [](CLI::App* cmd, semo::cli::CheckOptions& check) {
    cmd->add_option("--max-states", check.maxStates, "Stop after this many states (per liveness product; exit 3, partial result)");
    cmd->add_option("--max-memory", check.maxMemoryMiB, "Stop when the state store reaches this many MiB (exit 3)");
    cmd->add_option("--max-depth", check.maxDepth,
                    "Explore only paths of at most this many steps (bounded search: exit 3 unless nothing lies beyond)");
    cmd->add_flag_callback("--no-symmetry", [&check] { check.symmetry = false; },
                           "Store every state, not one per ordering of interchangeable robots (both searches)");
    cmd->add_flag_callback("--no-slicing", [&check] { check.slicing = false; },
                           "Decide each LTL property on the product of the whole model, not on slices of it refined by counterexamples");
    cmd->add_flag_callback("--slices-first", [&check] { check.slicesFirst = true; },
                           "Decide each LTL property on slices first even when the whole state space is small (a small one's products are searched whole first)");
    cmd->add_flag_callback("--no-symbolic", [&check] { check.symbolic = false; },
                           "Give up on a slice too large to enumerate instead of searching it as decision diagrams");
    cmd->add_flag_callback("--no-walks", [&check] { check.walks = false; },
                           "When no slice decides an LTL property, skip the random walks that hunt a fair violation on the whole model");
    cmd->add_option("--seed", check.walkSeed, "Seed of those random walks (default 1): the same seed gives the same walks and verdicts")
        ->check(kSeed);
    cmd->add_option("--symbolic-seconds", check.symbolicSeconds,
                    "Processor time the symbolic searches of one LTL property may take, its slices and the hunt on its cone (default " +
                        std::to_string(static_cast<int>(check.symbolicSeconds)) + "; less ends an undecided property sooner)")
        ->check(CLI::Range(1.0, 86400.0));
    cmd->add_option("--cone-seconds", check.coneSeconds,
                    "Processor time for an LTL property the slices leave undecided: its exact cone of influence, crashes included, "
                    "searched on every settling world (default " + std::to_string(static_cast<int>(check.coneSeconds)) +
                        "; 0: not tried; a proof ends when it is done, so more costs nothing where it is not needed)")
        ->check(CLI::Range(0.0, 86400.0));
    cmd->add_option("--slice-states", check.sliceStates,
                    "Product states one slice of the model may take (default 50000; --max-states, if lower, bounds it too)")
        ->check(CLI::Range(std::uint64_t{1}, UINT64_MAX));
    cmd->add_option("--threads", check.threads,
                    "Threads for the searches (default: SEMO_THREADS if set, else one per core; the results do not depend on it)")
        ->check(CLI::Range(1u, 256u));
    cmd->add_flag("--safety-only", check.safetyOnly, "Check the invariants and deadlock freedom only, not the LTL properties");
    cmd->add_option("--engine", check.engine,
                    "auto (default): a team with counts (more than 8 robots) first by counting, then explicit when the state "
                    "space fits its budget (2,000,000 states, whatever --max-depth says), else smt (with --max-depth for BMC); "
                    "the LTL properties on slices, then on their exact cones. explicit: state-space search only, to --max-states; "
                    "smt: Z3, bounded model checking to --max-depth (default 5), then k-induction and IC3 for unbounded proofs "
                    "(the LTL properties on slices); counting: the counter abstraction only, robots of one team counted per "
                    "local state (proves, never refutes)")
        ->check(CLI::IsMember({"explicit", "smt", "auto", "counting"}));
    cmd->add_flag("--bmc-only", check.bmcOnly, "With the smt engine: bounded model checking only (no k-induction, no IC3)");
    cmd->add_option("--smt-timeout", check.smtTimeoutS,
                    "With the smt engine: give up a solver call (one BMC depth, one IC3 run) after this many seconds; 0: never (default 600)");
  };

  semo::cli::CheckOptions check;
  CLI::App* checkCmd = app.add_subcommand("check", "Prove the mission's properties, or print a counterexample");
  addModelOptions(checkCmd, check.model);
  addEngineOptions(checkCmd, check);
  checkCmd->add_flag("--json", check.json, "Print the verdicts and counterexamples as JSON (specs/trace.md)");
  checkCmd->add_option("--trace-out", check.traceOut,
                       "Also write the verdicts and counterexamples as JSON (what --json prints, specs/trace.md) to this file, for "
                       "`show` and `replay`");
  checkCmd->add_option("--junit", check.junit, "Also write the verdicts as JUnit XML to this file: a test case per property, a violation "
                                              "a failure with its counterexample, unknown skipped");
  checkCmd->add_option("--sarif", check.sarif, "Also write violations and unknowns as SARIF 2.1.0 to this file, at their places in the "
                                              "mission, a counterexample as a code flow");
  checkCmd->add_option("--msc", check.msc, "Draw the first counterexample as a message sequence chart (SVG) in this file");
  checkCmd->add_option("--prop", check.props,
                       "Decide only this property (repeatable; a glob: `*` any text, `?` one character, brackets literal; a name "
                       "without brackets also means its family: --prop unique_leader; a leading ! leaves out what it matches: --prop "
                       "'!mode_agreement'); overrides the verify block's list");
  checkCmd->add_option("--props", check.propsFile,
                       "Decide only the properties this file names: a name or glob per line, or `check a, b` lines as in the verify "
                       "block; # starts a comment");

  semo::cli::ShowOptions show;
  CLI::App* showCmd = app.add_subcommand("show", "Print a kept counterexample again: for one robot, or with every variable");
  showCmd->footer("Print a counterexample of `check --json` or `check --trace-out` again, as check prints it, "
                                                 "for one robot, or with every variable after each step");
  showCmd->add_option("TRACE", show.trace, "A `check --json` / `--trace-out` file")->required();
  showCmd->add_option("MISSION", show.model.input, "Mission or IR file (default: the trace file's \"input\")");
  showCmd->add_option("--strategy,-s", show.model.strategy, "Strategy file (default: the trace file's)");
  showCmd->add_option("--robots,-r", show.model.robotsDir, "Folder of URDF files (default: the trace file's)");
  showCmd->add_option("--property,-p", show.property, "Which counterexample (default: the first violated property)");
  showCmd->add_option("--robot", show.robot, "Only this robot's steps; the others' are counted between them");
  showCmd->add_flag("--full-state", show.fullState, "Every variable after each step, not only those the step changed");
  showCmd->add_option("--msc", show.msc, "Also draw the counterexample as a message sequence chart (SVG) in this file");
  showCmd->add_flag_callback("--no-fingerprint", [&show] { show.checkFingerprint = false; },
                             "Read the trace although the model's fingerprint differs from the file's (the same mission read through "
                             "another path)");

  semo::cli::GraphOptions graph;
  CLI::App* graphCmd = app.add_subcommand("graph", "Draw the mode machines, group blocks or task graphs for Graphviz");
  graphCmd->footer("Draw the mission for Graphviz (dot -Tsvg): each team's mode machine, each group block "
                                                   "with its arms and candidate robots, or each robot's task graph by scenario with "
                                                   "execution times, rates and proven capacities");
  graphCmd->add_option("MISSION", graph.mission, "Mission file (.semo)")->required();
  graphCmd->add_option("--strategy,-s", graph.strategy, "Strategy file (.xml)")->required();
  graphCmd->add_option("--robots,-r", graph.robotsDir, "Folder of URDF files");
  auto* drawings = graphCmd->add_option_group("drawing", "What to draw");
  drawings->add_flag_callback("--modes", [&graph] { graph.what = "modes"; }, "Each team's modes and the events that switch them (default)");
  drawings->add_flag_callback("--groups", [&graph] { graph.what = "groups"; }, "Each group block, its arms and the robots that may take them");
  drawings->add_flag_callback("--tasks", [&graph] { graph.what = "tasks"; },
                              "Each robot's task graph, a cluster per scenario, with proven channel capacities (Z3: a few seconds)");
  drawings->require_option(0, 1);
  graphCmd->add_option("--robot", graph.robot, "With --tasks: only this robot");
  graphCmd->add_option("--output,-o", graph.output, "Write the dot text to this file (default: standard output)");

  semo::cli::EmitOptions emit;
  CLI::App* emitCmd = app.add_subcommand("emit", "Verify, then write one C++ program per robot, a CMake project and certificate.json");
  emitCmd->footer("Verify the mission, then write one C++ program per robot, a CMake project that builds them "
                                                 "against semo_runtime, and certificate.json (specs/certificate.md); refuses (exit 1) "
                                                 "unless every property and every buffer bound is proven");
  addModelOptions(emitCmd, emit.check.model);
  addEngineOptions(emitCmd, emit.check);
  emitCmd->add_option("--out,-o", emit.out, "The folder to write (new, empty, or an earlier emit's, which is replaced)")->required();
  emitCmd->add_flag("--uncertified", emit.uncertified,
                    "Write the programs although not everything is proven: every file and the certificate say so (exit 0)");
  emitCmd->add_option("--proof-timeout", emit.proofTimeoutMs, "Give up one Z3 buffer-bound query after this many milliseconds (default 10000)");

  semo::cli::CertifyOptions certify;
  CLI::App* certifyCmd = app.add_subcommand("certify", "Check an emitted tree without trusting it");
  certifyCmd->footer("Check a tree `emit` wrote without trusting it: the hashes of its inputs and files, and "
                                                       "its tables read back and compared with the verified model's projection, made again "
                                                       "from the inputs (exit 0 valid and certified, 1 a difference, 2 bad input, 3 valid but uncertified)");
  certifyCmd->add_option("DIR", certify.dir, "The folder emit wrote")->required();
  certifyCmd->add_flag("--json", certify.json, "Print the findings as JSON");
  certifyCmd->add_flag("--recheck", certify.recheck, "Also verify the mission again and compare every verdict with the certificate's");

  semo::cli::ExportOptions exportOptions;
  CLI::App* exportCmd = app.add_subcommand("export", "Write the formal model as IR text, Promela (SPIN) or PRISM");
  exportCmd->footer("The mission's formal model as IR text (specs/ir.md), Promela for SPIN, or the PRISM language for PRISM and Storm");
  addModelOptions(exportCmd, exportOptions.model);
  auto* formats = exportCmd->add_option_group("format", "What to write");
  formats->add_flag_callback("--ir", [&] { exportOptions.format = "ir"; }, "The IR in its text form (specs/ir.md)");
  formats->add_flag_callback("--promela", [&] { exportOptions.format = "promela"; }, "Promela for SPIN, one atomic step per rule");
  formats->add_flag_callback("--prism", [&] { exportOptions.format = "prism"; },
                             "The PRISM language, for PRISM or Storm: a dtmc when at most one rule is enabled in every reachable state, "
                             "else an mdp (specs/quantitative.md)");
  formats->require_option(1);
  exportCmd->add_flag("--spin-ltl", exportOptions.spinLiveness,
                      "With --promela: the LTL properties as `ltl` claims under semo's fairness (pan -a -N claim), instead of the invariants");
  exportCmd->add_flag("--spin-bfs", exportOptions.spinBreadthFirst,
                                  "With --promela: no hidden variables, for pan -DBFS (then -m bounds the depth as --max-depth does)");
  exportCmd->add_option("--output,-o", exportOptions.output, "Write to this file (default: standard output)");
  exportCmd->add_option("--props", exportOptions.properties, "With --prism: write the properties (P=?, R=?) to this file");

  semo::cli::SdfOptions sdfOptions;
  CLI::App* sdfCmd = app.add_subcommand("sdf", "Each robot's dataflow task graph, or one graph: schedule, period, proven buffer bounds");
  sdfCmd->footer("Build each robot's dataflow task graph from a mission, or read one graph; analyse every "
                                                "scenario: consistency, deadlock freedom, schedule, throughput, proven buffer bounds");
  sdfCmd->add_option("MISSION", sdfOptions.mission, "Mission file (.semo), with --strategy: one task graph per robot");
  sdfCmd->add_option("--strategy,-s", sdfOptions.strategy, "Strategy file (.xml), for a mission");
  sdfCmd->add_option("--robots,-r", sdfOptions.robotsDir, "Folder of URDF files");
  sdfCmd->add_option("--robot", sdfOptions.robot, "Only this robot's task graph");
  sdfCmd->add_option("--out,-o", sdfOptions.outDir, "Write each robot's task graph as ROBOT.json and ROBOT.dot into this folder");
  sdfCmd->add_option("--graph", sdfOptions.graphJson, "A task graph in semo's JSON form (specs/taskgraph.md)");
  sdfCmd->add_option("--proof-timeout", sdfOptions.proofTimeoutMs, "Give up one Z3 buffer-bound query after this many milliseconds (default 10000)");
  sdfCmd->add_option("--sdf3", sdfOptions.sdf3, "A graph in SDF3's XML format");
  sdfCmd->add_flag("--json", sdfOptions.json, "Print the analysis as JSON");
  sdfCmd->add_flag("--verbose,-v", sdfOptions.verbose,
                   "A mission's or task graph's scenarios in full (repetition vector, schedule, bounds with their capacities), "
                   "not a line each");
  sdfCmd->add_flag("--buffers", sdfOptions.buffers, "Also explore buffer capacities: the throughput-buffer Pareto front");
  sdfCmd->add_option("--dot", sdfOptions.dotOut, "Write the graph for Graphviz to this file");
  sdfCmd->add_option("--write-sdf3", sdfOptions.sdf3Out, "Write the graph in SDF3's format to this file");
  sdfCmd->add_option("--max-distributions", sdfOptions.maxDistributions,
                     "With --buffers: stop after this many buffer distributions (default 200000; exit 3, partial front)");

  semo::cli::SimulateOptions simulate;
  std::string seeds;
  CLI::App* simulateCmd = app.add_subcommand("simulate", "Run the verified mission in a simulated world, with crashes and message loss");
  simulateCmd->footer("Run the verified mission in the simulator (simulated time, injected crashes and "
                                                         "message loss) and summarise what happened (specs/runtime.md)");
  simulateCmd->add_option("MISSION", simulate.mission, "Mission file (.semo)")->required();
  simulateCmd->add_option("--strategy,-s", simulate.strategy, "Strategy file (.xml)")->required();
  simulateCmd->add_option("--robots,-r", simulate.robotsDir, "Folder of URDF files");
  simulateCmd->add_option("--world,-w", simulate.world, "World file (runtime/WORLD.md; default: MISSION.world.json next to the mission)");
  simulateCmd->add_option("--duration", simulate.duration, "Simulated time, e.g. 60s, 500ms, 2min (default 60s)");
  simulateCmd->add_option("--seed", simulate.seed, "Seed of every random choice (the same seed gives the same trace, byte for byte; default 1)")
      ->check(kSeed);
  simulateCmd->add_option("--seeds", seeds, "Run seeds A..B (inclusive) and print statistics instead of one run's summary");
  simulateCmd->add_option("--crash", simulate.crashes,
                          "Crash a robot at a time: ROBOT@TIME, leader@TIME (whoever leads then) or leader:BLOCK@TIME; repeatable");
  simulateCmd->add_option("--loss", simulate.loss, "Probability that a message is lost (messages the model lets be lost; default 0)")
      ->check(CLI::Range(0.0, 1.0));
  simulateCmd->add_option("--loss-model", simulate.lossModel, "How losses are spread: bernoulli (default), burst:N, gilbert:P,R");
  simulateCmd->add_option("--trace", simulate.trace, "Write the run's trace as JSON (semo-simtrace); with --seeds, {seed} in the name gives one file per run");
  simulateCmd->add_option("--svg", simulate.svg, "Write a picture of the run: trajectories and a timeline per robot; {seed} as for --trace");
  simulateCmd->add_flag("--keep-running", simulate.keepRunning, "Go on after the world's goal is reached, until --duration");
  simulateCmd->add_flag("--no-dataflow{false}", simulate.dataflow,
                        "Do not run the robots' task graphs (skips their analysis, which proves the channel capacities at startup)");
  simulateCmd->add_option("--generated", simulate.generated,
                          "Run the tables compiled in a generated project (emit, then build): its build folder or mission_simulation.so; "
                          "refused unless they equal the verified model's projection");
  simulateCmd->add_flag("--check-conformance", simulate.checkConformance,
                        "Replay every step on the verified model as it happens; stop at the first step the model does not allow");

  semo::cli::ReplayOptions replay;
  CLI::App* replayCmd = app.add_subcommand("replay", "Make a counterexample happen in the simulated team, step for step");
  replayCmd->footer("Make a counterexample of `check --json` happen in the running team: the simulator takes its "
                                                     "steps one for one and shows the violation at the same step (specs/runtime.md)");
  replayCmd->add_option("TRACE", replay.trace, "A `check --json` output, or one counterexample object (specs/trace.md)")->required();
  replayCmd->add_option("MISSION", replay.model.input, "Mission file (default: the trace file's \"input\")");
  replayCmd->add_option("--strategy,-s", replay.model.strategy, "Strategy file (default: the trace file's \"strategy\")");
  replayCmd->add_option("--robots,-r", replay.model.robotsDir, "Folder of URDF files (default: the trace file's \"robots\")");
  replayCmd->add_option("--crash", replay.model.crash, "As given to check (default: as the trace file records)")->check(CLI::Range(0, 100000));
  replayCmd->add_option("--loss", replay.model.loss, "As given to check (default: as the trace file records)")->check(lossKinds);
  replayCmd->add_option("--property,-p", replay.property, "Which counterexample of the file (default: the first violated property)");
  replayCmd->add_option("--world,-w", replay.world, "World file for the picture (default: MISSION.world.json when there is one)");
  replayCmd->add_option("--loops", replay.loops, "A lasso's loop is taken this many times (default 3)");
  replayCmd->add_option("--settle", replay.settle, "After a deadlock's last step, run freely this long to show nothing moves (default 10s)");
  replayCmd->add_option("--pace", replay.pace, "Simulated time between two steps (default 500ms)");
  replayCmd->add_option("--save-trace", replay.traceOut, "Write the run's trace as JSON (semo-simtrace)");
  replayCmd->add_option("--svg", replay.svg, "Write a picture of the run: a timeline per robot");
  replayCmd->add_flag("!--no-fingerprint", replay.checkFingerprint,
                      "Replay even when the trace's model fingerprint differs (the mission read through another path)");

  semo::cli::AnalyzeOptions analyze;
  CLI::App* analyzeCmd = app.add_subcommand(
      "analyze", "How likely and how soon: probabilities and expected times");
  analyzeCmd->footer("How likely and how soon: each `eventually {p}` property of the model, on its reachable states read as a Markov decision "
                 "process (specs/quantitative.md): P(within t steps), P(eventually), the expected steps (or rewards)");
  addModelOptions(analyzeCmd, analyze.model);
  analyzeCmd->add_option("--rounds", analyze.rounds, "Horizon of P(within t), in steps of the model (default 20)")->check(CLI::Range(1, 100000));
  analyzeCmd->add_option("--reward", analyze.reward,
                         "Count only the steps of the rules whose names match this glob (e.g. pick: rounds of a synchronous model); "
                         "default: every step");
  analyzeCmd->add_option("--max-states", analyze.maxStates, "Give up beyond this many reachable states (exit 3; default 5000000)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100'000'000}));
  analyzeCmd->add_option("--loss-prob", analyze.lossProb,
                         "A mission: the probability that one copy of a message is lost; measures each knowledge item's spread in "
                         "gossip rounds")
      ->check(CLI::Range(0.0, 1.0));
  analyzeCmd->add_option_function<std::string>(
      "--time",
      [&analyze](const std::string& text) {
        const std::optional<double> s = semo::cli::parseDuration(text);
        if (!s || *s <= 0 || *s > 1e7) throw CLI::ValidationError("--time", "not a duration: " + text + " (e.g. 60s, 2min)");
        analyze.seconds = *s;
      },
      "A mission: the horizon of the heartbeat questions, e.g. 60s, 2min (default 60s)");
  analyzeCmd->add_option("--runs", analyze.runs,
                         "Where the reachable states (of a model, or of a mission's round model) outgrow --max-states, estimate from this many simulated runs "
                         "instead, with confidence bands (default 10000; 0: give up with exit 3)")
      ->check(CLI::Range(0, 100'000'000));
  analyzeCmd->add_option("--seed", analyze.seed, "Seed of those runs (default 1): the same seed gives the same estimate")
      ->check(kSeed);
  analyzeCmd->add_flag("--json", analyze.json, "Print the results as JSON");
  analyzeCmd->add_option("--svg", analyze.svg, "Write a chart of P(within t) against t");

  semo::cli::WorldOptions worldOptions;
  CLI::App* worldCmd = app.add_subcommand("world", "Write a starting world file for a mission, to edit and simulate in");
  worldCmd->footer("Write a world file (runtime/WORLD.md) that `simulate` runs the mission in as it is: the robots in a ring or a "
                   "grid, spaced by their footprints, a place per place the mission names, a site per fact of its group services' "
                   "knowledge, a constant per sensed value it reads, and notes saying what to edit");
  worldCmd->add_option("MISSION", worldOptions.mission, "Mission file (.semo)")->required();
  worldCmd->add_option("--strategy,-s", worldOptions.strategy, "Strategy file (.xml)")->required();
  worldCmd->add_option("--robots,-r", worldOptions.robotsDir, "Folder of URDF files");
  worldCmd->add_option("--output,-o", worldOptions.output, "Write the world to this file (default: print it)");
  worldCmd->add_option("--layout", worldOptions.layout, "How the robots stand: ring (default; facing out) or grid (ranks facing +x)")
      ->check(CLI::IsMember({"ring", "grid"}));

  for (CLI::App* sub : app.get_subcommands({})) {
    if (const char* example = exampleOf(sub->get_name())) {
      const std::string details = sub->get_footer();
      sub->footer((details.empty() ? std::string() : details + "\n\n") + "Example:\n  " + example);
    }
  }
  // After the commands: a footer set before them is every command's too.
  std::string footer = "Examples (from the repository's top folder):\n";
  for (const CommandExample& e : kExamples) footer += std::string("  ") + e.example + "\n";
  app.footer(footer +
             "\nExit codes: 0 everything proven, 1 a property violated, 2 bad input, 3 partial (a limit reached).\n"
             "docs/guide.md describes every command; the language is in specs/language.md, strategies in specs/strategy.md.");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // The command, what is wrong, and an example of the command as it runs.
    const std::string command = commandOf(app);
    semo::setProgramName(command.empty() ? "semo-verify" : "semo-verify " + command);
    const bool unknownCommand = command.empty() && argc > 1 && argv[1][0] != '-';
    std::cerr << semo::cli::errorPrefix()
              << (unknownCommand ? "'" + std::string(argv[1]) + "' is not a command" : argc <= 1 ? std::string("give a command") : std::string(e.what()))
              << "\n";
    if (const char* example = exampleOf(command)) {
      std::cerr << "  e.g. " << example << "\n  (semo-verify " << command << " --help lists its options)\n";
    } else {
      std::cerr << "  the commands: ";
      for (const CommandExample& c : kExamples) std::cerr << c.name << (&c == &kExamples[std::size(kExamples) - 1] ? "" : ", ");
      std::cerr << "\n  (semo-verify --help shows each with an example)\n";
    }
    return semo::cli::kBadInput;
  }
  semo::setProgramName("semo-verify " + commandOf(app));
  semo::cli::setAnnounceWrites(!(lint.json || check.json || certify.json || sdfOptions.json || analyze.json || parse.json));
  // A malformed SEMO_THREADS is said, not quietly replaced by the default.
  if (const std::string why = semo::checker::threadsSettingError(); !why.empty()) {
    std::cerr << semo::cli::errorPrefix() << why << "\n";
    return semo::cli::kBadInput;
  }
  if (*parseCmd) return semo::cli::runParse(parse);
  if (*lintCmd) return semo::cli::runLint(lint);
  if (*checkCmd) return semo::cli::runCheck(check);
  if (*exportCmd) return semo::cli::runExport(exportOptions);
  if (*replayCmd) return semo::cli::runReplay(replay);
  if (*analyzeCmd) return semo::cli::runAnalyze(analyze);
  if (*worldCmd) return semo::cli::runWorld(worldOptions);
  if (*simulateCmd) {
    if (!seeds.empty()) {
      const auto dots = seeds.find("..");
      std::uint64_t from = 0, to = 0;
      try {
        if (dots == std::string::npos) throw std::invalid_argument(seeds);
        std::size_t used = 0;
        from = std::stoull(seeds.substr(0, dots), &used);
        to = std::stoull(seeds.substr(dots + 2));
      } catch (const std::exception&) {
        std::cerr << semo::cli::errorPrefix() << "--seeds '" << seeds << "': expected A..B, e.g. 1..100\n";
        return semo::cli::kBadInput;
      }
      if (to < from || to - from >= 1000000) {
        std::cerr << semo::cli::errorPrefix() << "--seeds '" << seeds << "': B must be at least A, and at most a million runs\n";
        return semo::cli::kBadInput;
      }
      simulate.seed = from;
      simulate.seedsTo = to;
    }
    return semo::cli::runSimulate(simulate);
  }
  if (*emitCmd) return semo::cli::runEmit(emit);
  if (*certifyCmd) return semo::cli::runCertify(certify);
  if (*showCmd) return semo::cli::runShow(show);
  if (*graphCmd) return semo::cli::runGraph(graph);
  if (*sdfCmd) {
    const int inputs = (sdfOptions.mission ? 1 : 0) + (sdfOptions.graphJson ? 1 : 0) + (sdfOptions.sdf3.empty() ? 0 : 1);
    if (inputs != 1) {
      std::cerr << semo::cli::errorPrefix() << "give exactly one of: a mission (with --strategy), --graph G.json, --sdf3 G.xml\n"
                << "  e.g. " << exampleOf("sdf") << "\n";
      return semo::cli::kBadInput;
    }
    if (sdfOptions.mission && !sdfOptions.strategy) {
      std::cerr << semo::cli::errorPrefix() << "a mission needs its strategy: add " << semo::cli::strategyExample(*sdfOptions.mission) << "\n";
      return semo::cli::kBadInput;
    }
    return sdfOptions.sdf3.empty() ? semo::cli::runTaskGraphs(sdfOptions) : semo::cli::runSdf(sdfOptions);
  }
  return semo::cli::kBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  // Z3 allocates and frees blocks of megabytes, query after query. glibc serves a block above its
  // mmap threshold with a fresh mapping and unmaps it when freed, so each query faults its pages in
  // again: after the SMT engine's proofs, emit's buffer-bound proofs of the scouting mission took
  // 23 s instead of 6 (the kernel's page faults, in perf). Blocks up to 32 MiB from the heap, reused.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  // Memory running out (a model too large for the machine: a team of tens of thousands of robots
  // is translated robot pair by robot pair) is a resource limit like --max-memory, said as such,
  // not an abort.
  try {
    return run(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "\nsemo-verify: error: out of memory: the model is too large for this machine's memory (exit 3)\n";
    return semo::cli::kLimit;
  }
}
