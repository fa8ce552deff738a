#pragma once
// Watches a replay (runtime/replay.hpp): the running team must take the counterexample's steps one
// for one, each the very rule of the trace, enabled where the team is and leading to exactly the
// state the trace records (the conformance monitor's check, plus the trace's own states), and the
// violation must happen where the trace says:
//  - an invariant: the first state of the running team where the property fails;
//  - a deadlock: after the last step no rule is enabled (and, in the free run that follows, the
//    team takes no step the model sees);
//  - an update out of range: the last step leaves a variable's declared range;
//  - a lasso: each time round the loop the team is back in the state where the loop starts.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "semo/checker/conformance.hpp"
#include "semo/checker/trace_reader.hpp"

namespace semo::checker {

class ReplayMonitor final : public runtime::StepObserver {
 public:
  // `loops`: how many times a lasso's loop is taken (the script is replayScript(trace, loops)).
  ReplayMonitor(const ir::Model& model, const runtime::MissionTables& tables, const ReplayedTrace& trace, std::size_t loops);
  bool onStep(const runtime::StepReport& step) override;
  [[nodiscard]] std::string why() const override { return why_; }

  // The IR rules the team is to take: the trace's steps, a lasso's loop `loops` times.
  static std::vector<runtime::Id> script(const ReplayedTrace& trace, std::size_t loops);

  [[nodiscard]] std::size_t stepsTaken() const { return taken_; }            // of the script
  [[nodiscard]] std::size_t scriptLength() const { return script_.size(); }
  [[nodiscard]] std::optional<std::size_t> violatedAt() const { return violatedAt_; }  // 1-based step of the script
  [[nodiscard]] const std::string& violation() const { return violation_; }            // in words
  [[nodiscard]] std::size_t freeSteps() const { return freeSteps_; }          // model steps after the script
  [[nodiscard]] const std::vector<std::size_t>& loopClosedAt() const { return loopClosedAt_; }  // 1-based steps
  [[nodiscard]] bool failed() const { return failed_; }  // the team left the trace (why())

 private:
  bool fail(std::string why);
  [[nodiscard]] std::size_t traceStep(std::size_t k) const;  // script step -> the trace's step

  ConformanceMonitor conformance_;
  const Stepper& stepper_;
  const ReplayedTrace& trace_;
  std::vector<runtime::Id> script_;
  std::optional<std::size_t> invariant_;
  std::size_t taken_ = 0, freeSteps_ = 0;
  std::optional<std::size_t> violatedAt_;
  std::string violation_, why_;
  std::vector<std::size_t> loopClosedAt_;
  bool failed_ = false;
};

}  // namespace semo::checker
