// Fuzzes the strategy XML reader (and tinyxml2 underneath it) and the diagnostic printer.
#include <cstddef>
#include <cstdint>
#include <string>

#include "semo/frontend/strategy.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  semo::SourceManager sources;
  semo::DiagnosticEngine diags(sources);
  semo::FileId file = sources.add("fuzz.xml", std::string(reinterpret_cast<const char*>(data), size));
  semo::strategy::Strategy strategy = semo::strategy::readStrategy(sources, file, diags);
  for (const semo::Diagnostic& d : diags.diagnostics()) (void)diags.format(d);
  return 0;
}
