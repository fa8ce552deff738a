// `world MISSION --strategy S [--layout ring|grid] [-o FILE]`: a starting world file for the
// mission (runtime/WORLD.md), for the user to edit: the robots laid out by their footprints, a place
// per place the mission names, a site per fact of its group services' knowledge, a constant per
// sensed value it reads. The layout is the runtime's (runtime::writeStartingWorld); this command
// builds the tables it works from, as `simulate` does, and reads what it wrote back through the
// world reader and the simulator's check before giving it out, so that a world it writes is one
// `simulate` takes.
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "semo/codegen/project.hpp"
#include "semo/runtime/simulator.hpp"
#include "semo/runtime/world.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::cli {

int runWorld(const WorldOptions& options) {
  runtime::StartingWorldOptions world;
  if (options.layout == "grid") {
    world.layout = runtime::StartingWorldOptions::Layout::Grid;
  } else if (options.layout != "ring") {
    std::cerr << errorPrefix() << "--layout '" << options.layout << "': expected ring or grid\n";
    return kBadInput;
  }
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::optional<model::MissionModel> mission = loadMission({options.mission, options.strategy, options.robotsDir}, sources, diags);
  std::optional<Translation> translation;
  if (mission) translation = translateMission(*mission, TranslationOptions{}, sources, diags);
  diags.sortByPosition();
  diags.print(std::cerr);
  if (!translation) return kBadInput;
  if (options.output) {
    std::vector<std::string> inputs = filesRead(sources);
    inputs.insert(inputs.end(), {options.mission, options.strategy, options.robotsDir.value_or("")});
    if (!outputsSpareInputs({{"--output", *options.output}}, inputs)) return kBadInput;
  }

  const runtime::MissionTables tables = codegen::project(*mission, *translation, sources);
  world.mission = std::filesystem::path(options.mission).filename().string();  // where it was read from is no part of the world
  for (const strategy::Value& v : mission->strategy.values) {
    const std::string name = v.team + "." + v.var;
    if (v.domain.kind == strategy::Domain::Kind::Range) {
      world.ranges[name] = {static_cast<double>(v.domain.min), static_cast<double>(v.domain.max)};
    }
    if (v.teamSource) world.teamSources.insert(name);
  }
  std::vector<runtime::StartingWorldProblem> problems;
  const std::string text = runtime::writeStartingWorld(tables, world, problems);
  for (const runtime::StartingWorldProblem& p : problems) {
    std::cerr << (p.origin.empty() ? errorPrefix() : p.origin + ": error: ") << p.message << "\n";
  }
  if (!problems.empty()) return kBadInput;

  // What `simulate` would say of it: nothing, or the writer has a bug, and no file is written.
  const std::string shownAs = options.output.value_or("<stdout>");
  std::vector<runtime::WorldError> errors;
  std::optional<runtime::World> written = runtime::parseWorld(text, shownAs, errors);
  std::vector<std::string> refused;
  for (const runtime::WorldError& e : errors) refused.push_back(runtime::formatWorldError(e));
  if (written) {
    refused = runtime::checkWorld(tables, *written);
    for (std::string& p : teamSourceProblems(*mission, *written)) refused.push_back(std::move(p));
  }
  if (!refused.empty()) {
    for (const std::string& r : refused) {
      std::cerr << errorPrefix() << "the world written for the mission would be refused by simulate (a bug of semo): " << r << "\n";
    }
    return kBadInput;
  }

  if (!options.output) {
    std::cout << text;
  } else if (!writeAtomically(*options.output, text)) {
    std::cerr << errorPrefix() << "cannot write '" << *options.output << "'\n";
    return kBadInput;
  }
  return kOk;
}

}  // namespace semo::cli
