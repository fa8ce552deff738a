#pragma once
// The subcommands of semo-verify. Each returns the process exit code:
// 0 clean, 1 property violated, 2 bad input, 3 resource limit reached.
#include <cstdint>
#include <memory>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "semo/checker/verify.hpp"
#include "semo/frontend/diagnostics.hpp"
#include "semo/frontend/source.hpp"
#include "semo/runtime/tables.hpp"
#include "semo/semantics/ir.hpp"
#include "semo/semantics/mission_model.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::runtime {
struct World;
}
namespace semo::sdf {
struct Period;
}

namespace semo::cli {

// The version every output names (--version, certificates).
inline constexpr const char* kToolVersion = "0.1.0";

// What a message without a file position starts with: "semo-verify check: error: " (the program
// name is set by main once the command is known).
inline std::string errorPrefix() { return programName() + ": error: "; }
inline std::string notePrefix() { return programName() + ": note: "; }

// How to give a mission's strategy, for an error that lacks it: the one next to the mission when
// there is one.
std::string strategyExample(const std::string& mission);

// 4: a replay's running team departed from the counterexample (a bug of semo, never of the mission).
enum ExitCode { kOk = 0, kViolated = 1, kBadInput = 2, kLimit = 3, kDiverged = 4 };

struct ParseOptions {
  std::string mission;
  bool json = false;
};

struct LintOptions {
  std::string mission;
  std::string strategy;
  std::optional<std::string> robotsDir;
  bool warningsAsErrors = false;
  bool json = false;                  // the diagnostics as JSON on stdout
  std::optional<std::string> sarif;   // and as SARIF 2.1.0 in this file
};

struct ModelInput {
  std::string input;  // a mission (.semo, with --strategy) or an IR file (.ir)
  std::optional<std::string> strategy;
  std::optional<std::string> robotsDir;
  std::optional<int> crash;                // --crash N: overrides the verify block
  std::map<std::string, int> crashPerTeam; // --crash N:TEAM (repeatable): that team's budget
  std::optional<std::string> loss;         // --loss none|publish|events|all
  std::optional<bool> fairLoss;            // --fair-loss / --unfair-loss
};

struct CheckOptions {
  ModelInput model;
  std::uint64_t maxStates = 50'000'000;
  std::uint32_t maxDepth = UINT32_MAX;
  bool symmetry = true;
  bool slicing = true;
  bool slicesFirst = false;     // LivenessOptions::slicesFirst
  bool symbolic = true;
  bool walks = true;            // LivenessOptions::walks
  std::uint64_t walkSeed = 1;   // LivenessOptions::walkSeed
  std::uint64_t sliceStates = checker::LivenessOptions{}.sliceStates;
  double symbolicSeconds = checker::LivenessOptions{}.symbolicSeconds;
  // The exact cone is tried by default (the library's default leaves it out): without it, an LTL
  // property that no slice decides stays unknown, as scouting's mode_agreement does.
  double coneSeconds = 600;
  bool safetyOnly = false;
  unsigned threads = 0;  // 0: one per core
  std::uint64_t maxMemoryMiB = 8192;
  bool json = false;
  std::string engine = "auto";  // the best answer without options: counting, explicit or smt, as the model allows
  bool bmcOnly = false;        // smt: bounded model checking only, no unbounded proofs
  std::optional<std::string> traceOut;  // --trace-out: the verdicts and counterexamples as JSON, kept
  std::optional<std::string> junit, sarif;  // the verdicts for CI: JUnit XML, SARIF 2.1.0
  std::optional<std::string> msc;           // the first counterexample as a message sequence chart (SVG)
  unsigned smtTimeoutS = 600;  // smt: per solver call (an IC3 run is one); 0: none
  std::vector<std::string> props;          // --prop: only these properties (globs)
  std::optional<std::string> propsFile;    // --props: more of them, a line each
};

struct ExportOptions {
  ModelInput model;
  std::string format;  // "ir", "promela" or "prism"
  bool spinBreadthFirst = false;
  bool spinLiveness = false;
  std::optional<std::string> output;
  std::optional<std::string> properties;  // --prism: the properties file
};

struct SdfOptions {
  std::string sdf3;  // a graph in SDF3's XML format
  // or a mission (with its strategy), or semo's own task-graph JSON: per-robot task graphs
  std::optional<std::string> mission, strategy, robotsDir, graphJson;
  std::optional<std::string> robot;   // only this robot's graph
  std::optional<std::string> outDir;  // write ROBOT.json and ROBOT.dot per robot there
  unsigned proofTimeoutMs = 10'000;
  bool json = false;
  bool buffers = false;  // also the throughput-buffer Pareto front
  bool verbose = false;  // a mission's or a task graph's: every scenario in full, not a line each
  std::uint64_t maxDistributions = 200'000;
  std::optional<std::string> dotOut, sdf3Out;  // write the graph for Graphviz / in SDF3's format
};

struct EmitOptions {
  CheckOptions check;  // the model and the engines, as for check
  std::string out;
  bool uncertified = false;
  unsigned proofTimeoutMs = 10'000;  // each Z3 buffer-bound proof
};

struct CertifyOptions {
  std::string dir;
  bool json = false;
  bool recheck = false;  // verify again and compare the verdicts with the certificate's
};

struct SimulateOptions {
  std::string mission, strategy;
  std::optional<std::string> robotsDir, world;
  std::string duration = "60s";
  std::uint64_t seed = 1;
  std::optional<std::uint64_t> seedsTo;  // --seeds A..B: seed is A
  std::vector<std::string> crashes;      // ROBOT@TIME
  double loss = 0;
  std::string lossModel = "bernoulli";
  std::optional<std::string> trace, svg;
  bool checkConformance = false;
  bool keepRunning = false;  // go on after the world's goal is reached, to --duration
  bool dataflow = true;      // project and run each robot's task graph (--no-dataflow: skip its analysis)
  std::optional<std::string> generated;  // run the tables of a generated project's simulation module
};

struct AnalyzeOptions {
  ModelInput model;
  std::size_t rounds = 20;              // horizon of P(within t), in steps of the model
  std::optional<std::string> reward;    // a glob of rule names whose steps the expectation counts
  std::size_t maxStates = 5'000'000;
  bool json = false;
  std::optional<std::string> svg;
  std::optional<double> lossProb;       // a mission: the probability that one copy of a message is lost
  double seconds = 60;                  // a mission: the horizon of the heartbeat questions
  std::size_t runs = 10'000;            // simulated runs where a round model outgrows --max-states (0: none)
  std::uint64_t seed = 1;               // of those runs
};

// Fills what the command line left open (input, strategy, robots, overrides) from a trace file's
// header (a `check --json` root). Returns an error in words, or "".
std::string modelInputFromTrace(const nlohmann::json& root, ModelInput& in);

struct GraphOptions {
  std::string mission, strategy;
  std::optional<std::string> robotsDir, robot, output;
  std::string what = "modes";  // modes, groups or tasks
};
int runGraph(const GraphOptions& options);

struct ShowOptions {
  std::string trace;                       // a `check --json` or `check --trace-out` file
  ModelInput model;                        // empty fields: as the trace file records them
  std::optional<std::string> property;     // which counterexample (default: the first)
  std::optional<std::string> robot;        // only this robot's steps (the others counted)
  bool fullState = false;                  // every variable after each step
  std::optional<std::string> msc;          // also draw it as a message sequence chart (SVG)
  bool checkFingerprint = true;
};
int runShow(const ShowOptions& options);

struct ReplayOptions {
  std::string trace;                 // a `check --json` output, or one counterexample object
  ModelInput model;                  // empty fields: as the trace file records them
  std::optional<std::string> property, world;
  std::size_t loops = 3;             // a lasso's loop, taken this many times
  std::string settle = "10s";        // free run after a deadlock's last step
  std::string pace = "500ms";        // simulated time between two steps
  std::optional<std::string> traceOut, svg;
  bool checkFingerprint = true;
};

// A model read from an IR file, or a mission loaded and translated (then `mission` too).
struct BuiltModel {
  SourceManager sources;
  std::optional<model::MissionModel> mission;
  std::optional<Translation> translation;  // a mission's: the IR and what it means (emit projects it)
  std::optional<ir::Model> model;
  double buildSeconds = 0;  // reading and translating
};
class ProgressLine;
// Diagnostics are printed; null on error. `line`, if given, is told the phase (reading,
// translating) for a long build.
// `warnings`: print lint's warnings too (show, reading a model checked before, prints only errors).
std::unique_ptr<BuiltModel> buildModel(const ModelInput& in, ProgressLine* line = nullptr, bool warnings = true);
// The options of `check` as the verification facade takes them; `line`, if given, gets the
// searches' phases and counts.
checker::VerifyOptions verifyOptions(const CheckOptions& options, ProgressLine* line = nullptr);
// The model's size and what the search will try, before a search (check, emit).
void announceSearch(const BuiltModel& built, const CheckOptions& options, ProgressLine& line);
// A Report as `check` prints it (check_report.cpp).
std::string reportText(const checker::Report& report, const ir::Model& model, const std::string& input, bool bmcOnly);
nlohmann::json reportJson(const checker::Report& report, const ir::Model& model, const ModelInput& in);
// A duration for people, three significant digits: "2.1 ms", "12.3 s", "2.08 min".
std::string durationText(double seconds);
// 1234567 as "1,234,567" (the checker's, which says its reasons so).
using checker::withThousands;
// For CI (check_formats.cpp): JUnit XML (a test case per property), SARIF 2.1.0 of the verdicts
// (violations and unknowns with their places, a counterexample as a code flow), and of diagnostics.
std::string junitXml(const checker::Report& report, const ir::Model& model, const std::string& input);
std::string checkSarif(const checker::Report& report, const ir::Model& model);
std::string diagnosticsSarif(const SourceManager& sources, const DiagnosticEngine& diags);
// The closing line of `check`: "result: 6 proven, 0 violated, 4 unknown (a, b, c, 1 more) — exit 3 (partial)".
std::string resultLine(const checker::Report& report);

// Records in a `check --json` root how the model was built (strategy, robots, overrides).
void addModelInput(nlohmann::json& root, const ModelInput& in);

// "60s", "60", "500ms", "2min" -> seconds (nullopt: not a duration).
std::optional<double> parseDuration(std::string_view text);
// MISSION.world.json next to the mission.
std::string defaultWorldPath(const std::string& mission);
// A value the strategy reads from one source for the team (source="team") that the world gives by
// region or by a sensor would be read differently by robots in different places: what the checker
// assumed would not be what runs. One sentence per such value.
std::vector<std::string> teamSourceProblems(const model::MissionModel& mission, const runtime::World& world);

// Writes through a temporary file and renames it, so that a failure never leaves half a file; says
// on stderr which file it wrote ("semo-verify simulate: wrote run.svg") unless told not to (a
// --json run keeps stderr for errors).
bool writeAtomically(const std::string& path, const std::string& text);
void setAnnounceWrites(bool on);
// One line of text (no newline in it) within `width` columns, ending in a newline: words that do
// not fit move to continuation lines indented by `indent`; a word longer than a line stays whole.
std::string wrapText(const std::string& line, std::size_t indent, std::size_t width = 100);

// No output replaces an input. Each output (its option, for the message, and its path) against each
// input file, and each file of an input folder (--robots), as std::filesystem::equivalent sees them
// (another name of the same file counts); and each output where it can be written (a file name, in
// a folder that exists). Prints the error and returns false on the first problem; commands call it
// before writing anything, so that a run that cannot write one of its outputs writes none.
struct Output {
  std::string flag, path;
  bool inNewFolder = false;  // its folder may be missing: the run makes it (sdf --out)
};
bool outputsSpareInputs(const std::vector<Output>& outputs, const std::vector<std::string>& inputs);
// Every file a run read through its SourceManager (mission, strategy, URDFs, ...), to add to `inputs`.
std::vector<std::string> filesRead(const SourceManager& sources);

// The tables of a generated project's simulation module (a build folder or the module itself);
// nullopt with `error` when it cannot be loaded or was built against another runtime.
std::optional<runtime::MissionTables> loadGeneratedTables(const std::string& path, std::string& error);
// The certificate of the generated project a --generated path is in (its build folder, or the module).
std::optional<std::string> generatedCertificate(const std::string& path);
// The model options (--crash, --loss, --fair-loss) a certificate records; false with `error`.
bool modelOptionsOf(const std::string& certificate, TranslationOptions& out, std::string& error);
// Where two tables first differ, in words ("" when they are equal).
std::string firstTableDifference(const runtime::MissionTables& expected, const runtime::MissionTables& actual);

// A period p/q as the sdf commands print it ("3" or "7/2").
std::string periodText(const sdf::Period& p);

// `world MISSION --strategy S`: a starting world file for the mission (runtime/WORLD.md), to edit.
struct WorldOptions {
  std::string mission, strategy;
  std::optional<std::string> robotsDir;
  std::optional<std::string> output;  // default: stdout
  std::string layout = "ring";        // ring or grid
};
int runWorld(const WorldOptions& options);

int runParse(const ParseOptions& options);
int runSdf(const SdfOptions& options);
// `sdf MISSION --strategy S` and `sdf --graph G.json` (taskgraph_command.cpp).
int runTaskGraphs(const SdfOptions& options);
int runCheck(const CheckOptions& options);
int runExport(const ExportOptions& options);
int runLint(const LintOptions& options);
int runSimulate(const SimulateOptions& options);
int runReplay(const ReplayOptions& options);
int runAnalyze(const AnalyzeOptions& options);
int runEmit(const EmitOptions& options);
int runCertify(const CertifyOptions& options);

}  // namespace semo::cli
