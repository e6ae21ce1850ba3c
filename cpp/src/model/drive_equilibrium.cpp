#include "leadscrew/model/drive_equilibrium.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "drive/run_setup.hpp"
#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model {

namespace {

constexpr int kMaxIterations = 50;
// The balance the result is checked to: a share of the forces that meet at
// each coordinate (round-off leaves 1e-16 of them; the Newton iteration stops
// at its step's round-off).
constexpr double kBalanceTolerance = 1e-9;
// What the Newton iteration takes for round-off of a balance.
constexpr double kRoundOff = 1e-13;

// The springs' stiffness matrix at nut position a (the Jacobian of their
// forces without the terms of the stiffness's change along the nut).
Eigen::MatrixXd stiffness_matrix(const DriveModel& model, double a) {
  const int n = model.coordinate_count();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  model.elements().forces.for_each([&](const auto& element) { element.add_stiffness(K, a); });
  return K;
}

std::string loads_text(const DriveModel& model, const DriveDynamics& dynamics) {
  // (the torque on the rotor, before a gear stage)
  return "drive torque " + format_value(model.gear().rotor_torque(dynamics.applied_torque())) +
         " N*m" + (dynamics.element_drive_torque() != 0.0 ? " (the motor's k_t i at rest)" : "") +
         ", axial force " +
         format_value(dynamics.axial_force()) + " N";
}

// The elements' states at rest in equilibrium (Element::initial_states: a
// DC motor's steady current U(0) / R within its limit), set in `dynamics`:
// their forces (the motor's torque k_t i on the rotor, a drive torque) join
// the balance through DriveDynamics::forces, as the run's first right-hand
// side takes them (its y made by the same call, drive::initial_vector).
void set_element_states_at_rest(const DriveModel& model, DriveDynamics& dynamics) {
  if (model.elements().elements.empty()) return;
  const int n = model.coordinate_count();
  const drive::StateLayout layout(model, dynamics.law());
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(layout.size());
  drive::initial_element_states(model, layout, rest.data(), rest.data(), true, y.data());
  dynamics.set_element_slots(layout.element_slots());
  dynamics.set_element_states(y.data());
}

}  // namespace

DriveStart initial_state(const DriveModel& model) {
  const DriveParameters& p = model.parameters();
  const int n = model.coordinate_count();
  DriveStart start;
  start.play = p.play_position;
  if (p.initial_state == InitialState::relaxed) {
    start.q = Eigen::VectorXd::Zero(n);
    start.v = model.consistent_velocity(p.speed_controlled ? p.drive_speed(0.0) : p.rotor_speed);
    return start;
  }
  // DriveModel refused a speed-controlled motor, a rotor speed and a play
  // position with this start.
  const Eigen::VectorXd& normal = model.normal_direction();
  const Eigen::VectorXd& tangent = model.tangent_direction();
  const Eigen::VectorXd& gradient = model.play_gradient();
  const bool penalty =
      p.backlash == BacklashContact::bistop || p.backlash == BacklashContact::cubic;
  const double half = 0.5 * p.clearance;
  const double cos_lead = std::cos(p.thread.lead_angle());
  const int rotor = model.rotor();

  DriveDynamics dynamics(model);
  CoordinateVector q = CoordinateVector::Zero(n), v = CoordinateVector::Zero(n);
  set_element_states_at_rest(model, dynamics);
  double normal_force = 0.0, friction_force = 0.0;
  // Where the nut rests: on the flank the normal force presses it against
  // (penetrated, for a penalty flank); in the middle of the play while the
  // thread carries nothing.
  auto rest_play = [&](double force) {
    if (model.bilateral_thread() || force == 0.0) return p.play_position;
    const double side = force > 0.0 ? -1.0 : 1.0;  // lower flank e = -c/2 for lambda_N > 0
    return side * (half + (penalty ? model.thread_pair().penetration_for(std::abs(force) * cos_lead) : 0.0));
  };
  // The scale of the forces that meet at each coordinate, against which
  // its balance is judged.
  auto force_scale = [&](int i) {
    const Eigen::MatrixXd K = stiffness_matrix(model, model.nut_position(q.data()));
    double scale = (K.row(i).cwiseAbs() * q.cwiseAbs())(0) +
                   std::abs(normal[i] * normal_force) + std::abs(tangent[i] * friction_force);
    if (i == rotor) scale += std::abs(dynamics.applied_torque());
    if (i == model.load()) scale += std::abs(dynamics.axial_force());
    return scale;
  };
  double target = p.play_position;
  const int size = n + 2;
  Eigen::VectorXd residual(size);
  Eigen::MatrixXd jacobian(size, size);
  bool converged = false;
  int iteration = 0;
  for (;; ++iteration) {
    dynamics.set_state(0.0, q, v);
    residual.head(n) = dynamics.forces() + normal * normal_force + tangent * friction_force;
    residual[n] = dynamics.play() - target;
    residual[n + 1] = q[rotor];
    // Converged where every force balances to round-off, the nut is at its
    // target and the target no longer moves.
    converged = std::abs(rest_play(normal_force) - target) <=
                    kRoundOff * (std::abs(target) + half) &&
                q[rotor] == 0.0 &&
                std::abs(residual[n]) <=
                    kRoundOff * ((gradient.cwiseProduct(q)).cwiseAbs().sum() +
                                 std::abs(target) + half);
    for (int i = 0; i < n && converged; ++i)
      converged = std::abs(residual[i]) <= kRoundOff * force_scale(i);
    if (converged || iteration == kMaxIterations || !residual.allFinite()) break;
    jacobian.setZero();
    jacobian.topLeftCorner(n, n) = -stiffness_matrix(model, model.nut_position(q.data()));
    jacobian.block(0, n, n, 1) = normal;
    jacobian.block(0, n + 1, n, 1) = tangent;
    jacobian.block(n, 0, 1, n) = gradient.transpose();
    jacobian(n + 1, rotor) = 1.0;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(jacobian);
    if (!lu.isInvertible())
      throw SimulationError(0.0, "the static equilibrium's equations are singular",
                            "check masses, stiffnesses and the thread geometry");
    const Eigen::VectorXd step = lu.solve(-residual);
    q += step.head(n);
    q[rotor] = 0.0;  // its row says so; no round-off
    normal_force += step[n];
    friction_force += step[n + 1];
    target = rest_play(normal_force);
  }
  if (!converged)
    throw SimulationError(0.0, "the static equilibrium did not converge in " +
                                   std::to_string(kMaxIterations) + " Newton iterations",
                          "check the loads at t = 0 and the stiffnesses");

  // An exact flank is closed where the play reaches c / 2 exactly (the
  // simulation's test): move the nut's axial coordinate by ulps until its
  // round-off no longer leaves it a hair inside.
  if (p.backlash == BacklashContact::exact && normal_force != 0.0) {
    int k = -1;
    for (int i = 0; i < n; ++i)
      if (i != rotor && (k < 0 || std::abs(gradient[i]) > std::abs(gradient[k]))) k = i;
    const double side = normal_force > 0.0 ? -1.0 : 1.0;
    for (int ulp = 0; ulp < 1000; ++ulp) {
      dynamics.set_state(0.0, q, v);
      if (side * dynamics.play() >= half) break;
      q[k] = std::nextafter(q[k], side * gradient[k] > 0.0 ? HUGE_VAL : -HUGE_VAL);
    }
  }

  dynamics.set_state(0.0, q, v);
  if (penalty) normal_force = dynamics.penalty_normal_force();  // the flank's own force
  // Stick: the friction force inside the static cone (mu_static's: a law
  // with a static coefficient holds up to it), to its round-off.
  const double mu = model.effective_mu_static();
  double cone = mu * std::abs(normal_force);
  // A preloaded nut (without lift-off): the halves' cone at mu_static', half
  // B at the edge the friction force heads for (elements/preloaded_nut.hpp:
  // its spring is internal, the balance the plain nut's).
  if (const elements::PreloadedNut* nut = model.preloaded_nut())
    cone = nut->sticking().bound(elements::PreloadedNut::edge_of(friction_force), normal_force);
  if (std::abs(friction_force) > cone + 1e-12 * (std::abs(friction_force) + cone))
    throw NoEquilibrium(
        "initial.state = \"equilibrium\" is invalid for the loads at t = 0 (" +
        loads_text(model, dynamics) + "): holding them at rest takes a flank friction force of " +
        format_value(std::abs(friction_force)) +
        " N, beyond the static friction cone mu_static' |N| = " +
        format_value(cone) + " N (normal force " +
        format_value(normal_force) + " N, mu_static' = " + format_value(mu) +
        "): the loads drive the thread, no static equilibrium exists");

  // The balance, checked with the forces DriveDynamics computes (after the
  // nudge and with the penalty flank's own force).
  const Eigen::VectorXd balance =
      dynamics.forces() + normal * normal_force + tangent * friction_force;
  for (int i = 0; i < n; ++i) {
    const double scale = force_scale(i);
    if (!(std::abs(balance[i]) <= kBalanceTolerance * scale))
      throw SimulationError(0.0, "the static equilibrium leaves a force of " +
                                     format_value(balance[i]) + " unbalanced on " +
                                     model.coordinate_names()[i] + " (of " +
                                     format_value(scale) + " meeting there)",
                            "check the loads at t = 0 and the stiffnesses");
  }
  start.q = q;
  start.v = Eigen::VectorXd::Zero(n);
  start.play = dynamics.play();
  start.normal_force = normal_force;
  start.friction_force = friction_force;
  start.iterations = iteration;
  return start;
}

}  // namespace leadscrew::model
