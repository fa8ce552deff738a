#include "semo/semantics/robot_program.hpp"

#include <algorithm>

namespace semo::lowering {

namespace {

class ProgramBuilder {
 public:
  ProgramBuilder(const model::MissionModel& m, PlanProgram& p) : m_(m), p_(p) {}

  std::size_t service(Index s) {
    owner_ = s;
    std::size_t entry = serviceBody(s, 0);
    p_.code[entry].controlPoint = true;
    return entry;
  }

 private:
  std::size_t add(Instr in) {
    in.service = owner_;
    p_.code.push_back(std::move(in));
    return p_.code.size() - 1;
  }

  // Where a periodic loop's body starts, so that the runtime knows when an iteration begins (an empty
  // body loops on its back edge alone and has no head).
  void markLoopHead(std::size_t head, std::size_t back) {
    if (head != back) p_.code[head].loopBack = back;
  }

  std::size_t serviceBody(Index s, std::size_t cont) {
    const model::CompositeService& sv = m_.services[s];
    if (!sv.repeat) return block(sv.body, cont);
    if (sv.repeat->isPeriod) {
      std::size_t back = add({Instr::Kind::Jump, nullptr, nullptr, 0, 0, 0, model::kNone, {}, true, "repeats " + sv.name, 0});
      std::size_t entry = block(sv.body, back);
      p_.code[back].next = entry;
      markLoopHead(entry, back);
      return entry;
    }
    std::size_t again = add({Instr::Kind::RepeatBranch, nullptr, sv.repeat->cond.get(), cont, 0, 0, model::kNone, {}, false,
                             "repeats " + sv.name, 0});
    std::size_t entry = block(sv.body, again);
    p_.code[again].alt = entry;
    return entry;
  }

  // Statements after a `loop` repeat for ever; the ones before it run once.
  std::size_t block(const std::vector<model::Stmt>& body, std::size_t cont) {
    auto loop = std::find_if(body.begin(), body.end(), [](const model::Stmt& s) { return s.kind == model::Stmt::Kind::Loop; });
    if (loop == body.end()) return sequence(body.begin(), body.end(), cont);
    std::size_t back = add({Instr::Kind::Jump, &*loop, nullptr, 0, 0, 0, model::kNone, {}, true, "loops", 0});
    std::size_t head = sequence(loop + 1, body.end(), back);
    p_.code[back].next = head;
    markLoopHead(head, back);
    return sequence(body.begin(), loop, head);
  }

  std::size_t sequence(std::vector<model::Stmt>::const_iterator begin, std::vector<model::Stmt>::const_iterator end,
                       std::size_t cont) {
    for (auto it = end; it != begin;) cont = statement(*--it, cont);
    return cont;
  }

  std::size_t statement(const model::Stmt& s, std::size_t cont) {
    using K = model::Stmt::Kind;
    Instr in;
    in.stmt = &s;
    in.next = cont;
    switch (s.kind) {
      case K::CallPrimitive:
        in.label = "calls " + s.service;
        return add(std::move(in));
      case K::CallGroupService:
        in.kind = Instr::Kind::GroupService;
        in.label = "works in " + s.service;
        in.controlPoint = true;
        return add(std::move(in));
      case K::Wait:
        in.label = "waits";
        return add(std::move(in));
      case K::Subscribe:
        in.label = "subscribes";
        return add(std::move(in));
      case K::Loop:
        return cont;  // handled by block()
      case K::CallComposite:
        return serviceBody(s.composite, cont);
      case K::Throw:
        in.kind = Instr::Kind::Throw;
        return add(std::move(in));
      case K::Publish:
        in.kind = Instr::Kind::Publish;
        return add(std::move(in));
      case K::Send:
        in.kind = Instr::Kind::Send;
        return add(std::move(in));
      case K::Receive:
        in.kind = Instr::Kind::Receive;
        in.controlPoint = true;  // it may block
        return add(std::move(in));
      case K::If: {
        std::size_t thenEntry = block(s.thenBody, cont);
        std::size_t elseEntry = s.elseBody.empty() ? cont : block(s.elseBody, cont);
        in.kind = Instr::Kind::Branch;
        in.cond = s.cond.get();
        in.next = thenEntry;
        in.alt = elseEntry;
        return add(std::move(in));
      }
      case K::Groups: {
        const model::GroupBlock& b = m_.groupBlocks[s.groupBlock];
        std::size_t first = p_.code.size();
        Instr exit;
        exit.kind = Instr::Kind::BlockExit;
        exit.stmt = &s;
        exit.next = cont;
        exit.block = s.groupBlock;
        exit.controlPoint = true;
        exit.label = "waits for the other groups to finish";
        std::size_t exitAt = add(std::move(exit));
        std::vector<std::size_t> arms, armFirst;
        for (const model::GroupArm& arm : b.arms) {
          armFirst.push_back(p_.code.size());
          std::size_t entry = block(arm.body, exitAt);
          p_.code[entry].controlPoint = true;
          arms.push_back(entry);
        }
        in.kind = Instr::Kind::Groups;
        in.block = s.groupBlock;
        in.arms = std::move(arms);
        in.controlPoint = true;
        in.label = b.isLeaderBlock ? "forms the leader group" : "forms the groups";
        std::size_t at = add(std::move(in));
        p_.blocks.push_back({s.groupBlock, first, at, exitAt, std::move(armFirst)});
        return at;
      }
    }
    return cont;
  }

  const model::MissionModel& m_;
  PlanProgram& p_;
  Index owner_ = model::kNone;
};

}  // namespace

PlanProgram buildProgram(const model::MissionModel& m, Index team, const std::string& plan) {
  PlanProgram p;
  p.team = team;
  p.plan = plan;
  p.entryOf.assign(m.services.size(), 0);
  Instr done;
  done.kind = Instr::Kind::Done;
  done.controlPoint = true;
  done.label = "done";
  p.code.push_back(done);
  ProgramBuilder builder(m, p);
  for (Index md : m.teams[team].modes) {
    for (const model::PlanSetting& s : m.modes[md].settings) {
      if (m.teams[team].plans[s.plan] != plan || p.entryOf[s.service] != 0) continue;
      p.entryOf[s.service] = builder.service(s.service);
    }
  }
  // Whatever follows a visible effect is where the robot rests; so is the start of a `loop`.
  for (Instr& in : p.code) {
    if (in.kind == Instr::Kind::Throw || in.kind == Instr::Kind::Publish || in.kind == Instr::Kind::Send ||
        in.kind == Instr::Kind::Receive) {
      p.code[in.next].controlPoint = true;
    }
  }
  return p;
}

}  // namespace semo::lowering
