#pragma once
// The entry point of a generated robot program (`semo-verify emit`, robots/NAME/main.cpp): runs
// `robot`'s step tables from `mission` (its own in full, the others' by identity) over a real
// transport, with its command line (`--help` lists it).
#include <string_view>

#include "semo/runtime/tables.hpp"

namespace semo::runtime {

int robotMain(const MissionTables& mission, std::string_view robot, int argc, char** argv);

}  // namespace semo::runtime
