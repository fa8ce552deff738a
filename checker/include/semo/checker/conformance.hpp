#pragma once
// Conformance, checked while the mission runs (specs/runtime.md, "Conformance"): the simulator
// reports every step of the team with the IR rules it claims to be and the team's state before and
// after, read through the abstraction function. The monitor replays the claim on the IR: each rule
// must be enabled and the rules together must lead to exactly the state the team is in; a step that
// claims no rule must change nothing the model sees. It also checks the model's invariants in every
// state the team reaches. Any mismatch stops the run with both states printed.
#include <string>

#include "semo/checker/stepper.hpp"
#include "semo/runtime/simulator.hpp"

namespace semo::checker {

class ConformanceMonitor final : public runtime::StepObserver {
 public:
  // `model` must be the IR the tables were projected from. `checkInvariants`: also stop at the
  // first state that violates one of the model's invariants (a replay checks its one property itself).
  ConformanceMonitor(const ir::Model& model, const runtime::MissionTables& tables, bool checkInvariants = true);
  bool onStep(const runtime::StepReport& step) override;
  [[nodiscard]] std::string why() const override { return why_; }
  [[nodiscard]] const Stepper& stepper() const { return stepper_; }

 private:
  Stepper stepper_;
  const runtime::MissionTables& tables_;
  Stepper::State current_;
  std::string why_;
  bool checkInvariants_ = true;
  bool mismatch(const runtime::StepReport& step, const std::string& what, const Stepper::State& expected);
};

}  // namespace semo::checker
