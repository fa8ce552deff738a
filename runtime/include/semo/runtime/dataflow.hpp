#pragma once
// A robot's dataflow while it runs (specs/runtime.md, "Dataflow"): one static schedule per scenario
// of its projected task graph (dataflow_tables.hpp), each over token counters of the proven
// capacities, all built and allocated when the runner is; afterwards selecting a scenario and
// running iterations allocates nothing.
//
// Time: a selected scenario starts an iteration at the moment it is selected and then one every
// period (the period the analysis computed for it within the proven capacities). advance(d) runs
// the iterations that start within the next d microseconds of the scenario's time; the caller
// decides how often to call it (the simulator: once per control period).
//
// Tokens only: the simulated tasks carry no data, so a channel's state is its token count.
// Generated robot programs will move values through BoundedChannels of the same capacities.
#include <cstdint>
#include <vector>

#include "semo/runtime/channel.hpp"
#include "semo/runtime/dataflow_tables.hpp"

namespace semo::runtime {

class DataflowRunner {
 public:
  explicit DataflowRunner(const DataflowTable& table);

  // Sound, with a schedule and a positive period: the only scenarios the runner fires.
  [[nodiscard]] bool runnable(Id scenario) const;

  // From now on `scenario` runs (kNone: none). A change starts the new scenario afresh: its channels
  // at their initial tokens (the control task issues the commands of its first iteration when a
  // scenario starts, specs/taskgraph.md), its first iteration due at once. The scenario left is
  // always between two iterations (advance runs whole iterations), so it leaves no tokens behind.
  void select(Id scenario);
  [[nodiscard]] Id selected() const { return selected_; }

  struct Advance {
    std::uint64_t iterations = 0;                               // completed in this call
    StaticSchedule::Stall stall = StaticSchedule::Stall::None;  // the iteration that could not complete, if one
    Id task = kNone, channel = kNone;                           // where: DataflowTable task and channel
  };
  // `micros` more of the selected scenario's time: runs the iterations that start within it. A stall
  // stops that scenario for the rest of the run (a static schedule cannot go on past it); by the
  // capacity proof it never happens.
  Advance advance(std::int64_t micros);

  [[nodiscard]] bool stopped(Id scenario) const { return stopped_[scenario] != 0; }
  [[nodiscard]] std::uint64_t iterations(Id scenario) const { return schedules_[scenario].iterations(); }
  [[nodiscard]] const StaticSchedule& schedule(Id scenario) const { return schedules_[scenario]; }
  [[nodiscard]] std::size_t scenarioCount() const { return schedules_.size(); }
  // The most tokens channel c (DataflowTable::channels) held in any scenario so far.
  [[nodiscard]] std::int64_t maxFill(Id channel) const;

 private:
  const DataflowTable* table_;
  std::vector<StaticSchedule> schedules_;  // per scenario
  std::vector<std::uint8_t> stopped_;      // per scenario: stalled once
  Id selected_ = kNone;
  std::int64_t elapsed_ = 0;   // microseconds of the selected scenario's time run so far
  std::uint64_t started_ = 0;  // its iterations started since it was selected
};

}  // namespace semo::runtime
