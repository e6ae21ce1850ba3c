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

// The scale of the forces that meet at each coordinate, against which its
// balance is judged: the springs' forces there, the flank's and the loads'.
// A coordinate no load passes through (the rotor's coupling under a zero
// drive torque: its torque is round-off of the angles beyond it) takes the
// scale its springs pass on from their other ends, |K_ij / K_jj| s_j (the
// force at j turned into coordinate i's units by the spring between them,
// along the chain, n - 1 sweeps); judged against itself, its round-off never
// balanced (docs/physics/drive_models.md, "The start").
Eigen::VectorXd force_scales(const DriveModel& model, const DriveDynamics& dynamics,
                             const Eigen::VectorXd& q, double normal_force,
                             double friction_force) {
  const int n = model.coordinate_count();
  const Eigen::VectorXd& normal = model.normal_direction();
  const Eigen::VectorXd& tangent = model.tangent_direction();
  const Eigen::MatrixXd K = stiffness_matrix(model, model.nut_position(q.data()));
  Eigen::VectorXd scale(n);
  for (int i = 0; i < n; ++i) {
    scale[i] = (K.row(i).cwiseAbs() * q.cwiseAbs())(0) + std::abs(normal[i] * normal_force) +
               std::abs(tangent[i] * friction_force);
    if (i == model.rotor()) scale[i] += std::abs(dynamics.applied_torque());
    if (i == model.load()) scale[i] += std::abs(dynamics.axial_force());
  }
  for (int sweep = 1; sweep < n; ++sweep) {
    const Eigen::VectorXd passed = scale;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (j != i && K(j, j) != 0.0)
          scale[i] = std::max(scale[i], std::abs(K(i, j) / K(j, j)) * passed[j]);
  }
  return scale;
}

// The scale of the play's equation e(q) = e*: the play's terms at q, the
// flank's place, and the deflection the forces meeting at each coordinate
// make on its own spring, s_j / K_jj, through grad e (without play and under
// no drive torque the nut's coordinates balance at zero: the play's terms
// are then round-off of themselves, as the rotor's torque above).
double play_scale(const DriveModel& model, const Eigen::VectorXd& q, double target,
                  const Eigen::VectorXd& force_scale) {
  const Eigen::VectorXd& gradient = model.play_gradient();
  const Eigen::MatrixXd K = stiffness_matrix(model, model.nut_position(q.data()));
  double deflections = 0.0;
  for (int j = 0; j < q.size(); ++j)
    if (K(j, j) != 0.0) deflections += std::abs(gradient[j] * force_scale[j] / K(j, j));
  return (gradient.cwiseProduct(q)).cwiseAbs().sum() + std::abs(target) +
         0.5 * model.parameters().clearance + deflections;
}

// The worst balance of `residual` (the coordinates' forces against their
// scales), in words, for an error's message.
std::string worst_balance(const DriveModel& model, const Eigen::VectorXd& residual,
                          const Eigen::VectorXd& scale) {
  int worst = 0;
  for (int i = 1; i < scale.size(); ++i)
    if (std::abs(residual[i]) * scale[worst] > std::abs(residual[worst]) * scale[i]) worst = i;
  return format_value(residual[worst]) + " unbalanced on " + model.coordinate_names()[worst] +
         " (of " + format_value(scale[worst]) + " meeting there)";
}

// The balance's unknowns besides the coordinates: the flank's forces.
struct Balance {
  CoordinateVector q;
  double normal_force = 0.0, friction_force = 0.0;
  int iterations = 0;
};

// Newton's method on f(q) + W_N lambda_N + W_T lambda_T = 0, e(q) = e*,
// q_rotor = 0 (drive_equilibrium.hpp), from q = 0 and no flank force; e*
// follows lambda_N between the iterations.
Balance solve_balance(const DriveModel& model, DriveDynamics& dynamics) {
  const DriveParameters& p = model.parameters();
  const int n = model.coordinate_count();
  const Eigen::VectorXd& normal = model.normal_direction();
  const Eigen::VectorXd& tangent = model.tangent_direction();
  const Eigen::VectorXd& gradient = model.play_gradient();
  const bool penalty =
      p.backlash == BacklashContact::bistop || p.backlash == BacklashContact::cubic;
  const double half = 0.5 * p.clearance;
  const double cos_lead = std::cos(p.thread.lead_angle());
  const int rotor = model.rotor();
  const CoordinateVector v = CoordinateVector::Zero(n);
  Balance b{CoordinateVector::Zero(n)};
  CoordinateVector& q = b.q;
  double& normal_force = b.normal_force;
  double& friction_force = b.friction_force;
  // Where the nut rests: on the flank the normal force presses it against
  // (penetrated, for a penalty flank); in the middle of the play while the
  // thread carries nothing.
  auto rest_play = [&](double force) {
    if (model.bilateral_thread() || force == 0.0) return p.play_position;
    const double side = force > 0.0 ? -1.0 : 1.0;  // lower flank e = -c/2 for lambda_N > 0
    return side * (half + (penalty ? model.thread_pair().penetration_for(std::abs(force) * cos_lead) : 0.0));
  };
  double target = p.play_position;
  const int size = n + 2;
  Eigen::VectorXd residual(size);
  Eigen::MatrixXd jacobian(size, size);
  bool converged = false;
  for (;; ++b.iterations) {
    dynamics.set_state(0.0, q, v);
    residual.head(n) = dynamics.forces() + normal * normal_force + tangent * friction_force;
    residual[n] = dynamics.play() - target;
    residual[n + 1] = q[rotor];
    // Converged where every force balances to round-off, the nut is at its
    // target and the target no longer moves.
    converged = std::abs(rest_play(normal_force) - target) <=
                    kRoundOff * (std::abs(target) + half) &&
                q[rotor] == 0.0;
    if (converged) {
      const Eigen::VectorXd scale = force_scales(model, dynamics, q, normal_force, friction_force);
      converged = std::abs(residual[n]) <= kRoundOff * play_scale(model, q, target, scale);
      for (int i = 0; i < n && converged; ++i)
        converged = std::abs(residual[i]) <= kRoundOff * scale[i];
    }
    if (converged || b.iterations == kMaxIterations || !residual.allFinite()) break;
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
    throw SimulationError(
        0.0,
        "the static equilibrium did not converge in " + std::to_string(kMaxIterations) +
            " Newton iterations (the last left a force of " +
            worst_balance(model, residual.head(n),
                          force_scales(model, dynamics, q, normal_force, friction_force)) +
            ", the nut " + format_value(residual[n]) + " m from where the loads put it)",
        "check the loads at t = 0 and the stiffnesses");
  return b;
}

// An exact flank is closed where the play reaches c / 2 exactly (the
// simulation's test): move the nut's axial coordinate by ulps until its
// round-off no longer leaves it a hair inside.
void close_exact_flank(const DriveModel& model, DriveDynamics& dynamics, Balance& b) {
  const DriveParameters& p = model.parameters();
  if (p.backlash != BacklashContact::exact || b.normal_force == 0.0) return;
  const int n = model.coordinate_count();
  const Eigen::VectorXd& gradient = model.play_gradient();
  const CoordinateVector v = CoordinateVector::Zero(n);
  int k = -1;
  for (int i = 0; i < n; ++i)
    if (i != model.rotor() && (k < 0 || std::abs(gradient[i]) > std::abs(gradient[k]))) k = i;
  const double side = b.normal_force > 0.0 ? -1.0 : 1.0;
  for (int ulp = 0; ulp < 1000; ++ulp) {
    dynamics.set_state(0.0, b.q, v);
    if (side * dynamics.play() >= 0.5 * p.clearance) break;
    b.q[k] = std::nextafter(b.q[k], side * gradient[k] > 0.0 ? HUGE_VAL : -HUGE_VAL);
  }
}

// The thread holds (the friction force inside the static cone) and every
// force balances, checked with the forces DriveDynamics computes at the
// state set in `dynamics` (after the nudge, with a penalty flank's own force
// in b.normal_force).
void check_holds(const DriveModel& model, const DriveDynamics& dynamics, const Balance& b) {
  // Stick: the friction force inside the static cone (mu_static's: a law
  // with a static coefficient holds up to it), to its round-off.
  const double mu = model.effective_mu_static();
  double cone = mu * std::abs(b.normal_force);
  // A preloaded nut (without lift-off): the halves' cone at mu_static', half
  // B at the edge the friction force heads for (elements/preloaded_nut.hpp:
  // its spring is internal, the balance the plain nut's).
  if (const elements::PreloadedNut* nut = model.preloaded_nut())
    cone = nut->sticking().bound(elements::PreloadedNut::edge_of(b.friction_force),
                                 b.normal_force);
  if (std::abs(b.friction_force) > cone + 1e-12 * (std::abs(b.friction_force) + cone))
    throw NoEquilibrium(
        "initial.state = \"equilibrium\" is invalid for the loads at t = 0 (" +
        loads_text(model, dynamics) + "): holding them at rest takes a flank friction force of " +
        format_value(std::abs(b.friction_force)) +
        " N, beyond the static friction cone mu_static' |N| = " +
        format_value(cone) + " N (normal force " +
        format_value(b.normal_force) + " N, mu_static' = " + format_value(mu) +
        "): the loads drive the thread, no static equilibrium exists");
  const Eigen::VectorXd balance = dynamics.forces() + model.normal_direction() * b.normal_force +
                                  model.tangent_direction() * b.friction_force;
  const Eigen::VectorXd scale =
      force_scales(model, dynamics, b.q, b.normal_force, b.friction_force);
  for (int i = 0; i < balance.size(); ++i)
    if (!(std::abs(balance[i]) <= kBalanceTolerance * scale[i]))
      throw SimulationError(0.0, "the static equilibrium leaves a force of " +
                                     worst_balance(model, balance, scale),
                            "check the loads at t = 0 and the stiffnesses");
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
  DriveDynamics dynamics(model);
  set_element_states_at_rest(model, dynamics);
  Balance b = solve_balance(model, dynamics);
  close_exact_flank(model, dynamics, b);
  dynamics.set_state(0.0, b.q, CoordinateVector::Zero(n));
  const bool penalty =
      p.backlash == BacklashContact::bistop || p.backlash == BacklashContact::cubic;
  if (penalty) b.normal_force = dynamics.penalty_normal_force();  // the flank's own force
  check_holds(model, dynamics, b);
  start.q = b.q;
  start.v = Eigen::VectorXd::Zero(n);
  start.play = dynamics.play();
  start.normal_force = b.normal_force;
  start.friction_force = b.friction_force;
  start.iterations = b.iterations;
  return start;
}

}  // namespace leadscrew::model
