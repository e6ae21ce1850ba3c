#include "leadscrew/model/drive_rigid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::model {

// From the model's structure (its elements), not its concept: two bodies'
// coordinates, no force element, the thread pair without play (one
// independent coordinate), a torque-controlled motor whose torque is a
// function of time (not a DC motor's k_t i: its current is a state, and its
// drive runs the general path, whose roots see the state), exact Coulomb.
bool RigidDriveModes::applies(const DriveModel& model, const DriveDynamics& dynamics) {
  // (An element's force, a DC motor's or a base excitation's, is not a
  // drive torque of time and an axial force: the general constrained solve
  // takes it.)
  return model.elements().elements.empty() && !model.train_friction() &&
         applies_to_thread(model, dynamics);
}

// The train's friction stages take penalty end stops besides (their force
// is one more axial force on the load, TrainSolver); the coefficients are
// per unit load, the stops' force not among them.
namespace {
bool no_force_elements_but_train_stops(const DriveModel& model) {
  if (model.elements().forces.empty()) return true;
  if (!model.train_friction()) return false;
  bool others = false;
  model.elements().forces.for_each([&](const auto& element) {
    if (!std::is_same_v<std::decay_t<decltype(element)>, elements::EndStop>) others = true;
  });
  return !others;
}
}  // namespace

// Exact Coulomb with one kinetic coefficient and a static one above it
// (friction.law = "coulomb" with mu_static): its slip modes' coefficients
// are constant, and the train's stick test takes mu_static
// (DriveHybrid::stick_mu). The train's friction stages take it
// (docs/physics/gear.md, "A static coefficient on the thread").
static bool constant_kinetic_coulomb(const friction::Law& law) {
  return law.resolution() == friction::Resolution::set_valued && law.viscous() == 0.0 &&
         law.slip_mu(0.0) == law.mu() && law.slip_mu(1.0) == law.mu() &&
         law.slip_mu(1e3) == law.mu();
}

bool RigidDriveModes::applies_to_thread(const DriveModel& model, const DriveDynamics& dynamics) {
  return model.bilateral_thread() && !model.motor().speed_controlled &&
         !model.preloaded_nut() &&
         (dynamics.plain_coulomb() ||
          (model.train_friction() && constant_kinetic_coulomb(dynamics.law()))) &&
         no_force_elements_but_train_stops(model) &&
         model.coordinate_count() == 2 && model.independent().size() == 1 &&
         !dynamics.painleve_possible();
}

std::string RigidDriveModes::train_obstacle(const DriveModel& model,
                                            const DriveDynamics& dynamics) {
  if (!no_force_elements_but_train_stops(model))
    return "a force element besides the end stops (the load spring's)";
  if (dynamics.painleve_possible())
    return "the thread in the Painleve regime (mu' |G_NT| / G_NN = " +
           format_value(model.effective_max_mu() * std::abs(dynamics.coupling())) + " >= 1)";
  return "";
}

RigidDriveModes::RigidDriveModes(const DriveModel& model, DriveDynamics& dynamics) {
  if (!applies_to_thread(model, dynamics))
    throw InvalidArgument("RigidDriveModes needs the torque-driven rigid drive without play "
                          "with exact Coulomb friction outside the Painleve regime");
  const int n = model.coordinate_count();
  const int rotor = model.rotor();
  const int load = model.load();
  // The thread e = grad e . q = 0 with the load eliminated (StateLayout):
  // u_load = -(de/dphi) / (de/du) phi, i.e. -h p phi (eq. 4.1 with the supports).
  const Eigen::VectorXd& play_gradient = model.play_gradient();
  load_per_angle_ = -play_gradient[rotor] / play_gradient[load];
  const Eigen::VectorXd& tangent = model.tangent_direction();
  slip_per_speed_ = tangent[rotor] + tangent[load] * load_per_angle_;
  inertia_ = model.mass()[rotor];
  mass_ = model.mass()[load];

  const CoordinateVector zero = CoordinateVector::Zero(n);
  dynamics.set_state(0.0, zero, zero);
  CoordinateVector unit_torque = zero, unit_force = zero;
  unit_torque[rotor] = model.gear().driven_torque(1.0);  // per unit torque on the rotor
  unit_force[load] = 1.0;
  const FrictionMode frictions[] = {FrictionMode::none, FrictionMode::stick, FrictionMode::slip,
                                    FrictionMode::slip};
  const int slip_signs[] = {0, 0, 1, -1};
  for (int mode = 0; mode < 4; ++mode) {
    for (int side = 0; side < 2; ++side) {
      ModeSpec spec;
      spec.contact = ThreadContact::bilateral;
      spec.sigma = side == 0 ? 1 : -1;
      spec.friction = frictions[mode];
      spec.slip_sign = slip_signs[mode];
      const ModeSolution torque = dynamics.solve_with_forces(spec, unit_torque);
      const ModeSolution force = dynamics.solve_with_forces(spec, unit_force);
      if (!torque.regular || !force.regular)
        throw SimulationError(0.0, "the constraint equations of the rigid drive are singular",
                              "check masses, inertias and the thread geometry");
      RigidModeCoefficients& c = table_[index(spec.friction, spec.slip_sign)][side];
      c.acceleration = {torque.acceleration[rotor], force.acceleration[rotor]};
      c.normal_force = {torque.normal_force, force.normal_force};
      c.friction_force = {torque.friction_force, force.friction_force};
    }
  }
}

}  // namespace leadscrew::model

namespace leadscrew::model {

namespace {

// A bound on |d^2/dt^2| of an excitation between its breakpoints, from the
// semantics Excitation documents for time_scale() and breakpoints(); nullopt
// for a callable (time scale 0: no hint).
std::optional<double> curvature_bound(const Excitation& load) {
  if (!load.breakpoints().empty()) return 0.0;  // table: linear between its knots
  const double scale = load.time_scale();
  if (std::isinf(scale)) return 0.0;         // constant (or a sine without amplitude)
  if (!(scale > 0.0)) return std::nullopt;   // callable
  // A sine of period `scale`: its derivative A w cos(w t + phase) has the
  // amplitude |A| w = hypot(f'(0), f'(scale / 4)), its second derivative |A| w^2.
  const double omega = 2.0 * 3.14159265358979323846 / scale;
  return std::hypot(load.derivative(0.0), load.derivative(0.25 * scale)) * omega;
}

}  // namespace

std::optional<LoadCrossing> first_load_crossing(const Excitation& torque, const Excitation& force,
                                          const LoadCoefficients* functions, int count,
                                          double t0, double t_end) {
  const std::optional<double> torque_curvature = curvature_bound(torque);
  const std::optional<double> force_curvature = curvature_bound(force);
  if (!torque_curvature || !force_curvature) return std::nullopt;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!(t_end > t0)) return LoadCrossing{};
  // The knots of table loads: f' jumps there, so a Taylor bound holds only
  // between them.
  std::vector<double> knots;
  for (const Excitation* load : {&torque, &force})
    for (double knot : load->breakpoints())
      if (knot > t0 && knot < t_end) knots.push_back(knot);
  std::sort(knots.begin(), knots.end());
  knots.push_back(t_end);
  // The shortest step the scan takes where a bound allows less (a touch).
  double time_scale = t_end - t0;
  for (const Excitation* load : {&torque, &force})
    if (std::isfinite(load->time_scale())) time_scale = std::min(time_scale, load->time_scale());
  const double floor_step =
      std::max(1e-12 * time_scale, 64.0 * std::numeric_limits<double>::epsilon() *
                                       std::max(std::abs(t0), std::abs(t_end)));

  double curvature[2] = {0.0, 0.0};
  for (int k = 0; k < count; ++k)
    curvature[k] = (std::abs(functions[k].per_torque) * *torque_curvature +
                    std::abs(functions[k].per_force) * *force_curvature) *
                   (1.0 + 1e-9);  // round-off of the bound itself
  auto value = [&](int k, double t) { return functions[k](torque(t), force(t)); };
  double t = t0;
  std::size_t next_knot = 0;
  // The loads and their slopes at t, shared by the functions.
  double torque_now = torque(t), force_now = force(t);
  for (long step = 0; step < kLoadScanSteps; ++step) {
    while (knots[next_knot] <= t && next_knot + 1 < knots.size()) ++next_knot;
    const double segment_end = knots[next_knot];
    if (t >= t_end) return LoadCrossing{};
    // The largest step over which every lower bound stays positive.
    const double torque_slope = torque.derivative(t), force_slope = force.derivative(t);
    double h = segment_end - t;
    double now[2];
    for (int k = 0; k < count; ++k) {
      const double f = functions[k](torque_now, force_now);
      const double d = functions[k](torque_slope, force_slope), c = curvature[k];
      now[k] = f;
      double safe;
      if (f <= 0.0) {
        safe = 0.0;
      } else if (c == 0.0) {  // linear up to the knot: exact
        safe = d >= 0.0 ? kInfinity : f / -d;
      } else {  // the positive root of f + d h - c h^2 / 2, without cancellation
        const double root = std::sqrt(d * d + 2.0 * c * f);
        safe = d > 0.0 ? (d + root) / c : 2.0 * f / (root - d);
      }
      h = std::min(h, safe);
    }
    double t_next = t + std::max(h, floor_step);
    if (t_next >= segment_end) t_next = segment_end;
    const double torque_next = torque(t_next), force_next = force(t_next);
    double crossing = kInfinity;
    for (int k = 0; k < count; ++k) {
      if (functions[k](torque_next, force_next) >= 0.0) continue;
      const double located = now[k] < 0.0 ? t : first_negative(
          [&](double time) { return value(k, time); }, t, t_next,
          4.0 * std::numeric_limits<double>::epsilon() * std::abs(t_next));
      crossing = std::min(crossing, located);
    }
    if (crossing < kInfinity) return LoadCrossing{crossing, true};
    t = t_next;
    torque_now = torque_next;
    force_now = force_next;
  }
  return LoadCrossing{t, false};  // the horizon: no crossing before t
}

}  // namespace leadscrew::model
