#pragma once
// Rebuilding a slice's lasso on the whole model (sliced_liveness.cpp): each step of the slice's
// lasso by its own rule, preceded where needed by steps the slice does not see (steps that change
// no kept variable), and the loop taken again and again until the whole model comes back to a
// state it was in at the loop's start; a fair rule the rebuilt loop neglects is taken on the loop
// when it changes nothing the slice sees. Where it fails, refine() names the variables to keep.
// Only sliced_liveness.cpp includes it.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <optional>
#include <queue>
#include <string>
#include <unordered_map>
#include <vector>

#include "region_lasso.hpp"
#include "semo/checker/compiled_model.hpp"
#include "semo/checker/fairness.hpp"
#include "semo/checker/lasso_check.hpp"
#include "semo/checker/slicing.hpp"

namespace semo::checker::detail::rebuild {

constexpr std::size_t kStutterSearch = 4096;  // states a search for a hidden step may visit
constexpr std::size_t kLoopRounds = 64;        // times the loop is taken waiting for the model to repeat
constexpr std::size_t kFairnessRepairs = 32;
constexpr std::size_t kEntrySearch = 200000;  // states a search for a way into the loop may visit
constexpr std::uint64_t kRegionStates = 200'000;  // product states a search of the loop's region may take

using State = std::vector<Value>;

struct StateHash {
  std::size_t operator()(const State& s) const {
    std::size_t h = 1469598103934665603ull;
    for (Value v : s) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
    return h;
  }
};

struct Move {
  std::uint32_t rule;
  std::uint32_t branch;
  State after;
};

class Concretizer {
 public:
  Concretizer(const CompiledModel& full, const Slice& slice, const Trace& abstractLasso, bool settled)
      : cm_(full), slice_(slice), fairness_(Fairness::of(full.model())), sensing_(Sensing::in(full.model())), settled_(settled),
        allowed_(sensing_.points, -1),
        refine_(full.model().variables.size(), 0), kept_(full.model().variables.size(), 0) {
    for (ir::VarId v : slice.variables) kept_[v] = 1;
    // The slice's states along its lasso, and the rule of each step.
    State a(slice.model.variables.size());
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = slice.model.variables[i].init;
    abstract_.push_back(a);
    for (const Step& s : abstractLasso.steps) {
      for (const Change& c : s.changes) a[c.var] = c.after;
      abstract_.push_back(a);
      ruleAt_.push_back(slice.rules[s.rule]);
    }
    loopStart_ = std::min(abstractLasso.loopStart, ruleAt_.size());
  }

  // A lasso of the whole model that checkLasso accepts, or false with refine() marked (or not,
  // when nothing the slice left out is to blame) and why() said.
  bool run(Trace& out, const ir::Property& property) {
    if (attempt(out, property)) return true;
    // Nothing on the loop to blame: then what kept the slice's own way into the loop from being taken.
    if (std::none_of(refine_.begin(), refine_.end(), [](char c) { return c != 0; })) refine_ = prefixBlame_;
    return false;
  }

  [[nodiscard]] const std::vector<char>& refine() const { return refine_; }
  [[nodiscard]] const std::string& why() const { return why_; }

 private:
  bool attempt(Trace& out, const ir::Property& property) {
    State x = cm_.initialValues();
    initial_ = x;
    std::size_t failedAt = SIZE_MAX;
    for (std::size_t i = 0; i < loopStart_; ++i) {
      if (!follow(x, i)) {
        failedAt = i;
        break;
      }
    }
    if (failedAt != SIZE_MAX) {
      // The slice's way into its loop may not exist, while the loop does: any way into it will do.
      prefixBlame_ = refine_;
      std::fill(refine_.begin(), refine_.end(), 0);
      path_.clear();
      slotAfter_.clear();
      if (!enterLoop(x)) return false;
    }
    extras_.assign(ruleAt_.size() - loopStart_ + 1, {});
    const std::size_t prefixEnd = path_.size();
    const State loopEntry = x;
    entryPath_.assign(path_.begin(), path_.end());
    entry_ = loopEntry;
    for (std::size_t repair = 0; repair <= kFairnessRepairs; ++repair) {
      path_.resize(prefixEnd);
      slotAfter_.resize(prefixEnd);
      x = loopEntry;
      std::size_t loopFrom = 0;
      if (!closeLoop(x, loopFrom)) return false;
      out = toTrace(path_, loopFrom);
      LassoCheck check = checkLasso(cm_.model(), out, property);
      if (!check.valid) {
        why_ = "the rebuilt lasso does not replay: " + check.why;
        return false;
      }
      if (!check.unsettled.empty()) {
        why_ = "the rebuilt loop decides a sensed condition both ways, on a settling world";
        return false;
      }
      if (check.unfairGroups.empty()) {
        if (check.violates) return true;
        why_ = "the rebuilt lasso satisfies the property";
        return false;
      }
      if (!repairFairness(check.unfairGroups, loopFrom)) return false;
    }
    why_ = "the rebuilt loop neglects fair rules after " + std::to_string(kFairnessRepairs) + " repairs";
    return false;
  }

  // Where the slice's loop cannot be followed step by step and the refinement ends: the whole
  // model's states that the slice sees as one of its loop's, searched from the state where the run
  // entered the loop for a fair accepting cycle of their own (region_lasso.hpp).
 public:
  bool searchRegion(Trace& out, const ir::Property& property) {
    if (!entry_) return false;
    std::unordered_map<State, char, StateHash> views;
    for (std::size_t k = loopStart_; k < abstract_.size(); ++k) views.emplace(abstract_[k], 1);
    State view(slice_.variables.size());
    auto inRegion = [&](const Value* v) {
      for (std::size_t i = 0; i < view.size(); ++i) view[i] = v[slice_.variables[i]];
      return views.count(view) != 0;
    };
    if (!inRegion(entry_->data())) return false;
    if (std::getenv("SEMO_DEBUG_SLICING") != nullptr) {
      for (const auto& [v, unused] : views) {
        std::string text;
        for (std::size_t i = 0; i < v.size(); ++i) text += " " + cm_.model().variables[slice_.variables[i]].name + "=" + std::to_string(v[i]);
        std::fprintf(stderr, "[slice]   region view:%s\n", text.c_str());
      }
    }
    RegionSearch found = lassoInRegion(cm_, property, *entry_, inRegion, kRegionStates);
    regionStates_ += found.states;
    if (!found.lasso) {
      why_ += "; " + found.why;
      return false;
    }
    Trace t = toTrace(entryPath_, entryPath_.size() + found.lasso->loopStart);
    for (Step& step : found.lasso->steps) t.steps.push_back(std::move(step));
    LassoCheck check = checkLasso(cm_.model(), t, property);
    if (!check.counterexample()) {
      why_ += "; the region's lasso does not replay: " + (check.valid ? std::string("unfair or not a violation") : check.why);
      return false;
    }
    out = std::move(t);
    return true;
  }
 private:

  [[nodiscard]] bool sees(const State& x, const State& abstract) const {
    for (std::size_t i = 0; i < slice_.variables.size(); ++i) {
      if (x[slice_.variables[i]] != abstract[i]) return false;
    }
    return true;
  }
  [[nodiscard]] bool sameView(const State& x, const State& y) const {
    for (ir::VarId v : slice_.variables) {
      if (x[v] != y[v]) return false;
    }
    return true;
  }
  [[nodiscard]] std::size_t distance(const State& x, const State& abstract) const {
    std::size_t d = 0;
    for (std::size_t i = 0; i < slice_.variables.size(); ++i) d += x[slice_.variables[i]] != abstract[i] ? 1 : 0;
    return d;
  }

  void successors(const State& x, std::vector<Move>& out) {
    out.clear();
    cm_.candidateRules(x.data(), candidates_);
    State y(x.size());
    for (std::uint32_t r : candidates_) {
      const CompiledRule& rule = cm_.rules()[r];
      if (!rule.guard.holds(x.data())) continue;
      for (std::uint32_t b = 0; b < rule.branches.size(); ++b) {
        if (cm_.step(rule.branches[b], x.data(), y.data())) out.push_back({r, b, y});
      }
    }
  }

  // Blames model rule r: the variables the slice left out that its guard reads (it was enabled
  // where the slice thought it could be), or that the new values of kept variables read.
  void blame(std::uint32_t r, bool guard, bool updates) {
    const ir::Rule& rule = cm_.model().rules[r];
    std::vector<char> reads(refine_.size(), 0);
    if (guard) markVariablesRead(rule.guard, reads);
    if (updates) {
      for (const ir::Branch& b : rule.branches) {
        for (const ir::Assignment& a : b.assignments) {
          if (kept_[a.var]) markVariablesRead(a.value, reads);
        }
      }
    }
    for (std::size_t v = 0; v < reads.size(); ++v) {
      if (reads[v] && !kept_[v]) refine_[v] = 1;
    }
  }

  // The variables a rule assigns, when the slice keeps none of them (so that the rule joins it).
  void blameTargets(std::uint32_t r) {
    const ir::Rule& rule = cm_.model().rules[r];
    for (const ir::Branch& b : rule.branches) {
      for (const ir::Assignment& a : b.assignments) {
        if (kept_[a.var]) return;
      }
    }
    for (const ir::Branch& b : rule.branches) {
      for (const ir::Assignment& a : b.assignments) refine_[a.var] = 1;
    }
  }

  // Step i of the slice's lasso, from x: steps the slice does not see first (breadth-first, the
  // fewest), then the step's own rule to a state the slice sees as the lasso's next.
  bool follow(State& x, std::size_t i) {
    const std::uint32_t rule = ruleAt_[i];
    const State& target = abstract_[i + 1];
    std::unordered_map<State, std::pair<std::size_t, Move>, StateHash> parent;  // state -> (index of parent in order, move)
    std::vector<State> order{x};
    parent.emplace(x, std::pair<std::size_t, Move>{SIZE_MAX, {}});
    std::vector<Move> moves;
    bool enabled = false;
    for (std::size_t head = 0; head < order.size() && order.size() <= kStutterSearch; ++head) {
      const State here = order[head];
      successors(here, moves);
      for (const Move& m : moves) {
        if (m.rule != rule) continue;
        enabled = true;
        if (!sees(m.after, target)) continue;
        // Found: the hidden steps to `here`, then the rule.
        std::vector<Move> hidden;
        for (const State* s = &here;;) {
          const auto& [from, move] = parent.at(*s);
          if (from == SIZE_MAX) break;
          hidden.push_back(move);
          s = &order[from];
        }
        std::reverse(hidden.begin(), hidden.end());
        for (Move& h : hidden) push(std::move(h), currentSlot_);
        push(m, currentSlot_ + 1);
        x = m.after;
        return true;
      }
      for (Move& m : moves) {
        if (!sameView(m.after, here) || parent.count(m.after) != 0 || forbidden(m.rule)) continue;
        parent.emplace(m.after, std::pair<std::size_t, Move>{head, m});
        order.push_back(std::move(m.after));
      }
    }
    blame(rule, !enabled, enabled);
    why_ = "step " + std::to_string(i + 1) + " of the slice's lasso ('" + cm_.model().rules[rule].name + "') " +
           (enabled ? "does not lead where the slice says" : "is not enabled") + " on the whole model";
    return false;
  }

  // A way from the initial state to a state the slice sees as one of its loop's: best first, by how
  // many kept variables still differ. The loop is then taken from there (rotated to start there).
  bool enterLoop(State& x) {
    std::unordered_map<State, std::size_t, StateHash> index;
    std::vector<std::pair<State, std::pair<std::size_t, Move>>> nodes;  // state, (parent node, move)
    using Entry = std::pair<std::size_t, std::size_t>;                  // (distance, node), smallest first
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    auto closest = [&](const State& s, std::size_t& at) {
      std::size_t best = SIZE_MAX;
      for (std::size_t j = loopStart_; j < abstract_.size(); ++j) {
        std::size_t d = distance(s, abstract_[j]);
        if (d < best) best = d, at = j;
      }
      return best;
    };
    std::size_t at = 0;
    index.emplace(initial_, 0);
    nodes.push_back({initial_, {SIZE_MAX, {}}});
    open.push({closest(initial_, at), 0});
    std::vector<Move> moves;
    while (!open.empty() && nodes.size() <= kEntrySearch) {
      const auto [d, n] = open.top();
      open.pop();
      if (d == 0) {
        closest(nodes[n].first, at);
        std::vector<Move> way;
        for (std::size_t k = n; nodes[k].second.first != SIZE_MAX; k = nodes[k].second.first) way.push_back(nodes[k].second.second);
        std::reverse(way.begin(), way.end());
        for (Move& m : way) push(std::move(m), 0);
        x = nodes[n].first;
        rotate(at);
        return true;
      }
      const State here = nodes[n].first;
      successors(here, moves);
      for (Move& m : moves) {
        if (index.count(m.after) != 0) continue;
        index.emplace(m.after, nodes.size());
        std::size_t dist = closest(m.after, at);
        nodes.push_back({m.after, {n, m}});
        open.push({dist, nodes.size() - 1});
      }
    }
    return false;
  }

  // The loop, starting at its j-th state; no prefix (the way in is already on the path).
  void rotate(std::size_t j) {
    std::vector<std::uint32_t> rules;
    std::vector<State> states;
    const std::size_t n = ruleAt_.size();
    for (std::size_t k = j; k < n; ++k) rules.push_back(ruleAt_[k]), states.push_back(abstract_[k]);
    for (std::size_t k = loopStart_; k < j; ++k) rules.push_back(ruleAt_[k]), states.push_back(abstract_[k]);
    states.push_back(abstract_[j]);
    ruleAt_ = std::move(rules);
    abstract_ = std::move(states);
    loopStart_ = 0;
  }

  // Takes the slice's loop from x again and again (with the repairs) until the whole model repeats
  // a state at the loop's start; loopFrom is then the path index where the repeated loop begins.
  bool closeLoop(State& x, std::size_t& loopFrom) {
    inLoop_ = true;
    std::fill(allowed_.begin(), allowed_.end(), -1);
    for (std::size_t i = loopStart_; i < ruleAt_.size(); ++i) decide(ruleAt_[i]);
    std::unordered_map<State, std::size_t, StateHash> seen;
    for (std::size_t round = 0; round < kLoopRounds; ++round) {
      auto [it, added] = seen.emplace(x, path_.size());
      if (!added) {
        loopFrom = it->second;
        return true;
      }
      for (std::size_t i = loopStart_; i <= ruleAt_.size(); ++i) {
        currentSlot_ = i - loopStart_;
        for (std::uint32_t r : extras_[i - loopStart_]) takeIfHidden(x, r);
        if (i < ruleAt_.size() && !follow(x, i)) return false;
      }
    }
    why_ = "the whole model does not come back to a state at the loop's start within " + std::to_string(kLoopRounds) + " rounds";
    return false;
  }

  // A step deciding a sensed condition otherwise than the loop does, which the loop of a
  // property on a settling world may not take.
  [[nodiscard]] bool forbidden(std::uint32_t rule) const { return inLoop_ && settled_ && !sensing_.agrees(rule, allowed_); }
  void decide(std::uint32_t rule) {
    for (const Sensing::Decision& d : sensing_.of[rule]) allowed_[d.point] = static_cast<std::int8_t>(d.holds);
  }

  void push(Move m, std::size_t slotAfter) {
    if (inLoop_ && settled_) decide(m.rule);
    path_.push_back(std::move(m));
    slotAfter_.push_back(slotAfter);
  }

  void takeIfHidden(State& x, std::uint32_t r) {
    const CompiledRule& rule = cm_.rules()[r];
    if (!rule.guard.holds(x.data())) return;
    State y(x.size());
    for (std::uint32_t b = 0; b < rule.branches.size(); ++b) {
      if (cm_.step(rule.branches[b], x.data(), y.data()) && sameView(x, y) && !forbidden(r)) {
        push({r, b, y}, currentSlot_);
        x = y;
        return;
      }
    }
  }

  // Each neglected group: one of its rules is taken where the loop first enables it without the
  // slice seeing the step; if none can be, the slice was wrong to neglect the group (it dropped
  // its fairness): its rules are blamed.
  bool repairFairness(const std::vector<std::uint32_t>& unfair, std::size_t loopFrom) {
    bool repaired = false;
    const State start = loopFrom == 0 ? initial_ : path_[loopFrom - 1].after;
    for (std::uint32_t g : unfair) {
      std::optional<std::pair<std::size_t, std::uint32_t>> placed;  // (slot, rule)
      for (std::size_t k = loopFrom; k <= path_.size() && !placed; ++k) {
        const State& here = k == loopFrom ? start : path_[k - 1].after;
        for (std::uint32_t r : fairness_.members[g]) {
          const CompiledRule& rule = cm_.rules()[r];
          if (forbidden(r) || !rule.guard.holds(here.data())) continue;
          State y(here.size());
          for (std::uint32_t b = 0; b < rule.branches.size() && !placed; ++b) {
            if (cm_.step(rule.branches[b], here.data(), y.data()) && sameView(here, y)) {
              placed = std::pair<std::size_t, std::uint32_t>{k == loopFrom ? 0 : slotAfter_[k - 1], r};
            }
          }
          if (placed) break;
        }
      }
      if (placed) {
        std::vector<std::uint32_t>& at = extras_[placed->first];
        if (std::find(at.begin(), at.end(), placed->second) == at.end()) {
          at.push_back(placed->second);
          repaired = true;
          continue;
        }
      }
      // The slice must see the group to be fair to it: every member (a rule is in a slice only
      // when it assigns a kept variable) with its exact guard.
      if (std::getenv("SEMO_DEBUG_SLICING") != nullptr) {
        for (std::uint32_t r : fairness_.members[g]) std::fprintf(stderr, "[slice]   neglected group member %s\n", cm_.model().rules[r].name.c_str());
      }
      for (std::uint32_t r : fairness_.members[g]) {
        blame(r, true, false);
        blameTargets(r);
      }
    }
    if (!repaired) {
      why_ = "the rebuilt loop neglects a fair group that the slice did not see enabled";
      return false;
    }
    return true;
  }

  // The moves from the initial state as a trace, its loop from step loopFrom.
  Trace toTrace(const std::vector<Move>& path, std::size_t loopFrom) const {
    Trace t;
    t.property = slice_.model.properties[0].name;
    t.kind = "lasso";
    t.initial = initial_;
    State before = initial_;
    for (const Move& m : path) {
      Step s{m.rule, m.branch, {}};
      for (ir::VarId v = 0; v < before.size(); ++v) {
        if (before[v] != m.after[v]) s.changes.push_back({v, before[v], m.after[v]});
      }
      t.steps.push_back(std::move(s));
      before = m.after;
    }
    t.loopStart = loopFrom;
    return t;
  }

  std::vector<Move> entryPath_;  // the way into the slice's loop, when one was found
  std::optional<State> entry_;
  std::uint64_t regionStates_ = 0;

 public:
  [[nodiscard]] std::uint64_t regionStates() const { return regionStates_; }

 private:
  const CompiledModel& cm_;
  const Slice& slice_;
  const Fairness fairness_;
  const Sensing sensing_;
  const bool settled_;
  std::vector<std::int8_t> allowed_;  // per sensed condition, how the loop decides it (-1: not yet)
  bool inLoop_ = false;
  std::vector<State> abstract_;       // the slice's states along its lasso
  std::vector<std::uint32_t> ruleAt_;  // the model rule of each of its steps
  std::size_t loopStart_ = 0;
  std::vector<char> refine_, kept_, prefixBlame_;
  std::string why_;
  State initial_;
  std::vector<Move> path_;
  std::vector<std::vector<std::uint32_t>> extras_;  // per slice loop step (and its end): rules taken first
  std::vector<std::size_t> slotAfter_;  // per path step: the loop slot the run is in after it
  std::size_t currentSlot_ = 0;
  std::vector<std::uint32_t> candidates_;
};

}  // namespace semo::checker::detail::rebuild
