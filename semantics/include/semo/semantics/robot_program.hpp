#pragma once
// Services flattened into one instruction graph per (team, plan) (specs/semantics.md, "Services as
// programs"). One lowering for everything downstream: the IR translation walks it to make the
// robots' rules, and the runtime's step tables keep its instruction indices as program counters,
// so a robot's `pc` in the IR and in the running code is the same number.
#include <cstddef>
#include <string>
#include <vector>

#include "semo/semantics/mission_model.hpp"

namespace semo::lowering {

using model::Index;

struct Instr {
  enum class Kind {
    Done,          // index 0: the plan runs nothing (no service, or the service has ended)
    Local,         // a call, wait or subscribe: no effect another robot can see
    Jump,          // the back edge of a loop or periodic repeat
    Branch,        // if: `next` when the condition holds, `alt` otherwise
    RepeatBranch,  // end of a service with repeat(cond): `alt` restarts, `next` ends
    Throw,
    Publish,
    Send,
    Receive,
    Groups,  // a [[ ]] block: arms[k] is the entry of the k-th arm; `next` skips the block
    GroupService,  // a group service: the robot works in it, sharing knowledge, until its goal
    BlockExit,     // the end of a [[ ]] block: waits until no robot is still inside it
  };
  Kind kind = Kind::Local;
  const model::Stmt* stmt = nullptr;
  const model::Cond* cond = nullptr;  // Branch, RepeatBranch
  std::size_t next = 0;
  std::size_t alt = 0;
  Index service = model::kNone;  // the top-level service this code belongs to
  Index block = model::kNone;    // Groups
  std::vector<std::size_t> arms;  // Groups
  bool controlPoint = false;      // a state the robot can rest in between rules
  std::string label;              // what a person reads in a trace
  std::size_t loopBack = 0;       // the first instruction of a periodic loop's body: the loop's back edge (a Jump)
};

struct BlockRange {
  Index block;
  std::size_t first, last;           // instructions [first, last] hold the block; `last` forms it
  std::size_t exit;                  // the BlockExit instruction (== first)
  std::vector<std::size_t> armFirst;  // arm k occupies [armFirst[k], armFirst[k+1]) (the last arm ends before `last`)
  [[nodiscard]] std::size_t armEnd(std::size_t k) const { return k + 1 < armFirst.size() ? armFirst[k + 1] : last; }
};

struct PlanProgram {
  Index team = model::kNone;
  std::string plan;
  std::vector<Instr> code;
  std::vector<std::size_t> entryOf;  // per service index; 0 if not on this plan
  std::vector<BlockRange> blocks;
};

// Builds the program of one plan of one team from every service a mode sets on that plan.
PlanProgram buildProgram(const model::MissionModel& m, Index team, const std::string& plan);

}  // namespace semo::lowering
