#pragma once
#include <string>

#include "semo/frontend/ast.hpp"

namespace semo {

// The AST as JSON (2-space indented), with "line"/"col" on every node that has a position.
std::string missionToJson(const ast::Mission& mission);
// One-paragraph summary: counts of teams, robots, services, modes, mains and verify items.
std::string missionSummary(const ast::Mission& mission);

}  // namespace semo
