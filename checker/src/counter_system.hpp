#pragma once
// The abstract system of the counter abstraction (counter_abstraction.hpp): its states, steps and
// the fairness premises each state offers.
//
// A state is one vector: the variables of no robot that are not counts, then the variables of each
// robot kept exactly, then (local state, count) pairs in increasing local state, count 1 .. K
// (K meaning "K or more"), for the local states some counted robot is in.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "counter_team.hpp"
#include "semo/checker/fairness.hpp"

namespace semo::checker::counter {

struct Label {
  enum class Kind : std::uint8_t { Counted, Explicit, Global, Stutter };
  Kind kind = Kind::Stutter;
  std::uint32_t rule = 0;    // the model rule (Counted: the representative robot's)
  std::int32_t from = -1;    // Counted: the local state left; Explicit: the robot (index into robots)
  std::int32_t to = -1;      // Counted: the local state entered (from when the step keeps it)
};

// "This state enables group g of robots in local state l" (Counted), "... of robot r" (Explicit),
// "... the team-wide group g" (Global), only where the abstraction knows it is enabled.
struct Premise {
  Label::Kind kind;
  std::int32_t where;
  std::uint32_t group;
  auto operator<=>(const Premise&) const = default;
};

class System {
 public:
  using State = std::vector<std::int32_t>;
  struct Step {
    State target;
    Label label;
  };
  struct Expansion {
    std::vector<Step> steps;
    std::vector<Premise> enabled;  // sorted, unique
    bool someKnownEnabled = false;  // some rule known to be enabled (else the run may end here)
  };

  // nullopt-like failure is reported through `error()` after construction or expansion.
  System(const ir::Model& model, const Team& team, std::vector<char> explicitRobots, std::uint32_t threshold);

  [[nodiscard]] const std::string& error() const { return error_; }
  [[nodiscard]] State initial();
  Expansion expand(const State& s);
  [[nodiscard]] Truth holds(const TeamFormula& f, const State& s);
  [[nodiscard]] Truth holds(const ir::Expr& e, const State& s);  // an expression reading no counted robot's variables
  [[nodiscard]] std::size_t localStates() const { return locals_.size(); }
  [[nodiscard]] std::size_t representative() const { return representative_; }
  [[nodiscard]] const std::vector<char>& explicitRobots() const { return explicit_; }
  [[nodiscard]] const Fairness& fairness() const { return fairness_; }

 private:
  struct View {  // a state taken apart
    std::vector<std::int32_t> globals;
    std::vector<const std::int32_t*> members;  // per robot: its slots (explicit robots only)
    std::vector<std::pair<std::uint32_t, std::int32_t>> counts;  // (local state, count)
    std::vector<Range> teamCounts;  // per Team::counts
  };
  View view(const State& s);
  State pack(const std::vector<std::int32_t>& globals, const std::vector<std::vector<std::int32_t>>& explicitSlots,
             const std::vector<std::pair<std::uint32_t, std::int32_t>>& counts) const;
  std::uint32_t localId(const std::vector<std::int32_t>& local);
  Env env(const View& v, std::int32_t self, const std::int32_t* slots) const;
  // The outcomes of one rule fired by `self` with `slots`: new slots and globals, or an error.
  bool fire(const ir::Rule& rule, const View& v, std::int32_t self, const std::int32_t* slots,
            std::vector<std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>>>& out);

  bool countsFollow(const ir::Rule& rule, const ir::Branch& branch, const View& v, std::int32_t self, const std::int32_t* before,
                    const std::int32_t* after);

  const ir::Model& model_;
  const Team& team_;
  std::vector<char> explicit_;
  std::vector<std::size_t> explicitOrder_;  // robots kept exactly, in order
  std::size_t representative_ = 0;
  std::size_t slotCount_ = 0;
  std::int32_t threshold_;
  Fairness fairness_;
  std::vector<std::vector<std::int32_t>> locals_;
  std::map<std::vector<std::int32_t>, std::uint32_t> localIds_;
  std::string error_;
};

}  // namespace semo::checker::counter
