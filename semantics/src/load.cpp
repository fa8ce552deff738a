#include "semo/semantics/load.hpp"

#include "semo/frontend/parser.hpp"
#include "semo/semantics/ir_text.hpp"
#include "semo/semantics/elaborate.hpp"

namespace semo {

std::optional<model::MissionModel> loadMission(const MissionInputs& inputs, SourceManager& sources, DiagnosticEngine& diags) {
  std::string why;
  FileId missionFile = sources.load(inputs.mission, why);
  if (missionFile == kNoFile) diags.error({}, why);
  FileId strategyFile = sources.load(inputs.strategy, why);
  if (strategyFile == kNoFile) diags.error({}, why);
  if (diags.hasErrors()) return std::nullopt;
  // An IR model given where a mission is expected: said at once, not as a page of syntax errors.
  if (const std::string& text = sources.text(missionFile); ir::looksLikeIr(text)) {
    // The caret under `semo-ir`, past the comments before it.
    std::uint32_t line = 1, column = 1;
    for (std::size_t at = text.find("semo-ir"), i = 0; i < at && at != std::string::npos; ++i) {
      if (text[i] == '\n') ++line, column = 1;
      else ++column;
    }
    diags.error({{missionFile, line, column}, 7}, "this is an IR model, not a mission: `check`, `analyze`, `export`, `show` and `parse` read IR "
                                          "files; this command needs a mission (.semo) and its strategy");
    return std::nullopt;
  }

  ast::Mission mission = parseMission(sources, missionFile, diags);
  strategy::Strategy strategy = strategy::readStrategy(sources, strategyFile, diags);
  RobotCatalog catalog = buildCatalog(strategy, inputs.robotsDir, sources, diags);
  if (diags.hasErrors()) return std::nullopt;
  model::MissionModel model = elaborate(mission, std::move(strategy), std::move(catalog), diags);
  if (diags.hasErrors()) return std::nullopt;
  return model;
}

}  // namespace semo
