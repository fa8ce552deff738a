// Fuzzes the task-graph JSON reader and, on every graph it accepts, the per-scenario consistency
// analysis and one iteration (bounded: iterations of more than a million firings are not run).
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <string>

#include "semo/sdf/consistency.hpp"
#include "semo/sdf/task_graph_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  semo::SourceManager sources;
  semo::DiagnosticEngine diags(sources);
  semo::FileId file = sources.add("fuzz.json", std::string(reinterpret_cast<const char*>(data), size));
  std::optional<semo::sdf::TaskGraph> tg = semo::sdf::readTaskGraphJson(sources, file, diags);
  for (const semo::Diagnostic& d : diags.diagnostics()) (void)diags.format(d);
  if (!tg) return 0;
  (void)semo::sdf::taskGraphToGraphviz(*tg);
  for (const semo::sdf::Scenario& s : tg->scenarios) {
    const semo::sdf::Graph g = semo::sdf::scenarioGraph(*tg, s);
    semo::sdf::RepetitionVector q = semo::sdf::repetitionVector(g);
    if (!q.consistent()) continue;
    long double firings = std::accumulate(q.firings.begin(), q.firings.end(), 0.0L);
    if (firings <= 1e6L) (void)semo::sdf::runIteration(g, q.firings);
  }
  return 0;
}
