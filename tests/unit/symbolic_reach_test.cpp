// The reachable states the symbolic search starts from (SymbolicProduct::reachableAnyAutomaton:
// the model's, with every automaton state its labels allow): on random models, as many model
// states as the explicit search reaches, every reachable product state among them, the set closed
// under the product's steps, and larger than the product's reachable states on some models.
#include <gtest/gtest.h>

#include "../../checker/src/projected_reach.hpp"
#include "../../checker/src/symbolic_product.hpp"
#include "ir_support.hpp"
#include "random_model.hpp"
#include "semo/checker/explicit_search.hpp"
#include "true_invariant.hpp"

namespace semo::checker {
namespace {

using detail::SymbolicProduct;

TEST(SymbolicReach, TheModelsReachableStatesHoldTheProductsAndAreClosed) {
  std::uint32_t compared = 0, larger = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(300); ++seed) {
    const std::string text = test::RandomModel(seed).text();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    const ir::Model m = test::parseIr(text);
    const Fairness fairness = Fairness::of(m);
    SearchLimits everyState;
    everyState.symmetry = false;
    const SearchResult reachable = checkSafety(m, everyState);
    ASSERT_TRUE(reachable.complete);
    for (std::size_t k = 0; k < m.properties.size(); ++k) {
      const Buchi ba = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, m.properties[k].formula));
      detail::packageError = 0;
      bdd_init(1 << 16, 1 << 14);
      bdd_error_hook(detail::recordError);
      {
        SymbolicProduct product(m, ba, fairness, detail::CpuClock::now() + std::chrono::hours(1));
        const bdd any = product.reachableAnyAutomaton();
        const bdd exact = product.reachable();
        // Every reachable product state is in the set; the set's model states are the reachable ones.
        EXPECT_EQ(detail::minus(exact, any), bddfalse);
        if (!reachable.rangeError) {
          EXPECT_EQ(product.modelStates(product.reachableModelStates()), static_cast<double>(reachable.states));
        }
        // Closed: no rule leads out of it.
        EXPECT_EQ(detail::minus(product.successors(any), any), bddfalse);
        larger += product.count(any) > product.count(exact) ? 1 : 0;
        ++compared;
      }
      bdd_done();
      ASSERT_EQ(detail::packageError, 0);
    }
  }
  EXPECT_GT(compared, 100u);
  // The automaton's part is an over-approximation that some models show (else the fallback to
  // the exact set in decideSymbolically would go untested by them).
  EXPECT_GT(larger, 0u);
}

// The superset the search of an exact cone starts from (projected_reach.hpp): on random models it
// holds every reachable state; without invariants it is closed under every rule's steps (each
// part's set holds the projections of every image); it is larger than the reachable states on
// some models (else the fallback to them would go untested); and a true invariant (two values no
// reachable state holds together) keeps every reachable state in it while cutting it on some.
TEST(SymbolicReach, TheProjectedSupersetHoldsEveryReachableState) {
  std::uint32_t compared = 0, larger = 0, cut = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(300); ++seed) {
    const std::string text = test::RandomModel(seed).text();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    const ir::Model m = test::parseIr(text);
    if (m.properties.empty()) continue;
    const std::vector<std::string> invariants = test::trueInvariants(m, 8);
    const Fairness fairness = Fairness::of(m);
    const Buchi ba = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, m.properties[0].formula));
    detail::packageError = 0;
    bdd_init(1 << 16, 1 << 14);
    bdd_error_hook(detail::recordError);
    {
      SymbolicProduct product(m, ba, fairness, detail::CpuClock::now() + std::chrono::hours(1));
      const bdd exact = product.reachableModelStates();
      const bdd over = detail::projectedReachable(product, m);
      EXPECT_EQ(detail::minus(exact, over), bddfalse);
      for (std::uint32_t r = 0; r < m.rules.size(); ++r) EXPECT_EQ(detail::minus(product.image(over, r), over), bddfalse) << m.rules[r].name;
      larger += over != exact ? 1 : 0;
      bool cutByOne = false;
      for (const std::string& invariant : invariants) {
        SCOPED_TRACE(invariant);
        const bdd within = detail::projectedReachable(product, test::parseIr(text + invariant));
        EXPECT_EQ(detail::minus(exact, within), bddfalse);
        cutByOne = cutByOne || within != over;
      }
      cut += cutByOne ? 1 : 0;
      ++compared;
    }
    bdd_done();
    ASSERT_EQ(detail::packageError, 0);
  }
  std::printf("%u models, %u supersets larger, %u cut by an invariant\n", compared, larger, cut);
  EXPECT_GT(compared, static_cast<std::uint32_t>(test::atLeast(200)));
  EXPECT_GT(larger, static_cast<std::uint32_t>(test::atLeast(20)));
  EXPECT_GT(cut, static_cast<std::uint32_t>(test::atLeast(20)));
}

}  // namespace
}  // namespace semo::checker
