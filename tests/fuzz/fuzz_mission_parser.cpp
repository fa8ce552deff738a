// Fuzzes the mission lexer, parser and elaboration. Elaboration runs against the scouting example's
// strategy and robots (read once), whenever the input parses, so that name resolution is fuzzed too.
#include <cstddef>
#include <cstdint>
#include <string>

#include "semo/frontend/parser.hpp"
#include "semo/frontend/robot_catalog.hpp"
#include "semo/semantics/elaborate.hpp"

namespace {

struct Fixture {
  semo::SourceManager sources;
  semo::DiagnosticEngine diags{sources};
  semo::strategy::Strategy strategy;
  semo::RobotCatalog catalog;
  Fixture() {
    std::string why;
    semo::FileId file = sources.load(SEMO_SOURCE_DIR "/specs/examples/scouting/strategy.xml", why);
    strategy = semo::strategy::readStrategy(sources, file, diags);
    catalog = semo::buildCatalog(strategy, std::nullopt, sources, diags);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Fixture fixture;
  semo::SourceManager sources;
  semo::DiagnosticEngine diags(sources);
  semo::FileId file = sources.add("fuzz.semo", std::string(reinterpret_cast<const char*>(data), size));
  semo::ast::Mission mission = semo::parseMission(sources, file, diags);
  for (const semo::Diagnostic& d : diags.diagnostics()) (void)diags.format(d);  // the printer must cope too
  if (!diags.hasErrors()) {
    semo::model::MissionModel model = semo::elaborate(mission, fixture.strategy, fixture.catalog, diags);
    for (const semo::Diagnostic& d : diags.diagnostics()) (void)diags.format(d);
  }
  return 0;
}
