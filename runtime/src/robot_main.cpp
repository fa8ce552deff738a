// robotMain (robot_main.hpp): a generated robot program's command line, its transport, and the
// real-time loop that drives its RobotNode from the steady clock.
#include "semo/runtime/robot_main.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "semo/runtime/dds_transport.hpp"
#include "semo/runtime/robot_node.hpp"
#include "semo/runtime/udp_transport.hpp"

namespace semo::runtime {

namespace {

volatile std::sig_atomic_t stopRequested = 0;
void requestStop(int) { stopRequested = 1; }

constexpr const char* kUsage = R"(options:
  --transport udp|dds     how it talks to its team (default udp; dds: Eclipse Cyclone DDS, when built with it)
  --peers NAME=HOST:PORT,...
                          udp: where each robot of the mission listens (default: 127.0.0.1, port
                          --port-base + the robot's place in the mission)
  --port-base N           udp: the first robot's port (default 47000)
  --multicast GROUP:PORT  udp: also join this IP multicast group (a LAN: 239.x.y.z), and send what
                          goes to every other robot as one datagram to it
  --interface ADDR        udp: the interface for --multicast (default: the system's choice)
  --domain N              dds: the DDS domain (default 0)
  --dds-interface ADDR    dds: use only the network interface of this address, multicast on
                          (127.0.0.1 for a team on one machine; default: Cyclone DDS's choice, or
                          its configuration in CYCLONEDDS_URI)
  --world FILE            the world its body and sensors are simulated in (semo-world JSON);
                          without one it stands at the origin and its sensed values read false
  --duration T            stop after T (60s, 500ms, 2min; default 60s)
  --keep-running          go on after the mission's goal is reached, until --duration
  --crash-at T            fall silent at T, as a crash (to try the team's failure detection)
  --loss P                lose this share of the messages the model lets be lost, on receipt
  --seed N                seed of its random choices (default 1)
  --status-period T       how often it tells its peers where it is (default 100ms)
  --report-every T        how often it prints how it is: time, mode, leaders, live peers,
                          packets (default 5s; 0: only at the end)
  --peer-timeout T        a peer silent this long is taken as crashed (default 3s)
  --trace FILE            write its trace (semo-simtrace JSON) at the end
  --quiet                 print nothing but errors
  --help                  this text
)";

std::optional<double> seconds(const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (...) {
    return std::nullopt;
  }
  const std::string unit = text.substr(used);
  if (unit.empty() || unit == "s") return v;
  if (unit == "ms") return v / 1000;
  if (unit == "min") return v * 60;
  return std::nullopt;
}

struct Arguments {
  std::string transport = "udp";
  std::map<std::string, std::string> peers;
  int portBase = 47000;
  int domain = 0;
  std::string ddsInterface;
  std::optional<UdpEndpoint> multicast;
  std::string interface = "0.0.0.0";
  std::string world, trace;
  double duration = 60, statusPeriod = 0.1, peerTimeout = 3, loss = 0, reportEvery = 5;
  std::optional<double> crashAt;
  std::uint64_t seed = 1;
  bool keepRunning = false, quiet = false, help = false;
};

// Parses argv; "" when fine, else the error.
std::string parse(int argc, char** argv, Arguments& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= argc) return false;
      out = argv[++i];
      return true;
    };
    auto time = [&](double& out) {
      std::string v;
      if (!value(v)) return false;
      const std::optional<double> s = seconds(v);
      if (!s || *s < 0 || *s > 86400) return false;
      out = *s;
      return true;
    };
    std::string v;
    if (arg == "--help") {
      a.help = true;
    } else if (arg == "--keep-running") {
      a.keepRunning = true;
    } else if (arg == "--quiet") {
      a.quiet = true;
    } else if (arg == "--transport") {
      if (!value(a.transport) || (a.transport != "udp" && a.transport != "dds")) return "--transport: expected udp or dds";
    } else if (arg == "--peers") {
      if (!value(v)) return "--peers: expected NAME=HOST:PORT,...";
      std::size_t start = 0;
      while (start <= v.size()) {
        const std::size_t comma = std::min(v.find(',', start), v.size());
        const std::string item = v.substr(start, comma - start);
        const std::size_t eq = item.find('=');
        if (eq == std::string::npos || !parseUdpEndpoint(item.substr(eq + 1))) return "--peers: '" + item + "' is not NAME=HOST:PORT";
        a.peers[item.substr(0, eq)] = item.substr(eq + 1);
        start = comma + 1;
      }
    } else if (arg == "--port-base" || arg == "--domain") {
      if (!value(v) || v.empty() || v.size() > 5 || v.find_first_not_of("0123456789") != std::string::npos) return arg + ": expected a number";
      (arg == "--port-base" ? a.portBase : a.domain) = std::stoi(v);
      if (a.portBase < 1 || a.portBase > 65000) return "--port-base: expected 1..65000";
    } else if (arg == "--multicast") {
      if (!value(v) || !(a.multicast = parseUdpEndpoint(v))) return "--multicast: expected GROUP:PORT, an IPv4 multicast address and a port";
    } else if (arg == "--interface") {
      if (!value(a.interface)) return "--interface: expected an address";
    } else if (arg == "--dds-interface") {
      if (!value(a.ddsInterface)) return "--dds-interface: expected an address";
    } else if (arg == "--world") {
      if (!value(a.world)) return "--world: expected a file";
    } else if (arg == "--trace") {
      if (!value(a.trace)) return "--trace: expected a file";
    } else if (arg == "--duration") {
      if (!time(a.duration) || a.duration <= 0) return "--duration: expected a time such as 60s, 500ms or 2min";
    } else if (arg == "--status-period") {
      if (!time(a.statusPeriod) || a.statusPeriod <= 0) return "--status-period: expected a time such as 100ms";
    } else if (arg == "--report-every") {
      if (!time(a.reportEvery)) return "--report-every: expected a time such as 5s (0: only at the end)";
    } else if (arg == "--peer-timeout") {
      if (!time(a.peerTimeout) || a.peerTimeout <= 0) return "--peer-timeout: expected a time such as 3s";
    } else if (arg == "--crash-at") {
      double t = 0;
      if (!time(t)) return "--crash-at: expected a time such as 5s";
      a.crashAt = t;
    } else if (arg == "--loss") {
      if (!value(v)) return "--loss: expected a probability";
      try {
        a.loss = std::stod(v);
      } catch (...) {
        a.loss = -1;
      }
      if (a.loss < 0 || a.loss > 1) return "--loss: expected a probability between 0 and 1";
    } else if (arg == "--seed") {
      if (!value(v) || v.empty() || v.find_first_not_of("0123456789") != std::string::npos) return "--seed: expected a number";
      a.seed = std::stoull(v);
    } else {
      return "unknown option '" + arg + "' (--help lists them)";
    }
  }
  return {};
}

// How the robot is, in a line: "ev3_0  12.0 s  SEARCH_MODE; leaders: ReportPapers#2 ev3_0,
// WatchLight#3 burger_1; peers alive 4 of 4; packets 812 sent, 790 received, 0 refused".
std::string statusLine(const MissionTables& mission, const RobotNode& node, Id self, double seconds, const TransportCounters& c) {
  std::string out = mission.robots[self].name + "  " + std::to_string(static_cast<long long>(seconds)) + "." +
                    std::to_string(static_cast<long long>(seconds * 10) % 10) + " s  " +
                    mission.teams[mission.robots[self].team].modes[node.mode(self)].name + (node.alive(self) ? "" : " (crashed)");
  std::string leaders;
  for (Id lb = 0; lb < mission.leaderBlocks.size(); ++lb) {
    const LeaderBlockTable& l = mission.leaderBlocks[lb];
    if (std::find(l.candidates.begin(), l.candidates.end(), self) == l.candidates.end()) continue;
    std::string who = "none";
    for (Id r : l.candidates) {
      if (node.alive(r) && node.leads(r, lb)) who = mission.robots[r].name;
    }
    const std::string block = l.name.substr(l.name.rfind('.') == std::string::npos ? 0 : l.name.rfind('.') + 1);
    leaders += (leaders.empty() ? "" : ", ") + block + " " + who;
  }
  if (!leaders.empty()) out += "; leaders: " + leaders;
  std::size_t peers = 0, alive = 0;
  for (Id r = 0; r < mission.robots.size(); ++r) {
    if (r == self) continue;
    ++peers;
    if (node.alive(r)) ++alive;
  }
  // Refused: not of the team's format (the transport), or not what the mission's tables allow (the
  // node), by reason.
  const PacketRefusals& r = node.refusals();
  std::string why;
  for (std::size_t k = 1; k < kPacketRefusals; ++k) {
    if (r.count[k] != 0) why += (why.empty() ? "" : ", ") + std::to_string(r.count[k]) + " " + std::string(packetRefusalName(static_cast<PacketRefusal>(k)));
  }
  if (c.refused != 0) why += (why.empty() ? "" : ", ") + std::to_string(c.refused) + " malformed";
  return out + "; peers alive " + std::to_string(alive) + " of " + std::to_string(peers) + "; packets " + std::to_string(c.sent) + " sent, " +
         std::to_string(c.delivered) + " received, " + std::to_string(c.refused + r.total()) + " refused" + (why.empty() ? "" : " (" + why + ")");
}

}  // namespace

int robotMain(const MissionTables& mission, std::string_view robotName, int argc, char** argv) {
  const std::string name(robotName);
  Arguments a;
  if (const std::string error = parse(argc, argv, a); !error.empty()) {
    std::cerr << name << ": error: " << error << "\n";
    return 2;
  }
  Id self = kNone;
  for (Id r = 0; r < mission.robots.size(); ++r) {
    if (mission.robots[r].name == name) self = r;
  }
  if (a.help || self == kNone) {
    std::cout << "usage: " << name << " [options]\n" << "The program of robot " << name << " of the mission (" << mission.robots.size()
              << " robots, model " << mission.modelFingerprint << "), generated by semo-verify emit.\n"
              << kUsage;
    return self == kNone ? 2 : 0;
  }
  for (const auto& given : a.peers) {
    const std::string& peer = given.first;
    const bool known = std::any_of(mission.robots.begin(), mission.robots.end(), [&](const RobotTable& r) { return r.name == peer; });
    if (!known) {
      std::cerr << name << ": error: --peers: no robot named '" << peer << "' in the mission\n";
      return 2;
    }
  }

  World world;
  if (!a.world.empty()) {
    std::vector<WorldError> errors;
    std::optional<World> read = readWorld(a.world, errors);
    for (const WorldError& e : errors) std::cerr << formatWorldError(e);
    if (!read) return 2;
    world = std::move(*read);
    const std::vector<std::string> problems = checkWorld(mission, world);
    for (const std::string& p : problems) std::cerr << a.world << ": error: " << p << "\n";
    if (!problems.empty()) return 2;
  }

  std::unique_ptr<Transport> transport;
  std::string error;
  if (a.transport == "udp") {
    std::vector<UdpEndpoint> endpoints;
    for (Id r = 0; r < mission.robots.size(); ++r) {
      auto given = a.peers.find(mission.robots[r].name);
      endpoints.push_back(given != a.peers.end() ? *parseUdpEndpoint(given->second)
                                                 : UdpEndpoint{"127.0.0.1", static_cast<std::uint16_t>(a.portBase + static_cast<int>(r))});
    }
    std::optional<UdpMulticast> group;
    if (a.multicast) group = UdpMulticast{*a.multicast, a.interface};
    auto udp = std::make_unique<UdpTransport>(self, std::move(endpoints), group);
    if (!udp->open(error)) {
      std::cerr << name << ": error: " << error << "\n";
      return 2;
    }
    transport = std::move(udp);
  } else {
    transport = makeDdsTransport(mission, self, {a.domain, a.ddsInterface}, error);
    if (!transport) {
      std::cerr << name << ": error: " << error << "\n";
      return 2;
    }
  }

  NodeOptions options;
  options.simulation.duration = a.duration;
  options.simulation.seed = a.seed;
  options.simulation.loss = a.loss;
  options.simulation.stopAtGoal = !a.keepRunning;
  if (a.crashAt) options.simulation.crashes.push_back({name, *a.crashAt});
  options.statusPeriod = a.statusPeriod;
  options.peerTimeout = a.peerTimeout;
  RobotNode node(mission, self, world, TaskLibrary::registry(), *transport, options);

  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const auto end = static_cast<std::int64_t>(a.duration * 1e6);
  node.start();
  const auto reportEvery = static_cast<std::int64_t>(a.reportEvery * 1e6);
  std::int64_t nextReport = reportEvery;
  while (stopRequested == 0) {
    const std::int64_t now = std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start).count();
    if (!node.advanceTo(std::min(now, end)) || now >= end) break;
    // A line every --report-every, so that whoever watches the robot sees how it is.
    if (reportEvery > 0 && now >= nextReport && !a.quiet) {
      std::cout << statusLine(mission, node, self, static_cast<double>(now) / 1e6, transport->counters()) << std::endl;
      while (nextReport <= now) nextReport += reportEvery;
    }
    // Until the next timed step, but at least every millisecond for what the peers send.
    const std::int64_t next = std::min({node.nextEventTime(), now + 1000, end});
    std::this_thread::sleep_until(start + std::chrono::microseconds(next));
  }
  SimTrace trace = node.finish();
  if (!a.trace.empty()) {
    std::ofstream out(a.trace + ".partial", std::ios::binary);
    out << simTraceToJson(trace);
    out.close();
    if (!out || std::rename((a.trace + ".partial").c_str(), a.trace.c_str()) != 0) {
      std::cerr << name << ": error: cannot write '" << a.trace << "'\n";
      return 2;
    }
  }
  const TransportCounters c = transport->counters();
  if (!a.quiet) {
    const TeamTable& team = mission.teams[mission.robots[self].team];
    std::cout << name << ": " << trace.duration << " s, mode " << team.modes[node.mode(self)].name
              << (trace.summary.completed ? ", the mission's goal reached" : "") << (node.alive(self) ? "" : ", crashed (--crash-at)")
              << "; packets: " << c.sent << " sent, " << c.delivered << " received\n";
    std::cout << "at the end: " << statusLine(mission, node, self, trace.duration, c) << "\n";
  }
  return trace.summary.violations.empty() ? 0 : 1;
}

}  // namespace semo::runtime
