// robotMain (robot_main.hpp). The networked robot runtime is the next step of issue 14; until it
// lands, a generated program explains that and exits with 2, rather than pretending to run.
#include "semo/runtime/robot_main.hpp"

#include <iostream>
#include <string>

namespace semo::runtime {

int robotMain(const MissionTables& mission, std::string_view robot, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--help") {
      std::cout << "usage: " << robot << " [--transport udp|dds] [--peers NAME=HOST:PORT,...]\n";
      return 0;
    }
  }
  std::cerr << robot << ": error: this semo_runtime cannot run a robot over a network yet (" << mission.robots.size() << " robots)\n";
  return 2;
}

}  // namespace semo::runtime
