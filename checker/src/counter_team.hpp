#pragma once
// A team of interchangeable robots seen as counts (counter_abstraction.hpp): which variables are a
// robot's own, which are the team's counts and how each is defined, which rules are one robot's
// template, and expressions evaluated on a state that lists how many robots are in each local
// state instead of the robots themselves.
//
// Values are ranges: a count of "K or more" robots is the range [K, infinity), and an expression
// over it evaluates to every value it may take. A guard whose range holds both 0 and 1 is one the
// abstraction cannot decide (Truth::Unknown): it may be enabled, but is not known to be.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker::counter {

inline constexpr std::int64_t kInfinity = std::int64_t{1} << 40;

struct Range {
  std::int64_t lo = 0, hi = 0;
  [[nodiscard]] bool point() const { return lo == hi; }
};

enum class Truth : std::uint8_t { False, True, Unknown };
Truth truthOf(Range r);

// The team, checked to be one template: every counted robot's variables, rules and count terms
// are the first counted robot's, renamed.
struct Team {
  std::vector<std::int32_t> robots;          // model robot indices, in model order
  std::vector<std::int32_t> memberOf;        // per model variable: index into robots, or -1
  std::vector<std::int32_t> slotOf;          // per model variable of a robot: its slot
  std::vector<std::vector<ir::VarId>> slots; // per robot (index into robots): its variable per slot
  std::vector<std::vector<std::uint32_t>> rules;  // per robot: its rules, aligned with the template's
  std::vector<std::uint32_t> globalRules;    // rules of no robot
  std::vector<ir::VarId> globals;            // variables of no robot that are not counts
  std::vector<std::int32_t> globalIndex;     // per model variable: index into globals, or -1
  struct Count {
    ir::VarId var;
    std::vector<ir::Expr> term;  // per robot: 1 when the robot is counted (reads that robot only)
  };
  std::vector<Count> counts;
  std::vector<std::int32_t> countIndex;      // per model variable: index into counts, or -1
};

// The team of `model`, from the definitions of its counts (Lowering::countDefinitions). nullopt
// with `why` when the model is not one team of interchangeable robots around counts.
std::optional<Team> teamOf(const ir::Model& model, const std::vector<ir::Expr>& countDefinitions, std::string& why);

// Whether robot `a`'s rules, variables and count terms are robot `b`'s renamed (indices into
// Team::robots). `why` says where they differ.
bool sameTemplate(const ir::Model& model, const Team& team, std::size_t a, std::size_t b, std::string& why);

// What an expression reads in an abstract state.
struct Env {
  const Team* team = nullptr;
  std::int32_t self = -1;                   // the robot (index into robots) the slots below are
  const std::int32_t* selfSlots = nullptr;  // its variables, by slot
  const std::vector<const std::int32_t*>* members = nullptr;  // per robot: its slots if known exactly, else null
  const std::int32_t* globals = nullptr;    // by Team::globals index
  const Range* counts = nullptr;            // by Team::counts index
};

// The range of `e`; nullopt when it reads something the state does not know (another counted
// robot's variable) or uses an operator on ranges that the abstraction does not take.
std::optional<Range> evaluate(const ir::Expr& e, const Env& env);

// A state formula over the whole team: `for every robot, p(robot)` and `for some robot` where a
// conjunction or disjunction names every counted robot in the same way.
struct TeamFormula {
  enum class Kind : std::uint8_t { Plain, Every, Some, And, Or, Not };
  Kind kind = Kind::Plain;
  ir::Expr expr;  // Plain: reads no counted robot; Every/Some: the body, for robot `self` of the team
  std::vector<TeamFormula> parts;
};

// `e` as a team formula where the robots outside `explicitRobots` (indices into robots, marked)
// are counted, with the template robot `representative`. nullopt when a counted robot is read on
// its own; `individual` then names the robots read so.
std::optional<TeamFormula> teamFormula(const ir::Model& model, const Team& team, const ir::Expr& e, const std::vector<char>& explicitRobots,
                                       std::size_t representative, std::vector<std::size_t>& individual);

}  // namespace semo::checker::counter
