// Fuzzes the IR text reader; whatever parses is written back, read again, and searched briefly, so
// that the writer, the compiled evaluator, the explicit search (with symmetry) and the liveness
// engine see arbitrary models too.
#include <cstddef>
#include <cstdint>
#include <string>

#include "semo/checker/explicit_search.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/semantics/ir_text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  semo::SourceManager sources;
  semo::DiagnosticEngine diags(sources);
  semo::FileId file = sources.add("fuzz.ir", std::string(reinterpret_cast<const char*>(data), size));
  std::optional<semo::ir::Model> model = semo::ir::parseText(sources, file, diags);
  for (const semo::Diagnostic& d : diags.diagnostics()) (void)diags.format(d);
  if (!model) return 0;
  std::string text = semo::ir::toText(*model);
  semo::FileId again = sources.add("again.ir", text);
  if (!semo::ir::parseText(sources, again, diags)) __builtin_trap();  // what semo writes, semo must read
  semo::checker::SearchLimits limits;
  limits.maxStates = 2000;
  (void)semo::checker::checkSafety(*model, limits);
  (void)semo::checker::checkLiveness(*model, limits);
  return 0;
}
