// Inputs shared by the commands that run a mission (simulate, replay).
#include <charconv>
#include <filesystem>

#include "commands.hpp"

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

std::string defaultWorldPath(const std::string& mission) {
  const std::filesystem::path m(mission);
  return (m.parent_path() / (m.stem().string() + ".world.json")).string();
}

}  // namespace semo::cli
