// Inputs shared by the commands: a mission's strategy and world, durations.
#include <charconv>
#include <filesystem>

#include "commands.hpp"
#include "semo/runtime/world.hpp"

namespace semo::cli {

std::optional<double> parseDuration(std::string_view text) {
  double value = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
  if (r.ec != std::errc() || !(value >= 0)) return std::nullopt;
  const std::string_view unit = text.substr(static_cast<std::size_t>(r.ptr - text.data()));
  if (unit.empty() || unit == "s") return value;
  if (unit == "ms") return value / 1000.0;
  if (unit == "min") return value * 60.0;
  return std::nullopt;
}

std::vector<std::string> teamSourceProblems(const model::MissionModel& mission, const runtime::World& world) {
  std::vector<std::string> problems;
  for (const strategy::Value& v : mission.strategy.values) {
    if (!v.teamSource) continue;
    const std::string name = v.team + "." + v.var;
    const runtime::ValueSource* src = world.value(name);
    if (src == nullptr) continue;
    if (src->kind == runtime::ValueSource::Kind::Regions || src->kind == runtime::ValueSource::Kind::Sensor) {
      problems.push_back(name + " is one source for the whole team (strategy: source=\"team\"), but the world gives it " +
                         (src->kind == runtime::ValueSource::Kind::Regions ? "by region" : "by a sensor") +
                         ", so robots in different places read it differently; give it as \"constant\" or a \"schedule\" (runtime/WORLD.md)");
    }
  }
  return problems;
}

std::string defaultWorldPath(const std::string& mission) {
  const std::filesystem::path m(mission);
  return (m.parent_path() / (m.stem().string() + ".world.json")).string();
}

std::string strategyExample(const std::string& mission) {
  const std::filesystem::path next = std::filesystem::path(mission).parent_path() / "strategy.xml";
  std::error_code ec;
  if (std::filesystem::is_regular_file(next, ec)) return "--strategy " + next.string() + " (the strategy next to the mission)";
  return "--strategy FILE.xml (specs/strategy.md)";
}

}  // namespace semo::cli
