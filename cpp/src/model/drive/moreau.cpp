// DriveMoreau (moreau.hpp): the Moreau-Jean step of a drive, its flank LCP
// on the velocity level, the restitution that creates no energy, and the
// check that a step resolves the drive's stiffness.
#include "moreau.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/friction/law.hpp"
#include "screw_end.hpp"

namespace leadscrew::model::drive {

DriveMoreau::DriveMoreau(const DriveModel& model)
    : model_(model), p_(model.parameters()), dynamics_(model), layout_(model, false),
      names_(drive_channel_names(layout_)), current_state_(layout_.find_state("motor_current")),
      copper_state_(layout_.find_state("copper_loss")),
      dc_channel_(layout_.find_channel("motor_current")) {
  const int n = model.coordinate_count();
  q_.setZero(n);
  v_.setZero(n);
}

void DriveMoreau::initialize(double t, const double* y) {
  layout_.expand(t, y, q_, v_);
  dynamics_.set_state(t, q_, v_);
  if (const elements::DcMotor* dc = model_.dc_motor())
    last_voltage_ = dc->terminal_voltage(t, dynamics_.motor_current(), v_[dc->rotor], false);
  kinetic0_ = dynamics_.kinetic_energy();
  elastic0_ = dynamics_.elastic_energy();
}

void DriveMoreau::step(double t, double h, double theta, const double* y, double* y_next) {
  const double excess = friction_excess_, play_rate = play_rate_;
  if (!take_step(t, h, theta, y, y_next, p_.restitution)) return;
  // A step that closes a flank with Newton's restitution e > 0: with
  // Coulomb friction it can create energy (Kane and Levinson's paradox, as
  // at the event-driven scheme's impacts: a rigid nut's closing step at
  // e = 1 created 0.3 of the run's energy, at every dt). The step takes the
  // largest restitution up to e that creates no more than its plastic
  // version (e = 0, whose impulses solve the LCP of maximal dissipation),
  // found by bisection; the step is rare, its 40 solves cheap.
  const StepAccount first = energy_created(t, h, y, y_next);
  auto retake = [&](double e) {
    friction_excess_ = excess;
    play_rate_ = play_rate;
    take_step(t, h, theta, y, y_next, e);
    return energy_created(t, h, y, y_next);
  };
  const StepAccount plastic = retake(0.0);
  const double allowed =
      std::max(plastic.created, 0.0) + std::max(first.round_off, plastic.round_off);
  if (first.created <= allowed) {
    retake(p_.restitution);
    return;
  }
  double low = 0.0, high = p_.restitution;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double middle = 0.5 * (low + high);
    (retake(middle).created <= allowed ? low : high) = middle;
  }
  retake(low);
}

// One step at restitution e; true where it closes a flank with e > 0. A DC
// motor's current over the step is implicit (elements::DcMotor::theta_step);
// where it would pass the driver's limit the step is taken again with the
// current held there.
bool DriveMoreau::take_step(double t, double h, double theta, const double* y, double* y_next,
                            double restitution) {
  const double excess = friction_excess_, play_rate = play_rate_;
  const bool restituting = take_step_held(t, h, theta, y, y_next, restitution, 0);
  const elements::DcMotor* dc = model_.dc_motor();
  if (dc == nullptr || !dc->limited()) return restituting;
  layout_.expand(t, y, q_, v_);
  if (current_state_ >= 0) dynamics_.set_motor_current(y[current_state_]);
  dynamics_.set_state(t + theta * h, q_, v_);
  const double omega_next = last_omega_next_;
  const elements::DcMotor::ThetaStep free = dc->theta_step(
      dc->voltage(t + theta * h), h, theta, dynamics_.motor_current(), v_[dc->rotor], 0);
  if (!dc->exceeds(free, omega_next)) return restituting;
  const double beyond = dc->has_state() ? free.end + free.end_slope * omega_next
                                        : free.mean + free.mean_slope * omega_next;
  friction_excess_ = excess;  // (the step is taken again)
  play_rate_ = play_rate;
  return take_step_held(t, h, theta, y, y_next, restitution, beyond > 0.0 ? 1 : -1);
}

bool DriveMoreau::take_step_held(double t, double h, double theta, const double* y,
                                 double* y_next, double restitution, int held) {
  layout_.expand(t, y, q_, v_);
  const CoordinateVector q0 = q_, v0 = v_;
  bool restituting = false;
  const elements::DcMotor* dc = model_.dc_motor();
  if (current_state_ >= 0) dynamics_.set_motor_current(y[current_state_]);
  dynamics_.set_state(t + theta * h, q_, v_);
  const double play0 = dynamics_.play();
  const double play_rate0 = dynamics_.play_rate();
  // A DC motor's current over the step, i_theta = mean + mean_slope omega+:
  // its torque's impulse h k_t i_theta in place of the start's k_t i, its
  // slope an implicit damping of the rotor.
  elements::DcMotor::ThetaStep current;
  if (dc != nullptr)
    current = dc->theta_step(dc->voltage(t + theta * h), h, theta, dynamics_.motor_current(),
                             v0[dc->rotor], held);

  // Iteration matrix and free velocity.
  Square stiffness, damping;
  assemble(h, theta, stiffness, damping,
           dc != nullptr ? -h * dc->torque(current.mean_slope) : 0.0);
  CoordinateVector rhs = model_.mass().cwiseProduct(v0) + h * dynamics_.forces() -
                         theta * (1.0 - theta) * h * h * (stiffness * v0) +
                         theta * h * (damping * v0);
  if (dc != nullptr)
    rhs[dc->rotor] += h * (dc->torque(current.mean) - dc->torque(dynamics_.motor_current()));
  free_ = solver_.solve(rhs);

  // Which thread contact is active in this step.
  int sigma_fixed = 0;  // 0: bilateral (sign free); +-1: a flank
  bool contact = true;
  double normal_target = 0.0;
  if (model_.thread_pair().exact_play()) {
    const double half = 0.5 * p_.clearance;
    const double predicted = play0 + h * play_rate0;
    if (predicted <= -half) {
      sigma_fixed = 1;
    } else if (predicted >= half) {
      sigma_fixed = -1;
    } else {
      contact = false;
    }
    // Newton's restitution where this step closes the flank (the play
    // inside the clearance at its start); a flank already closed stays so
    // (target 0), as in the event-driven scheme an impact happens once:
    // restitution at every step of a persistent contact flipped its normal
    // velocity step after step, and with friction and the springs the
    // account created energy (up to 1e3 of the work).
    const bool closing = std::abs(play0) < half;
    normal_target = closing ? -restitution * model_.normal_direction().dot(v0) : 0.0;
    restituting = contact && closing && restitution > 0.0;
  }
  const double rotor_target =
      p_.speed_controlled ? model_.motor().prescribed_speed(t + h) : 0.0;

  Impulses impulses;
  bool stick = false;
  if (contact) {
    // The flank's sign, or both (no allocation: this runs every step).
    const int sigmas[2] = {sigma_fixed != 0 ? sigma_fixed : 1, -1};
    const int sigma_count = sigma_fixed != 0 ? 1 : 2;
    const Impulses without = solve(true, normal_target, rotor_target, 0.0);
    const Impulses unit = solve(true, normal_target, rotor_target, 1.0);
    double c = model_.tangent_direction().dot(without.velocity);
    double d = model_.tangent_direction().dot(unit.velocity) - c;
    double beta = without.normal;
    double alpha = unit.normal - beta;
    // The law's viscous term, implicit: P_T = P_C - h viscous gamma+ with
    // P_C in the cone. With gamma+ = c + d P_T and the normal impulse
    // beta + alpha P_T, P_C solves the flank LCP of c, d, beta, alpha
    // scaled by s = 1 / (1 + h viscous d) (beta less alpha h viscous c s);
    // a stuck step (gamma+ = 0) has no viscous impulse.
    const friction::Law& law = dynamics_.law();
    const double viscous_step = law.viscous() * h;
    const double viscous_scale = 1.0 / (1.0 + viscous_step * d);
    const double viscous_c = c;
    if (viscous_step > 0.0) {
      beta -= alpha * viscous_step * c * viscous_scale;
      c *= viscous_scale;
      d *= viscous_scale;
      alpha *= viscous_scale;
    }
    if (model_.effective_max_mu() * std::abs(alpha) >= 1.0 && !dynamics_.painleve_possible())
      throw SimulationError(t,
                            "dt = " + format_value(h) + " s is too long for the stiffness of "
                            "this drive here: " + step_too_long(theta, alpha),
                            "use dt < " + format_value(resolving_step(h, theta)) + " s");
    int found = 0;
    friction::FlankLcpResult chosen;
    // The motor prescribes every velocity (DriveDynamics::slip_prescribed):
    // the step's slip velocity c decides, friction cannot change it.
    const double slip_noise =
        64.0 * std::numeric_limits<double>::epsilon() *
        model_.tangent_direction().cwiseProduct(without.velocity).cwiseAbs().sum();
    // One coefficient: the LCP decides stick and slip. A static one
    // above the kinetic one: stick where the impulse that sticks lies in
    // mu_static''s cone, else the LCP at the slip's coefficient at the
    // step's start speed (Stribeck's curve, explicit in the speed).
    // (In the Painleve regime the LCP may find no impulse where the stick
    // holds: a stick that is admissible is taken then too.)
    double lcp_mu = model_.effective_mu();
    const friction::FlankLcpResult stick_step =
        dynamics_.slip_prescribed()
            ? friction::FlankLcpResult{}
            : friction::flank_stick(c, d, alpha, beta, model_.effective_mu_static(), sigma_fixed);
    bool stuck = false;
    if (!law.plain_coulomb()) {
      if (stick_step.consistent) {
        chosen = stick_step;
        stuck = true;
        found = 1;
      }
      lcp_mu = law.slip_mu(std::abs(model_.tangent_direction().dot(v0))) * model_.flank_factor();
    }
    for (int k = 0; k < sigma_count && !stuck; ++k) {
      const friction::FlankLcpResult r =
          dynamics_.slip_prescribed()
              ? friction::solve_flank_prescribed_slip(
                    c, std::abs(c) <= slip_noise, alpha, beta, lcp_mu, sigmas[k],
                    without.rotor, unit.rotor - without.rotor)
              : solve_flank_lcp_scaled(c, d, alpha, beta, lcp_mu, sigmas[k], lcp_workspace_,
                                       lcp_options_);
      ++lcp_solves_;
      if (!r.consistent) continue;
      if (found == 0) chosen = r;
      ++found;
    }
    if (found == 0 && stick_step.consistent) {
      chosen = stick_step;
      found = 1;
    }
    // The viscous impulse on top of the cone's (zero where stuck).
    if (viscous_step > 0.0 && found > 0)
      chosen.friction_force = (chosen.friction_force - viscous_step * viscous_c) * viscous_scale;
    if (found == 0 && sigma_fixed != 0) {
      contact = false;  // the flank separates: no impulse on it
    } else if (found == 0) {
      throw JammingError(t, "dynamic jamming: no consistent flank impulse in the "
                            "Moreau-Jean step; " + dynamics_.jamming_report(),
                         "reduce the friction or change the inertia ratio");
    } else {
      impulses = solve(true, normal_target, rotor_target, chosen.friction_force);
      impulses.friction = chosen.friction_force;
      stick = chosen.slip_acceleration == 0.0;
    }
  }
  if (!contact) impulses = solve(false, 0.0, rotor_target, 0.0);
  v_ = impulses.velocity;
  if (model_.thread_pair().exact_play() && !contact)
    impulses.normal = 0.0, impulses.friction = 0.0;

  // Positions of the independent coordinates; the layout fills the rest.
  const CoordinateVector v_theta = (1.0 - theta) * v0 + theta * v_;
  q_ = q0 + h * v_theta;
  CoordinateVector q_positions = q_;
  layout_.compress(q_positions, v_, y_next);
  const int offset = layout_.energy_offset();
  for (int e = 0; e < kEnergyCount; ++e) y_next[offset + e] = y[offset + e];
  layout_.expand(t + h, y_next, q_, v_);
  // The event-driven scheme's root g4, for every concept: the run ends at
  // the end of the first step that takes the nut's end past the screw's
  // (checked at each step's end, so the last step's end is checked too; the
  // start is the model's checked initial position).
  const double nut_end = model_.nut_position(q_.data());
  if (!(model_.screw_end_margin(nut_end) > 0.0)) nut_left_the_screw(model_, t + h, nut_end);
  double* energy = y_next + offset;
  const double motor = p_.speed_controlled ? impulses.rotor * v_theta[model_.rotor()]
                                           : model_.motor().applied_torque(t + theta * h) *
                                                 (q_[model_.rotor()] - q0[model_.rotor()]);
  energy[kWorkDrive] += motor;
  if (dc != nullptr) {
    // The armature over the step: i_theta, i+, and the driver's voltage
    // U_d = R i_theta + k_e omega_theta + L (i+ - i) / h (U(t + theta h)
    // unless held), its electrical work and the copper loss.
    const double omega_next = v_[dc->rotor], omega_theta = v_theta[dc->rotor];
    const double i_theta = current.mean + current.mean_slope * omega_next;
    const double i0 = dynamics_.motor_current();
    const double i_next = dc->has_state() ? current.end + current.end_slope * omega_next : 0.0;
    last_voltage_ = dc->resistance * i_theta + dc->back_emf_constant * omega_theta +
                    (dc->has_state() ? dc->inductance * (i_next - i0) / h : 0.0);
    energy[kWorkDrive] += h * (last_voltage_ * i_theta +
                               (dc->torque_constant - dc->back_emf_constant) * i_theta *
                                   omega_theta);
    y_next[copper_state_] = y[copper_state_] + h * dc->copper_loss_rate(i_theta);
    if (dc->has_state()) y_next[current_state_] = i_next;
    last_omega_next_ = omega_next;
  }
  energy[kWorkAxial] +=
      p_.axial_force(t + theta * h) * (q_[model_.load()] - q0[model_.load()]);
  const double slip = model_.tangent_direction().dot(v_);
  // A sticking step (the LCP's stick basis) ends at zero slip exactly; its
  // computed slip is the round-off of terms of h f / m (1e-17 m/s against
  // 4 m/s of a stuck drive's step), which would book a round-off loss of
  // either sign.
  if (!(contact && stick)) {
    energy[kFrictionLoss] += -impulses.friction * slip;
    // (ResultCheckSpec::step_friction_excess)
    const double slip0 = model_.tangent_direction().dot(v0);
    friction_excess_ += std::max(0.0, -(1.0 - theta) * impulses.friction * (slip - slip0));
  }
  play_rate_ = std::max({play_rate_, std::abs(play_rate0),
                         std::abs(model_.play_gradient().dot(v_))});
  double damping_power = 0.0;
  model_.elements().forces.for_each(
      [&](const auto& element) { damping_power += element.damping_power(v_theta); });
  energy[kDampingLoss] += h * damping_power;
  last_.normal = impulses.normal / h;
  last_.friction = impulses.friction / h;
  last_.motor_torque =
      p_.speed_controlled ? impulses.rotor / h : model_.motor().applied_torque(t + h);
  if (dc != nullptr)
    last_.motor_torque = dc->torque(dc->has_state() ? y_next[current_state_]
                                                     : current.mean +
                                                           current.mean_slope * v_[dc->rotor]);
  last_.motor_torque = model_.gear().rotor_torque(last_.motor_torque);
  last_.stick = contact && stick;
  return restituting;
}

// The energy a step from y to y_next creates (StepAccount).
DriveMoreau::StepAccount DriveMoreau::energy_created(double t, double h, const double* y,
                                                      const double* y_next) {
  double largest = 0.0;
  const elements::DcMotor* dc = model_.dc_motor();
  auto account = [&](double time, const double* state) {
    layout_.expand(time, state, q_, v_);
    if (current_state_ >= 0) dynamics_.set_motor_current(state[current_state_]);
    dynamics_.set_state(time, q_, v_);
    const double* energy = state + layout_.energy_offset();
    double stored = dynamics_.kinetic_energy() + dynamics_.elastic_energy();
    if (dc != nullptr)  // the magnetic energy, and the copper loss among the losses
      stored += dc->magnetic_energy(dc->has_state() ? dynamics_.motor_current() : 0.0) +
                state[copper_state_];
    double balance = stored;
    largest = std::max(largest, std::abs(stored));
    for (int e = 0; e < kEnergyCount; ++e) {
      balance += (e == kWorkDrive || e == kWorkAxial) ? -energy[e] : energy[e];
      largest = std::max(largest, std::abs(energy[e]));
    }
    return balance;
  };
  const double before = account(t, y);
  const double after = account(t + h, y_next);
  return {after - before, 64.0 * std::numeric_limits<double>::epsilon() * largest};
}

void DriveMoreau::channels(double t, const double* y, double* out) {
  layout_.expand(t, y, q_, v_);
  if (current_state_ >= 0) dynamics_.set_motor_current(y[current_state_]);
  dynamics_.set_state(t, q_, v_);
  const double* energy = y + layout_.energy_offset();
  // The Moreau-Jean scheme's numerical dissipation (and impacts) closes the
  // account: what the work and the named losses leave over.
  ChannelState state = channel_state(dynamics_);
  if (last_.stick) state.slip_velocity = 0.0;  // the step's stick: zero slip (as above)
  if (const elements::DcMotor* dc = model_.dc_motor()) {  // its channels (hybrid_motor.cpp)
    double* values = state.values.data() + dc_channel_;
    values[0] = dynamics_.motor_current();
    values[1] = last_voltage_;  // over the last step
    values[2] = y[copper_state_];
    values[3] = dc->has_state() ? dc->magnetic_energy(values[0]) : 0.0;
  }
  write_drive_channels(layout_, state, last_, energy, 0.0, kinetic0_,
                       elastic0_, out);
}

// The iteration matrix W = M + theta h C + theta^2 h^2 K at the positions
// q_ (factored into solver_), and its stiffness and damping matrices.
void DriveMoreau::assemble(double h, double theta, Square& stiffness, Square& damping,
                           double rotor_damping) {
  const int n = model_.coordinate_count();
  stiffness = Square::Zero(n, n);
  damping = Square::Zero(n, n);
  const double a = model_.nut_position(q_.data());
  model_.elements().forces.for_each([&](const auto& element) {
    element.add_stiffness(stiffness, a);
    element.add_damping(damping);
  });
  Square iteration = theta * h * damping + theta * theta * h * h * stiffness;
  iteration.diagonal() += model_.mass();
  iteration(model_.rotor(), model_.rotor()) += rotor_damping;
  solver_.compute(iteration);
}

// The step's coupling of the flank's friction impulse into its normal
// impulse, alpha = dP_N / dP_T, at the positions q_: W^-1 in place of
// M^-1 in the Delassus terms, alpha = -G~_NT / G~_NN (the rotor held
// where speed-controlled). For h -> 0 it is the drive's own.
double DriveMoreau::step_coupling(double h, double theta) {
  Square stiffness, damping;
  assemble(h, theta, stiffness, damping);
  free_ = CoordinateVector::Zero(model_.coordinate_count());
  return solve(true, 0.0, 0.0, 1.0).normal - solve(true, 0.0, 0.0, 0.0).normal;
}

// A Moreau-Jean step whose flank problem has mu' |alpha| >= 1 has the
// Painleve paradox's structure although the drive has not (mu' |G_NT| <
// G_NN): the springs' stiffness in W (theta^2 h^2 K) dominates the masses
// and turns the flank's friction into a lever on its own normal impulse.
// No consistent impulse, or a spurious one, follows: a jam of the time
// discretization, not of the drive (dt 7e-4 s "jammed" a flexible nut at
// rest that dt 3e-4 s and the event-driven scheme run).
std::string DriveMoreau::step_too_long(double theta, double alpha) {
  return "in the Moreau-Jean step (iteration matrix W = M + theta h C + theta^2 h^2 K, "
         "theta = " + format_value(theta) + ") the flank's "
         "friction impulse drives its own normal impulse, mu' |G~_NT| / G~_NN = " +
         format_value(model_.effective_mu() * std::abs(alpha)) +
         " >= 1, a jam of the time discretization that the drive does not have (mu' |G_NT| "
         "/ G_NN = " +
         format_value(model_.effective_mu() * std::abs(dynamics_.coupling())) +
         " with the masses alone)";
}

// The longest step up to h whose flank coupling stays below 1 / mu' at q_
// (bisection; the coupling falls to the drive's own as h -> 0).
double DriveMoreau::resolving_step(double h, double theta) {
  const CoordinateVector free = free_;
  double low = 0.0, high = h;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double middle = 0.5 * (low + high);
    (model_.effective_mu() * std::abs(step_coupling(middle, theta)) < 1.0 ? low : high) = middle;
  }
  free_ = free;
  return low;
}

void DriveMoreau::check_step(double h, double theta) {
  if (dynamics_.painleve_possible()) return;  // the drive's own condition decides
  const double alpha = step_coupling(h, theta);
  if (model_.effective_mu() * std::abs(alpha) >= 1.0)
    throw InvalidArgument("dt = " + format_value(h) + " is invalid: must be < " +
                          format_value(resolving_step(h, theta)) +
                          " s for the stiffness of this drive: " +
                          step_too_long(theta, alpha));
}

// v+ = free + W^-1 (B lambda + tangential W_T) with the active velocity
// constraints: W_N v+ = normal_target (thread), e_rotor v+ = rotor_target.
DriveMoreau::Impulses DriveMoreau::solve(bool thread, double normal_target, double rotor_target,
                                         double tangential) {
  const int n = model_.coordinate_count();
  const int nc = (thread ? 1 : 0) + (p_.speed_controlled ? 1 : 0);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates, 2> B =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates, 2>::Zero(n, nc);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2, 1> r(nc);
  int row = 0;
  if (thread) {
    B.col(row) = model_.normal_direction();
    r[row++] = normal_target;
  }
  if (p_.speed_controlled) {
    B(model_.rotor(), row) = 1.0;
    r[row++] = rotor_target;
  }
  Impulses out;
  CoordinateVector base = free_;
  if (tangential != 0.0) {
    const CoordinateVector shift = solver_.solve(CoordinateVector(model_.tangent_direction()));
    base += tangential * shift;
  }
  if (nc == 0) {
    out.velocity = base;
    return out;
  }
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates, 2> weighted =
      solver_.solve(B);
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 2, 2> schur =
      B.transpose() * weighted;
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2, 1> lambda =
      schur.fullPivLu().solve(r - B.transpose() * base);
  out.velocity = base + weighted * lambda;
  row = 0;
  if (thread) out.normal = lambda[row++];
  if (p_.speed_controlled) out.rotor = lambda[row++];
  return out;
}

}  // namespace leadscrew::model::drive
