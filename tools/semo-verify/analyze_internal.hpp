#pragma once
// The two halves of `analyze`: an IR model's `eventually` properties (analyze_command.cpp) and a
// mission's knowledge spread in gossip rounds and its heartbeats (analyze_mission.cpp).
#include "commands.hpp"

namespace semo::cli {

// A probability or an expected time as analyze prints it: 9 significant digits, or "infinite".
std::string number(double v);

// A probability of P(within t) for people: "0.960000"; near 1 as "1 - 3.2e-7" and near 0 as
// "3.2e-7", where six decimals would round a value short of 1 up to 1.000000 or a small one down to
// 0.000000; "1" and "0" only within 1e-12 of them (the arithmetic's own error is about 1e-15).
std::string probabilityText(double p);

int analyzeMission(const AnalyzeOptions& options, const BuiltModel& built);

}  // namespace semo::cli
