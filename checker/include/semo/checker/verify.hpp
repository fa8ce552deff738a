#pragma once
// Verification as one call: `verify(model, mission, options) -> Report`. Every engine choice
// (`--engine explicit|smt|auto`), every rule for when liveness is not checked and the exit code
// live here, so that `check` and `sdf` print a Report, and `emit` and the certificate read the very
// same value: what the certificate says was proven is what was proven, with no second reading.
//
// A Report holds, per property of the model (the invariants and deadlock freedom, the LTL
// properties, and with the smt engine group formation for every crash set), its verdict, the engine
// that decided it, the kind of proof (complete search, k-induction at k, an IC3 invariant of n
// conjuncts, Z3 over every crash set) and its coverage in words; the searches' figures; and, when
// asked, every robot's task graph with its analysis and proven buffer bounds.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "semo/checker/counter_abstraction.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/checker/group_formation.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/checker/smt_search.hpp"
#include "semo/frontend/diagnostics.hpp"
#include "semo/sdf/task_graph_analysis.hpp"
#include "semo/semantics/ir.hpp"
#include "semo/semantics/mission_model.hpp"

namespace semo::checker {

// Counting: the counter abstraction (counter_abstraction.hpp), for a team of interchangeable
// robots with counts; it proves or leaves undecided, never finds a violation.
enum class Engine : std::uint8_t { Explicit, Smt, Auto, Counting };

struct VerifyOptions {
  bool properties = true;   // decide the model's properties (false: task graphs only, as `sdf` does)
  Engine engine = Engine::Explicit;
  SearchLimits limits;      // the explicit engine (limits.maxDepth: a bounded search; with smt: BMC's K)
  bool safetyOnly = false;  // leave the LTL properties unchecked
  LivenessOptions liveness; // slicing; with the smt engine the whole product is never searched
  SmtOptions smt;           // the smt engine (smt.maxDepth is set from limits.maxDepth when that is bounded)
  std::optional<int> crashOverride;  // --crash N: the budget group formation is decided for (smt)
  std::map<std::string, int> crashPerTeam;  // --crash N:TEAM, before crashOverride
  bool taskGraphs = false;  // generate and analyse every robot's task graph (needs the mission)
  // --prop: only the group formation verdicts whose names match one of these (all when empty); the
  // model's own properties are chosen with selectProperties before verify().
  std::vector<std::string> propertyGlobs;
  // A mission's teams get counts from this many robots on (CountingOptions::countedTeamsFrom).
  std::size_t countedTeamsFrom = 0;
  sdf::BoundsOptions bounds;
};

// --engine auto: the explicit engine decides everything (liveness too) when the state space fits
// this many states; past it, the smt engine's symbolic proofs do not depend on the number of states.
inline constexpr std::uint64_t kAutoStateBudget = 2'000'000;

// A count as people read it: 2000000 as "2,000,000" (the engine's reasons, the CLI's progress).
std::string withThousands(std::uint64_t n);

// How a verdict was reached.
enum class ProofKind : std::uint8_t {
  None,            // not proven (violated, or unknown)
  CompleteSearch,  // explicit: every reachable state (or every fair run of the product) explored
  Exhausted,       // smt: no path is longer than the BMC depth, every reachable state checked
  KInduction,      // smt: k-induction at `k`
  Ic3,             // smt: an inductive strengthening of `conjuncts` conjuncts, checked independently
  Z3Formation,     // smt: a valid assignment of live robots to groups for every crash set in the budget
  Counting,        // counting: every state, or every fair run, of the counter abstraction
};
const char* proofKindName(ProofKind k);  // "complete search", "k-induction", ...

struct PropertyVerdict {
  enum class Kind : std::uint8_t { Safety, Liveness, GroupFormation };
  std::string name, origin;
  Kind kind = Kind::Safety;
  Verdict verdict = Verdict::Unknown;
  std::string engine;  // "explicit", "smt"
  ProofKind proof = ProofKind::None;
  std::uint32_t k = 0;          // KInduction
  std::uint32_t conjuncts = 0;  // Ic3
  std::string coverage;         // what the verdict covers, in words ("all 120 reachable states ...")
  std::optional<Trace> counterexample;
  // A check the verify block names that has nothing to check in this mission (buffer_bounds without
  // any send): proven, and why it holds vacuously. Empty otherwise.
  std::string vacuous;
  // Counting: proven for a team of any size from this many robots (0: for this team only).
  std::size_t everyTeamFrom = 0;
};
const char* propertyKindName(PropertyVerdict::Kind k);  // "safety", "liveness", "group formation"

struct TaskGraphReport {
  sdf::TaskGraph graph;
  sdf::TaskGraphAnalysis analysis;
};

struct Report {
  std::string modelFingerprint;         // SHA-256 of the IR text (fingerprint.hpp)
  std::vector<std::string> assumptions;  // the model's, as every verdict states them
  Engine engine = Engine::Explicit;     // the engine that decided the properties
  std::string engineReason;             // --engine auto: why that one

  // Figures of the searches, for those who print them.
  SearchResult safety;                     // explicit or smt: states, depth, coverage, model error
  std::optional<SmtResult> smt;            // the smt engine's proofs, per invariant
  std::optional<CountingResult> counting;  // the counter abstraction, when it ran
  LivenessResult liveness;                 // explicit engine only
  std::string livenessSkipped;             // why the LTL properties were not checked ("" when they were)
  std::vector<FormationVerdict> formation;  // smt engine on a mission
  std::vector<std::string> formationOrigins;  // "file:line:col" per formation verdict

  // Every property, in the order the engines report them: the invariants (deadlock freedom last),
  // group formation per block (smt), the LTL properties.
  std::vector<PropertyVerdict> properties;

  std::vector<TaskGraphReport> taskGraphs;  // with VerifyOptions::taskGraphs
  std::string taskGraphAssumptions;         // what every task-graph verdict rests on

  // 1: a property violated, a model error, or a task graph with a real defect; 3: something not
  // decided (a limit, a partial engine, a solver timeout); 0: everything proven.
  int exitCode = 0;

  // What keeps the result from being a proof of everything, one line each ("unknown
  // mode_agreement[SlaveTeam]", "scenario SEARCH_MODE of ev3_0: minimality unknown"): empty when
  // every property is proven and every task graph's bounds are (what `emit` needs).
  [[nodiscard]] std::vector<std::string> unproven() const;
};

// `mission` may be null (an IR file): then no group formation and no task graphs. nullopt only when
// the task graphs were asked for and cannot be generated (the reasons are in `diags`).
// A property name against a glob of --prop: `*` any run of characters, `?` any one; everything
// else literal, brackets included, so that `unique_leader[*]` means every unique_leader.
bool globMatches(std::string_view glob, std::string_view name);

// Whether --prop's `globs` choose a property known by any of `names` (a name and its aliases): a
// glob without `[` also matches the family `glob[...]`, as the verify block's `check unique_leader`
// does; a glob starting with `!` leaves out what it matches. Chosen: matched by no `!` glob, and by
// one of the others (or there are only `!` globs: everything but what they leave out).
bool propertySelected(const std::vector<std::string>& globs, const std::vector<std::string>& names);

// Keeps the invariants and LTL properties (and deadlock_freedom, the model's valid end) that `globs`
// choose (propertySelected), and returns the names kept. A glob that matches none of them, or a
// selection that leaves none, is a std::invalid_argument naming the model's properties.
std::vector<std::string> selectProperties(ir::Model& model, const std::vector<std::string>& globs);

std::optional<Report> verify(const ir::Model& model, const model::MissionModel* mission, const VerifyOptions& options,
                             DiagnosticEngine& diags);

// Analyses `graphs` (bounds chosen and proven per scenario) into report.taskGraphs and folds their
// outcome into report.exitCode: `sdf` on a mission or on a task-graph file, and verify itself.
void addTaskGraphs(Report& report, std::vector<sdf::TaskGraph> graphs, const sdf::BoundsOptions& bounds);

// The version of Z3 the proofs ran on ("4.8.12.0"), as certificates record it.
std::string z3Version();

// What every task-graph verdict rests on (also Report::taskGraphAssumptions).
extern const char* const kTaskGraphAssumptions;

}  // namespace semo::checker
