// Names of the simulated trace's event kinds, as the JSON form and the picture write them.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "semo/runtime/sim_trace.hpp"

namespace semo::runtime {
namespace {

TEST(SimTraceKinds, EveryKindHasItsOwnName) {
  std::set<std::string> names;
  for (int k = 0; k <= static_cast<int>(TraceEvent::Kind::Violation); ++k) {
    names.insert(eventKindName(static_cast<TraceEvent::Kind>(k)));
  }
  EXPECT_EQ(names.size(), 10u);
  EXPECT_EQ(names.count("?"), 0u);
  EXPECT_STREQ(eventKindName(TraceEvent::Kind::Drop), "drop");
}

}  // namespace
}  // namespace semo::runtime
