// A robot's body (kinematics.hpp): the unicycle x' = v cos θ, y' = v sin θ, θ' = ω integrated with
// SUNDIALS CVODE. Commands are piecewise constant, so the integrator restarts (CVodeReInit) at each
// change rather than stepping over the discontinuity, and every advance stops exactly at the time
// asked (CVodeSetStopTime) so that poses are sampled where the simulator wants them.
//
// The system is not stiff: Adams-Moulton (high order, cheap steps) fits it. CVODE solves the implicit
// step with Newton's method, whose 3x3 dense linear system uses the exact Jacobian given below.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "semo/runtime/kinematics.hpp"

namespace semo::runtime {

static_assert(std::is_same_v<sunrealtype, double>, "semo expects SUNDIALS built in double precision (as Debian ships it)");

// The unicycle's command, the data CVODE hands the right-hand side. Outside the anonymous namespace
// because Body::State holds one (a unity build would warn of a member of internal linkage).
struct BodyCommand {
  double v = 0, w = 0;
};

namespace {

constexpr double kRelativeTolerance = 1e-8;
constexpr double kAbsoluteTolerance = 1e-10;
// CVODE's default (500 internal steps per call) would stop a long idle-free advance (an hour of
// driving in one call); the bound only guards against a runaway.
constexpr long kMaxSteps = 10'000'000;

int rhs(sunrealtype /*t*/, N_Vector y, N_Vector ydot, void* data) {
  const auto* c = static_cast<const BodyCommand*>(data);
  const double theta = NV_Ith_S(y, 2);
  NV_Ith_S(ydot, 0) = c->v * std::cos(theta);
  NV_Ith_S(ydot, 1) = c->v * std::sin(theta);
  NV_Ith_S(ydot, 2) = c->w;
  return 0;
}

// d(rhs)/d(x, y, θ): only the θ column is non-zero.
int jacobian(sunrealtype /*t*/, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* data, N_Vector, N_Vector, N_Vector) {
  const auto* c = static_cast<const BodyCommand*>(data);
  const double theta = NV_Ith_S(y, 2);
  SUNMatZero(J);
  SM_ELEMENT_D(J, 0, 2) = -c->v * std::sin(theta);
  SM_ELEMENT_D(J, 1, 2) = c->v * std::cos(theta);
  return 0;
}

void check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(std::string("CVODE: ") + what + " failed (flag " + std::to_string(flag) + ")");
}

double finiteOr0(double x) { return std::isfinite(x) ? x : 0; }

}  // namespace

struct Body::State {
  DriveGeometry geometry;
  double t = 0;
  Pose pose;  // authoritative between advances; θ is not wrapped here (the integral stays smooth)
  BodyCommand command;
  bool restart = true;  // the command changed since CVODE last ran: re-initialise it
  // Created at the first advance that moves: a robot that never moves never allocates a solver.
  SUNContext context = nullptr;
  N_Vector y = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver solver = nullptr;
  void* cvode = nullptr;

  ~State() {
    if (cvode != nullptr) CVodeFree(&cvode);
    if (solver != nullptr) SUNLinSolFree(solver);
    if (matrix != nullptr) SUNMatDestroy(matrix);
    if (y != nullptr) N_VDestroy(y);
    if (context != nullptr) SUNContext_Free(&context);
  }

  void load() {
    NV_Ith_S(y, 0) = pose.x;
    NV_Ith_S(y, 1) = pose.y;
    NV_Ith_S(y, 2) = pose.theta;
  }

  void create() {
    check(SUNContext_Create(nullptr, &context), "SUNContext_Create");
    y = N_VNew_Serial(3, context);
    if (y == nullptr) throw std::runtime_error("CVODE: cannot allocate the state vector");
    load();
    cvode = CVodeCreate(CV_ADAMS, context);
    if (cvode == nullptr) throw std::runtime_error("CVODE: CVodeCreate failed");
    check(CVodeInit(cvode, rhs, t, y), "CVodeInit");
    check(CVodeSStolerances(cvode, kRelativeTolerance, kAbsoluteTolerance), "CVodeSStolerances");
    check(CVodeSetUserData(cvode, &command), "CVodeSetUserData");
    check(CVodeSetMaxNumSteps(cvode, kMaxSteps), "CVodeSetMaxNumSteps");
    matrix = SUNDenseMatrix(3, 3, context);
    solver = SUNLinSol_Dense(y, matrix, context);
    if (matrix == nullptr || solver == nullptr) throw std::runtime_error("CVODE: cannot allocate the linear solver");
    check(CVodeSetLinearSolver(cvode, solver, matrix), "CVodeSetLinearSolver");
    check(CVodeSetJacFn(cvode, jacobian), "CVodeSetJacFn");
    restart = false;
  }

  void integrate(double target) {
    if (cvode == nullptr) {
      create();
    } else if (restart) {
      load();
      check(CVodeReInit(cvode, t, y), "CVodeReInit");
      restart = false;
    }
    check(CVodeSetStopTime(cvode, target), "CVodeSetStopTime");
    sunrealtype reached = t;
    check(CVode(cvode, target, y, &reached, CV_NORMAL), "CVode");
    pose = {NV_Ith_S(y, 0), NV_Ith_S(y, 1), NV_Ith_S(y, 2)};
  }

  void set(double v, double w) {
    v = std::clamp(finiteOr0(v), -geometry.maxSpeed, geometry.maxSpeed);
    w = std::clamp(finiteOr0(w), -geometry.maxTurnRate, geometry.maxTurnRate);
    if (v == command.v && w == command.w) return;  // nothing changes: keep CVODE's step history
    command = {v, w};
    restart = true;
  }
};

Body::Body(Pose start, DriveGeometry geometry, double startTime) : s_(std::make_unique<State>()) {
  geometry.maxSpeed = std::max(0.0, finiteOr0(geometry.maxSpeed));
  geometry.maxTurnRate = std::max(0.0, finiteOr0(geometry.maxTurnRate));
  s_->geometry = geometry;
  s_->pose = start;
  s_->t = startTime;
}

Body::~Body() = default;
Body::Body(Body&&) noexcept = default;
Body& Body::operator=(Body&&) noexcept = default;

void Body::command(double speed, double turnRate) { s_->set(speed, turnRate); }

void Body::wheelSpeeds(double left, double right) {
  const DriveGeometry& g = s_->geometry;
  if (!g.wheeled) return;
  // Differential drive: the rim speeds R·l and R·r average to the forward speed, and their
  // difference over the wheel separation is the turn rate (positive: counter-clockwise).
  const double v = g.wheelRadius * (left + right) / 2;
  const double w = g.wheelSeparation > 0 ? g.wheelRadius * (right - left) / g.wheelSeparation : 0;
  s_->set(v, w);
}

void Body::advanceTo(double t) {
  if (!std::isfinite(t) || t <= s_->t) return;
  // Standing still is the common case (waiting for a message, a crashed robot): no solver at all.
  if (s_->command.v != 0 || s_->command.w != 0) s_->integrate(t);
  s_->t = t;
}

Pose Body::pose() const {
  Pose p = s_->pose;
  p.theta = std::remainder(p.theta, 2 * std::numbers::pi);  // (-π, π]
  return p;
}

double Body::time() const { return s_->t; }
double Body::speed() const { return s_->command.v; }
double Body::turnRate() const { return s_->command.w; }
const DriveGeometry& Body::geometry() const { return s_->geometry; }

}  // namespace semo::runtime
