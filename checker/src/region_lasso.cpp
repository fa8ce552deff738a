// A lasso inside a region of the model's states (region_lasso.hpp).
#include "region_lasso.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "fair_cycle_search.hpp"
#include "liveness_product.hpp"
#include "semo/checker/buchi.hpp"
#include "semo/checker/fairness.hpp"
#include "semo/checker/lasso_check.hpp"

namespace semo::checker::detail {

namespace {

// The product's fair accepting cycle and the lasso to it, once explored (cut short or not).
void findLasso(const CompiledModel& cm, const ir::Property& property, const Buchi& ba, Product& product, RegionSearch& out) {
  out.states = product.size();
  product.closeFrontier();
  FairCycleSearch search(cm, ba, product, property.settled);
  std::vector<std::uint32_t> cycle = search.find();
  if (cycle.empty()) {
    out.why = "no fair cycle in the " + std::to_string(out.states) + " states explored";
    return;
  }
  const std::uint32_t entry = *std::min_element(cycle.begin(), cycle.end());
  out.lasso = lasso(cm, product, entry, fairLoop(ba, product, search, cycle, entry));
}

std::optional<Buchi> negation(const ir::Property& property, RegionSearch& out) {
  try {
    return buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, property.formula));
  } catch (const std::length_error& e) {
    out.why = e.what();
    return std::nullopt;
  }
}

// Product states one world of the round-robin hunt may take, and worlds one stage may try.
constexpr std::uint64_t kStatesPerWorld = 200'000;
constexpr std::size_t kWorldsPerStage = 4096;

// Calls visit(world) for the worlds of the hunt, each deciding every sensed condition one way for
// the whole run: the quiet one (every condition failing: no danger, the operator away, arrived),
// then each where one condition holds, then each where two do; until visit returns false. Made one
// at a time: a swarm senses hundreds of conditions.
template <typename Visit>
void forEachWorld(std::size_t points, Visit visit) {
  std::vector<std::int8_t> world(points, 0);
  if (!visit(world)) return;
  for (std::size_t a = 0; a < points; ++a) {
    world[a] = 1;
    const bool more = visit(world);
    world[a] = 0;
    if (!more) return;
  }
  for (std::size_t a = 0; a < points; ++a) {
    for (std::size_t b = a + 1; b < points; ++b) {
      world[a] = world[b] = 1;
      const bool more = visit(world);
      world[a] = world[b] = 0;
      if (!more) return;
    }
  }
}

SearchLimits within(std::uint64_t maxStates) {
  SearchLimits limits;
  limits.maxStates = maxStates;
  limits.symmetry = false;
  return limits;
}

}  // namespace

RegionSearch lassoUnderRoundRobin(const CompiledModel& cm, const ir::Property& property, std::uint64_t maxStates) {
  RegionSearch out;
  std::optional<Buchi> ba = negation(property, out);
  if (!ba) return out;
  const ir::Model& model = cm.model();
  const Fairness fairness = Fairness::of(model);
  const Sensing sensing = Sensing::in(model);
  // Without crashes and losses first, then with losses, then with crashes too: most violations
  // need few faults. Each stage gets an equal share of what the stages before it left.
  auto has = [&](ir::RuleKind kind) {
    return std::any_of(model.rules.begin(), model.rules.end(), [&](const ir::Rule& r) { return r.kind == kind; });
  };
  struct Stage {
    bool losses, crashes;
  };
  std::vector<Stage> stages{{false, false}};
  if (has(ir::RuleKind::Loss)) stages.push_back({true, false});
  if (has(ir::RuleKind::Crash)) stages.push_back({true, true});
  std::uint64_t left = maxStates;
  std::size_t tried = 0;
  for (std::size_t k = 0; k < stages.size() && left > 0; ++k) {
    std::vector<char> barred(model.rules.size(), 0);
    for (std::size_t r = 0; r < barred.size(); ++r) {
      const ir::RuleKind kind = model.rules[r].kind;
      barred[r] = (kind == ir::RuleKind::Crash && !stages[k].crashes) || (kind == ir::RuleKind::Loss && !stages[k].losses) ? 1 : 0;
    }
    const std::uint64_t stageEnd = left - left / (stages.size() - k);  // what this stage leaves to the rest
    std::size_t visited = 0;
    forEachWorld(sensing.points, [&](const std::vector<std::int8_t>& world) {
      if (left <= stageEnd || ++visited > kWorldsPerStage) return false;
      Product product(cm, *ba, nullptr);
      product.roundRobin(&fairness);
      product.bar(barred);
      product.senseOnly(&sensing, world);
      std::string why;
      RegionSearch stage;
      const std::uint64_t budget = std::min(left - stageEnd, kStatesPerWorld);
      if (!product.explore(within(budget), Clock::now(), 0, why) && why.rfind("--max-states", 0) != 0) {
        left -= std::min<std::uint64_t>(left, product.size() + 1);  // every world costs something
        return true;
      }
      findLasso(cm, property, *ba, product, stage);
      ++tried;
      out.states += stage.states;
      left -= std::min(left, stage.states);
      if (!stage.lasso) return true;
      stage.lasso->property = property.name;
      stage.lasso->kind = "lasso";
      if (!checkLasso(model, *stage.lasso, property).counterexample()) return true;
      out.lasso = std::move(stage.lasso);
      return false;
    });
    if (out.lasso) return out;
  }
  out.why = "no fair violation in " + std::to_string(tried) + " worlds under a round-robin scheduler (" +
            std::to_string(out.states) + " product states)";
  return out;
}

RegionSearch lassoInRegion(const CompiledModel& cm, const ir::Property& property, const std::vector<Value>& start,
                           const std::function<bool(const Value*)>& inRegion, std::uint64_t maxStates) {
  RegionSearch out;
  std::optional<Buchi> ba = negation(property, out);
  if (!ba) return out;
  // The automaton starts afresh at `start`: a run from there that satisfies the negation is the
  // end of a run from the initial state that does for the built-in properties (each an `always`);
  // for any other, checkLasso decides on the whole lasso.
  Product product(cm, *ba, nullptr);
  product.startFrom(start);
  product.expandOnly(inRegion);
  std::string why;
  if (!product.explore(within(maxStates), Clock::now(), 0, why) && why.rfind("--max-states", 0) != 0) {
    out.why = why;
    return out;
  }
  findLasso(cm, property, *ba, product, out);
  return out;
}

}  // namespace semo::checker::detail
