#pragma once
// certificate.json of an emitted tree (specs/certificate.md): written by emit, read by certify.
#include <string>

#include "semo/codegen/emit.hpp"

namespace semo::codegen {

// The certificate for `emitted.files` (every file but the certificate itself, which it describes).
std::string certificateJson(const model::MissionModel& mission, const Translation& translation, const SourceManager& sources,
                            const checker::Report& report, const EmitOptions& options, const Emitted& emitted);

// The role of an input file in the certificate: "mission", "strategy", "robot" (a URDF), "input".
std::string inputRole(const std::string& path, const EmitOptions& options);

// How many rules of the IR are steps of each robot's program (a row each): the bijection's one side.
std::vector<std::size_t> programRulesPerRobot(const Translation& translation, std::size_t robots);

}  // namespace semo::codegen
