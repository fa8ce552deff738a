// Fuzzes the world file reader: any bytes give either a world or positioned errors, never both, and
// every error formats. On every world it accepts, the shapes' inside and distance tests run on a few
// points, since the simulator calls them on whatever the file described.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "semo/runtime/world.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<semo::runtime::WorldError> errors;
  std::optional<semo::runtime::World> world =
      semo::runtime::parseWorld(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json", errors);
  for (const semo::runtime::WorldError& e : errors) (void)semo::runtime::formatWorldError(e);
  if (world.has_value() == !errors.empty()) __builtin_trap();
  if (!world) return 0;
  const semo::runtime::Vec2 probes[] = {{0, 0}, {1, 1}, {-3.5, 2}, {1e6, -1e6}};
  for (const semo::runtime::Obstacle& o : world->obstacles) {
    for (semo::runtime::Vec2 p : probes) (void)o.shape.contains(p), (void)o.shape.distance(p);
  }
  for (const semo::runtime::ValueSource& v : world->values) {
    for (const auto& r : v.regions) {
      for (semo::runtime::Vec2 p : probes) (void)r.shape.contains(p);
    }
  }
  return 0;
}
