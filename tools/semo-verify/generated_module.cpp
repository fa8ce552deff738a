// `simulate --generated`: the simulator's module of a generated project (mission/simulation.cpp of
// `emit`), loaded with dlopen, its tables checked against the projection before anything runs.
#include <dlfcn.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/codegen/cpp_tables.hpp"

namespace semo::cli {

std::optional<runtime::MissionTables> loadGeneratedTables(const std::string& path, std::string& error) {
  std::filesystem::path module(path);
  if (std::filesystem::is_directory(module)) module /= "mission_simulation.so";
  // RTLD_LOCAL: its symbols stay its own; RTLD_NOW: a module missing a symbol fails here, not later.
  void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    error = "cannot load '" + module.string() + "': " + dlerror() + " (build the generated project first: cmake --build DIR/build)";
    return std::nullopt;
  }
  using Mission = const runtime::MissionTables* (*)();
  using Layout = unsigned long long (*)();
  auto mission = reinterpret_cast<Mission>(dlsym(handle, "semo_generated_mission"));
  auto layout = reinterpret_cast<Layout>(dlsym(handle, "semo_generated_layout"));
  std::optional<runtime::MissionTables> out;
  if (mission == nullptr || layout == nullptr) {
    error = "'" + module.string() + "' is not the simulation module of a generated project (no semo_generated_mission)";
  } else if (layout() != runtime::kTablesLayout) {
    error = "'" + module.string() + "' was built against another semo_runtime (tables layout " + std::to_string(layout()) + ", this one " +
            std::to_string(runtime::kTablesLayout) + "): emit and build it again";
  } else {
    out = *mission();  // a copy of our own: the module is closed below
  }
  dlclose(handle);
  return out;
}

std::optional<std::string> generatedCertificate(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path given(path);
  const fs::path folder = fs::is_directory(given, ec) ? given : given.parent_path();
  for (const fs::path& candidate : {folder / "certificate.json", folder.parent_path() / "certificate.json"}) {
    if (fs::is_regular_file(candidate, ec)) return candidate.string();
  }
  return std::nullopt;
}

bool modelOptionsOf(const std::string& certificate, TranslationOptions& out, std::string& error) {
  std::ifstream in(certificate);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  const nlohmann::json* options = j.is_object() && j.contains("modelOptions") ? &j["modelOptions"] : nullptr;
  if (options == nullptr || !options->is_object()) {
    error = "'" + certificate + "' is not a certificate semo can read (no \"modelOptions\")";
    return false;
  }
  try {
    if (options->contains("crash")) out.crashOverride = options->at("crash").get<int>();
    if (options->contains("loss")) out.lossOverride = options->at("loss").get<std::string>();
    if (options->contains("fairLoss")) out.fairLossOverride = options->at("fairLoss").get<bool>();
  } catch (const nlohmann::json::exception& e) {
    error = "'" + certificate + "': \"modelOptions\": " + e.what();
    return false;
  }
  return true;
}

std::string firstTableDifference(const runtime::MissionTables& expected, const runtime::MissionTables& actual) {
  const codegen::cpp::Node none;
  if (expected.robots.size() != actual.robots.size()) return "they have " + std::to_string(actual.robots.size()) + " robots, not " + std::to_string(expected.robots.size());
  for (std::size_t r = 0; r < expected.robots.size(); ++r) {
    if (auto d = codegen::cpp::compareRobot(expected.robots[r], actual.robots[r], none)) {
      return "robot " + expected.robots[r].name + ": " + d->path + " is " + d->actual + " where the projection has " + d->expected + (d->what.empty() ? "" : " (" + d->what + ")");
    }
  }
  runtime::MissionTables a = actual, e = expected;
  a.robots.clear(), e.robots.clear();
  if (auto d = codegen::cpp::compareMission(e, a, none)) return d->path + " is " + d->actual + " where the projection has " + d->expected;
  return {};
}

}  // namespace semo::cli
