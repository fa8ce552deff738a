#pragma once
// The two halves of `analyze`: an IR model's `eventually` properties (analyze_command.cpp) and a
// mission's knowledge spread in gossip rounds and its heartbeats (analyze_mission.cpp).
#include "commands.hpp"

namespace semo::cli {

// A probability or an expected time as analyze prints it: 9 significant digits, or "infinite".
std::string number(double v);

int analyzeMission(const AnalyzeOptions& options, const BuiltModel& built);

}  // namespace semo::cli
