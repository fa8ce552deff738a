#pragma once
// `semo-verify emit` (specs/certificate.md): the verified mission as one C++ program per robot, a
// CMake project that builds them against semo_runtime, and the certificate that says what was
// proven and ties every generated file, table row and function to it.
//
// Everything is made in memory from the verification's Report (checker/verify.hpp: the very value
// `check` and `sdf` print) and the tables projected from the same translation: the caller writes the
// files, all or none. The same inputs give the same files, byte for byte.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/checker/verify.hpp"
#include "semo/frontend/source.hpp"
#include "semo/runtime/tables.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::codegen {

struct GeneratedFile {
  std::string path;  // relative to the output folder, '/'-separated
  std::string text;
};

struct EmitOptions {
  std::string missionPath, strategyPath;  // as given on the command line (the certificate records them)
  std::string robotsDir;                  // --robots, when given
  // How the model was built: --crash, --loss, --fair-loss/--unfair-loss (certify builds it again so).
  std::optional<int> crash;
  std::optional<std::string> loss;
  std::optional<bool> fairLoss;
  // How it was verified (certify --recheck verifies again so).
  std::string engine = "explicit";  // explicit | smt | auto
  std::uint64_t maxStates = 50'000'000;
  std::uint32_t maxDepth = UINT32_MAX;
  bool symmetry = true, safetyOnly = false, bmcOnly = false;
  unsigned proofTimeoutMs = 10'000;
  // How the LTL properties were decided (checker::LivenessOptions): a proof on the exact cone is
  // found again only with the cone's time.
  bool slicing = true, slicesFirst = false, symbolic = true, walks = true;
  std::uint64_t sliceStates = 50'000, walkSeed = 1;
  double symbolicSeconds = 90, coneSeconds = 0;
  std::string toolVersion;                // "0.1.0"
  bool uncertified = false;               // emit although not everything is proven: every file says so
};

struct Emitted {
  std::vector<GeneratedFile> files;  // the certificate last
  runtime::MissionTables tables;     // what the files hold, as the projection made it
  bool certified = false;
  std::vector<std::string> unproven;  // Report::unproven(): why it is not certified
};

// The tables every generated program is made from: the projection of `translation` onto each robot
// with each robot's dataflow from the Report's task graphs (report.taskGraphs must be there).
runtime::MissionTables projectForEmit(const model::MissionModel& mission, const Translation& translation, const SourceManager& sources,
                                      const checker::Report& report);

// Every generated file but the certificate, from the tables alone: what certify compares a tree
// with, made again from the inputs.
std::vector<GeneratedFile> generateSources(const runtime::MissionTables& tables, const EmitOptions& options, bool certified);

// The generated tree. `sources` holds every input read (mission, strategy, URDF files), whose
// SHA-256 the certificate records.
Emitted emit(const model::MissionModel& mission, const Translation& translation, const SourceManager& sources,
             const checker::Report& report, const EmitOptions& options);

// The mission's name as the generated project calls it: the mission file's stem, made an identifier.
std::string missionIdentifier(const std::string& missionPath);

// The version of the certificate format (specs/certificate.md).
inline constexpr int kCertificateVersion = 1;

}  // namespace semo::codegen
