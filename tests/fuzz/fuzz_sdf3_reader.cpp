// Fuzzes the SDF3 graph reader and, on every graph it accepts, the consistency analysis and one
// iteration (bounded: graphs whose iteration has more than a million firings are not run).
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <string>

#include "semo/sdf/consistency.hpp"
#include "semo/sdf/sdf3_xml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  semo::SourceManager sources;
  semo::DiagnosticEngine diags(sources);
  semo::FileId file = sources.add("fuzz.xml", std::string(reinterpret_cast<const char*>(data), size));
  std::optional<semo::sdf::Graph> g = semo::sdf::readSdf3(sources, file, diags);
  for (const semo::Diagnostic& d : diags.diagnostics()) (void)diags.format(d);
  if (!g) return 0;
  semo::sdf::RepetitionVector q = semo::sdf::repetitionVector(*g);
  if (!q.consistent()) return 0;
  long double firings = std::accumulate(q.firings.begin(), q.firings.end(), 0.0L);
  if (firings <= 1e6L) (void)semo::sdf::runIteration(*g, q.firings);
  return 0;
}
