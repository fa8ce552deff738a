#pragma once
// The simulated task library: what a primitive or group service does to a simulated robot (drive
// to a place, search the floor, march in line, turn back, ...), registered by the service's name.
// Every service of specs/examples has one; a service without one takes a short fixed time and does
// nothing else. A user's own service plugs in the same way (TaskLibrary::add).
//
// A behaviour runs once per control period while its call is under way; it commands the robot's
// body and says when the call is over. It never blocks and never sees other robots' state except
// their poses and teams (what a camera or a proximity sensor would show).
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "semo/runtime/kinematics.hpp"
#include "semo/runtime/world.hpp"

namespace semo::runtime {

// What a behaviour can see and do.
struct BehaviourContext {
  std::uint32_t robot = 0;
  double now = 0;   // seconds
  double dt = 0;    // the control period, seconds
  Body* body = nullptr;
  const World* world = nullptr;
  const std::vector<Pose>* poses = nullptr;  // every robot's pose now (robot order)
  const std::vector<bool>* alive = nullptr;
  const std::vector<std::string>* teams = nullptr;  // every robot's team name (robot order)
  std::vector<std::string> args;             // the call's arguments, as text ("base camp")
  // Facts of the knowledge items the call works for that the robot does not hold yet (group services).
  std::vector<const FactSite*> unknownFacts;
  Vec2* destination = nullptr;               // the robot's last destination (sensors at_destination, ...)
};

class Behaviour {
 public:
  virtual ~Behaviour() = default;
  // Called once when the call starts.
  virtual void start(BehaviourContext& ctx) = 0;
  // Called once per control period; returns true when the call is over (group services: never,
  // their goal ends them).
  virtual bool step(BehaviourContext& ctx) = 0;
};

class TaskLibrary {
 public:
  using Factory = std::function<std::unique_ptr<Behaviour>()>;
  // The library of every service of specs/examples.
  static TaskLibrary standard();
  // The one library a generated robot program runs: the standard one, to which a user's own source
  // adds or replaces tasks before main runs, e.g. in a file of their own that the generated project
  // builds in (user_tasks.cmake, specs/certificate.md):
  //   static const bool mine = (semo::runtime::TaskLibrary::registry().add("move", [] { return ...; }), true);
  static TaskLibrary& registry();
  void add(const std::string& service, Factory factory);
  [[nodiscard]] bool has(std::string_view service) const;
  // A new behaviour for `service` (a fixed short pause for a service the library does not know).
  [[nodiscard]] std::unique_ptr<Behaviour> make(std::string_view service) const;

 private:
  std::map<std::string, Factory, std::less<>> factories_;
};

}  // namespace semo::runtime
