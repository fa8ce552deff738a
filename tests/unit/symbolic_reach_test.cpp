// The reachable states the symbolic search starts from (SymbolicProduct::reachableAnyAutomaton:
// the model's, with every automaton state its labels allow): on random models, as many model
// states as the explicit search reaches, every reachable product state among them, the set closed
// under the product's steps, and larger than the product's reachable states on some models.
#include <gtest/gtest.h>

#include "../../checker/src/symbolic_product.hpp"
#include "ir_support.hpp"
#include "random_model.hpp"
#include "semo/checker/explicit_search.hpp"

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

}  // namespace
}  // namespace semo::checker
