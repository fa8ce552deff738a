#pragma once
// Robot types from URDF (through urdfdom): capabilities derived from the description, plus the
// strategy's explicit additions; wheel geometry kept for the simulator.
#include <optional>
#include <string>
#include <vector>

#include "semo/frontend/strategy.hpp"

namespace semo {

struct Capability {
  std::string name;
  std::string source;  // where it came from, e.g. "link 'base_scan'" or "strategy"
};

struct WheelGeometry {
  int wheelCount = 0;
  double radius = 0;      // metres
  double separation = 0;  // metres, between the outermost wheel joints
  double maxWheelSpeed = 0;  // rad/s: the smallest velocity limit of the wheel joints (0: none stated)
};

struct RobotType {
  std::string name;
  std::string urdfPath;
  std::vector<Capability> capabilities;
  std::optional<WheelGeometry> wheels;
  double massKg = 0;
  std::vector<std::string> links;
  SourceRange declaredAt;  // the strategy's <robot> element, if any
  [[nodiscard]] bool has(const std::string& capability) const;
};

class RobotCatalog {
 public:
  void add(RobotType type) { types_.push_back(std::move(type)); }
  [[nodiscard]] const RobotType* find(const std::string& name) const;
  [[nodiscard]] const std::vector<RobotType>& types() const { return types_; }
  [[nodiscard]] std::vector<std::string> typeNames() const;
  [[nodiscard]] std::vector<std::string> capabilityNames() const;  // sorted, unique

 private:
  std::vector<RobotType> types_;
};

// Reads one URDF file; reports errors (positioned where possible) and returns nullopt on failure.
// `requestedAt` is where the file was named (for "cannot open" errors).
std::optional<RobotType> loadRobotType(SourceManager& sources, const std::string& path, SourceRange requestedAt,
                                       DiagnosticEngine& diags);

// Builds the catalog from the strategy's <robot> entries; URDF paths are relative to `robotsDir` when
// given, else to the strategy's folder. With no <robot> entry, every *.urdf in `robotsDir` is loaded.
RobotCatalog buildCatalog(const strategy::Strategy& strategy, const std::optional<std::string>& robotsDir,
                          SourceManager& sources, DiagnosticEngine& diags);

}  // namespace semo
