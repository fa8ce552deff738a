#pragma once
// A robot's body in the simulated world: its pose integrated over time with SUNDIALS CVODE from
// the commands its tasks give. A wheeled robot is a differential drive (wheel radius and separation
// from its URDF); a legged robot moves as a unicycle. Commands are piecewise constant: the
// integrator is re-initialised at each change, so a pose at time t is exact up to CVODE's
// tolerances (1e-8 relative, 1e-10 absolute).
#include <memory>

namespace semo::runtime {

struct Pose {
  double x = 0, y = 0, theta = 0;  // metres, radians
};

struct DriveGeometry {
  bool wheeled = false;
  double wheelRadius = 0;       // metres (wheeled)
  double wheelSeparation = 0;   // metres (wheeled)
  double maxSpeed = 0.3;        // m/s, forward or backward
  double maxTurnRate = 1.5;     // rad/s
  friend bool operator==(const DriveGeometry&, const DriveGeometry&) = default;
};

class Body {
 public:
  Body(Pose start, DriveGeometry geometry, double startTime = 0);
  ~Body();
  Body(Body&&) noexcept;
  Body& operator=(Body&&) noexcept;
  Body(const Body&) = delete;
  Body& operator=(const Body&) = delete;

  // Forward speed (m/s) and turn rate (rad/s), each clipped to the geometry's limits; a wheeled
  // robot turns them into wheel speeds. Takes effect from the body's current time.
  void command(double speed, double turnRate);
  // Wheel angular speeds (rad/s), wheeled robots only (a legged robot ignores this).
  void wheelSpeeds(double left, double right);
  // Integrates from the body's current time to `t` (t below the current time is ignored).
  void advanceTo(double t);

  [[nodiscard]] Pose pose() const;
  [[nodiscard]] double time() const;
  [[nodiscard]] double speed() const;     // the commanded forward speed
  [[nodiscard]] double turnRate() const;  // the commanded turn rate
  [[nodiscard]] const DriveGeometry& geometry() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace semo::runtime
