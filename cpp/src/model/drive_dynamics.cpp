#include "leadscrew/model/drive_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/model/drive_geometry.hpp"

namespace leadscrew::model {

namespace {

// A normal power of two 2^k (-1022 <= k <= 1023), from its bits.
double power_of_two(int k) noexcept {
  const std::uint64_t bits = static_cast<std::uint64_t>(k + 1023) << 52;
  double value = 0.0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// frexp's exponent of a normal positive x (x = m 2^exponent, 1/2 <= m < 1)
// from its bits, and 2^-exponent, 2^exponent; false where x is subnormal or
// either power is not normal (then frexp and ldexp).
bool binary_scale(double x, int& exponent, double& down, double& up) noexcept {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased == 0 || biased == 0x7ff) return false;
  exponent = biased - 1022;
  if (exponent < -1022 || exponent > 1022) return false;
  down = power_of_two(-exponent);
  up = power_of_two(exponent);
  return true;
}

using ConstraintMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConstraints, kMaxCoordinates>;
using ColumnMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates, kMaxConstraints>;
using SmallMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConstraints, kMaxConstraints>;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxConstraints, 1>;

// Solves M x = f + B lambda, C x = r for x and lambda (M diagonal, given as
// its inverse). Returns false if C M^-1 B is singular.
bool solve_constrained(const CoordinateVector& inverse_mass, const CoordinateVector& f,
                       const ColumnMatrix& B, const ConstraintMatrix& C, const SmallVector& r,
                       CoordinateVector& x, SmallVector& lambda) {
  const int nc = static_cast<int>(r.size());
  const int n = static_cast<int>(f.size());
  if (nc == 0) {
    x = inverse_mass.cwiseProduct(f);
    lambda.resize(0);
    return true;
  }
  if (nc == n && r.isZero(0.0)) {
    // The constraints lock every coordinate (the rigid drive in stick): the
    // motion is exactly zero, and the multipliers balance the forces,
    // B lambda = -f. Solving the Schur complement instead would leave
    // round-off accelerations that let a stuck drive creep.
    Eigen::FullPivLU<SmallMatrix> lu(B);
    if (!lu.isInvertible()) return false;
    lambda = lu.solve(SmallVector(-f));
    x.setZero(n);
    return lambda.allFinite();
  }
  ColumnMatrix weighted = inverse_mass.asDiagonal() * B;
  if (nc == 1) {  // one constraint: the Schur complement is a number
    const double schur = C.row(0).dot(weighted.col(0));
    if (schur == 0.0) return false;
    lambda.resize(1);
    lambda[0] = (r[0] - C.row(0).dot(inverse_mass.cwiseProduct(f))) / schur;
    x = inverse_mass.cwiseProduct(f) + weighted.col(0) * lambda[0];
    return std::isfinite(lambda[0]) && x.allFinite();
  }
  SmallMatrix schur = C * weighted;
  SmallVector rhs = r - C * inverse_mass.cwiseProduct(f);
  if (nc == 2) {  // Cramer's rule, with the same singularity test as the LU
    const double det = schur(0, 0) * schur(1, 1) - schur(0, 1) * schur(1, 0);
    const double scale = schur.cwiseAbs().maxCoeff();
    if (!(std::abs(det) > 1e-14 * scale * scale)) return false;
    lambda.resize(2);
    lambda[0] = (rhs[0] * schur(1, 1) - schur(0, 1) * rhs[1]) / det;
    lambda[1] = (schur(0, 0) * rhs[1] - schur(1, 0) * rhs[0]) / det;
  } else {
    Eigen::FullPivLU<SmallMatrix> lu(schur);
    if (!lu.isInvertible()) return false;
    lambda = lu.solve(rhs);
  }
  x = inverse_mass.cwiseProduct(f) + weighted * lambda;
  return x.allFinite() && lambda.allFinite();
}

}  // namespace

friction::FlankLcpResult solve_flank_lcp_scaled(double c, double d, double alpha, double beta,
                                                double mu, int sigma, lcp::Workspace& workspace,
                                                const lcp::Options& options) {
  // Force scale: the normal force, and the friction force that would stop
  // the slip acceleration c.
  const double scale = std::max(std::abs(beta), d != 0.0 ? std::abs(c / d) : std::abs(c));
  if (!(scale > 0.0) || !std::isfinite(scale))
    return friction::solve_flank_lcp(c, d, alpha, beta, mu, sigma, workspace, options);
  int exponent = 0;
  double down = 0.0, up = 0.0;  // 2^-exponent, 2^exponent
  if (binary_scale(scale, exponent, down, up)) {
    // (a product with a normal power of two rounds once, as ldexp: the
    // same bits, without five library calls on every LCP)
    friction::FlankLcpResult r = friction::solve_flank_lcp(c * down, d, alpha, beta * down, mu,
                                                           sigma, workspace, options);
    r.friction_force *= up;
    r.normal_force *= up;
    r.slip_acceleration *= up;
    return r;
  }
  std::frexp(scale, &exponent);
  friction::FlankLcpResult r = friction::solve_flank_lcp(
      std::ldexp(c, -exponent), d, alpha, std::ldexp(beta, -exponent), mu, sigma, workspace,
      options);
  r.friction_force = std::ldexp(r.friction_force, exponent);
  r.normal_force = std::ldexp(r.normal_force, exponent);
  r.slip_acceleration = std::ldexp(r.slip_acceleration, exponent);
  return r;
}

DriveDynamics::DriveDynamics(const DriveModel& model, const friction::Law* law)
    : model_(model),
      law_(law ? law : &model.law()),
      plain_coulomb_(law_->plain_coulomb()),
      one_slip_mu_(law_->resolution() == friction::Resolution::set_valued &&
                   law_->viscous() == 0.0 && law_->slip_mu(0.0) == law_->mu() &&
                   law_->slip_mu(1.0) == law_->mu()) {
  if (has_transverse_slip(model.parameters()))
    transverse_ = &model.parameters().transverse_slip_velocity;
  const int n = model.coordinate_count();
  if (n > kMaxCoordinates) throw InvalidArgument("a drive model has at most 6 coordinates");
  q_ = CoordinateVector::Zero(n);
  v_ = CoordinateVector::Zero(n);
  forces_ = CoordinateVector::Zero(n);
  element_forces_ = CoordinateVector::Zero(n);
  element_slots_.assign(model.elements().elements.size(), ElementSlot{});
  element_modes_.assign(model.elements().elements.size(), ElementMode{});
  inverse_mass_ = model.mass().cwiseInverse();
  // Effective Delassus terms of the flank, with the speed-controlled rotor held.
  const Eigen::VectorXd& normal = model.normal_direction();
  const Eigen::VectorXd& tangent = model.tangent_direction();
  const Eigen::VectorXd w_n = inverse_mass_.cwiseProduct(normal);
  const Eigen::VectorXd w_t = inverse_mass_.cwiseProduct(tangent);
  delassus_nn_ = normal.dot(w_n);
  delassus_nt_ = normal.dot(w_t);
  if (model.motor().speed_controlled) {
    const int r = model.rotor();
    delassus_nn_ -= w_n[r] * w_n[r] / inverse_mass_[r];
    delassus_nt_ -= w_n[r] * w_t[r] / inverse_mass_[r];
  }
  // (with the largest coefficient the law reaches: a static one above mu)
  painleve_possible_ =
      law_->max_mu() * model.flank_factor() * std::abs(delassus_nt_) >= delassus_nn_;
  if (model.motor().speed_controlled) {
    // The slip's response to a tangential force with the flank and the rotor
    // held: W_T . x with M x = W_T + B lambda, C x = 0. Zero (to round-off of
    // the unconstrained W_T M^-1 W_T) when those constraints fix every velocity.
    const int n = model.coordinate_count();
    ColumnMatrix B = ColumnMatrix::Zero(n, 2);
    B.col(0) = normal;
    B(model.rotor(), 1) = 1.0;
    const ConstraintMatrix C = B.transpose();
    CoordinateVector x;
    SmallVector lambda;
    const CoordinateVector force = tangent;
    if (solve_constrained(inverse_mass_, force, B, C, SmallVector::Zero(2), x, lambda))
      slip_prescribed_ = std::abs(tangent.dot(x)) <= 1e-12 * tangent.dot(w_t);
  }
}

double DriveDynamics::element_energy_terms() const {
  double sum = 0.0;
  const std::vector<std::shared_ptr<const Element>>& elements = model_.elements().elements;
  for (std::size_t k = 0; k < elements.size(); ++k)
    sum += elements[k]->energy_terms(element_state(k));
  return sum;
}

void DriveDynamics::set_element_slots(const std::vector<std::pair<int, int>>& slots) {
  int offset = 0;
  for (std::size_t k = 0; k < element_slots_.size() && k < slots.size(); ++k) {
    const int count = slots[k].first >= 0 ? slots[k].second : 0;
    if (offset + count > kMaxElementStates)
      throw std::logic_error("the drive's elements declare more than kMaxElementStates states");
    element_slots_[k] = {slots[k].first, count, offset};
    offset += count;
  }
}

void DriveDynamics::add_element_forces(int rotor) {
  const std::vector<std::shared_ptr<const Element>>& elements = model_.elements().elements;
  element_forces_.setZero();
  CoordinateVector own(element_forces_.size());
  for (std::size_t k = 0; k < elements.size(); ++k) {
    own.setZero();
    elements[k]->add_forces(element_state(k), element_modes_[k], own.data());
    if (elements[k]->drives_rotor()) {
      element_drive_torque_ += own[rotor];
      own[rotor] = 0.0;
    }
    element_forces_ += own;
  }
}

void DriveDynamics::set_state(double t, const CoordinateVector& q, const CoordinateVector& v) {
  const elements::ThreadPair& thread = model_.thread_pair();
  const elements::Motor& motor = model_.motor();
  t_ = t;
  q_ = q;
  v_ = v;
  if (transverse_) transverse_slip_ = (*transverse_)(t);
  forces_.setZero();
  elastic_ = 0.0;
  damping_power_ = 0.0;

  const double a = thread.nut_position(q.data());
  // Either drive: the nut is a point of the screw in (0, L) (the scene checks
  // the initial position alike); beyond an end it is off the screw.
  if (model_.springs_on_screw() && !(a > 0.0 && a < model_.parameters().screw_length)) {
    throw NutOffScrew(t, model_.nut_off_screw(a), DriveModel::kNutOffScrewHint);
  }
  // The elements' forces, grouped by type: the force elements (springs,
  // dampers and supports), the motor's torque, the axial load.
  model_.elements().forces.for_each([&](const auto& element) {
    element.add_forces(q, v, a, thread.nut_position_gradient(), forces_, elastic_, damping_power_);
  });
  applied_torque_ = motor.applied_torque(t);
  // The model's elements' forces at their states (model/element.hpp): a
  // motor's on the rotor is the drive's torque; the others' (a base
  // excitation's -a m_u - alpha J_phi) join after the loads.
  const std::vector<std::shared_ptr<const Element>>& elements = model_.elements().elements;
  element_drive_torque_ = 0.0;
  if (!elements.empty()) {
    add_element_forces(motor.rotor);
    applied_torque_ += element_drive_torque_;
  }
  axial_force_ = model_.axial_load().force_at(t);
  forces_[motor.rotor] += applied_torque_;
  forces_[model_.axial_load().coordinate] += axial_force_;
  if (!elements.empty()) forces_ += element_forces_;
  // A prescribed speed's derivative is taken when a mode is solved (solve):
  // Moreau-Jean sets states but never needs it, and takes a step of the
  // speed as an impulse, where a differentiating scheme cannot follow one.
  rotor_acceleration_ = motor.speed_controlled ? std::numeric_limits<double>::quiet_NaN() : 0.0;

  // The thread pair: its kinematics and its penalty flanks' force.
  play_ = thread.play(q);
  play_rate_ = thread.play_gradient().dot(v);
  slip_ = thread.tangent().dot(v);
  slip_noise_ = 64.0 * std::numeric_limits<double>::epsilon() *
                thread.tangent().cwiseProduct(v).cwiseAbs().sum();
  thread.penalty_force(play_, play_rate_, penalty_);
  // A preloaded nut's lift-off spring (elements/preloaded_nut.hpp).
  if (const elements::PreloadedNut* nut = model_.preloaded_nut(); nut && nut->lift_off)
    preload_spring_ = nut->spring_force(play_);
}

double DriveDynamics::contact_energy() const noexcept {
  double energy = model_.thread_pair().contact_energy(penalty_.penetration);
  // A lift-off nut's spring S^2 / (2 k_p) (elements/preloaded_nut.hpp).
  if (const elements::PreloadedNut* nut = model_.preloaded_nut(); nut && nut->lift_off)
    energy += nut->spring_energy(play_);
  return energy;
}

double DriveDynamics::kinetic_energy() const {
  return 0.5 * v_.dot(model_.mass().cwiseProduct(v_));
}

double DriveDynamics::friction_factor(const ModeSpec& spec, double slip_acceleration) const {
  const double factor = model_.flank_factor();
  switch (spec.friction) {
    case FrictionMode::slip:
      // mu' itself for one coefficient (the same bits as before the laws
      // were types); Stribeck's curve at the slip speed otherwise.
      return spec.slip_sign * (plain_coulomb_ ? model_.effective_mu()
                                                     : law_->slip_mu(std::abs(slip_)) * factor);
    case FrictionMode::regularized_velocity:
      if (transverse_)
        return cone_coefficient(slip_, transverse_slip_,
                                cone_mu(std::hypot(slip_, transverse_slip_)));
      return law_->velocity_coefficient(slip_) * factor;
    case FrictionMode::regularized_acceleration:
      return law_->acceleration_coefficient(slip_acceleration) * factor;
    case FrictionMode::bristle:
      return law_->bristle_coefficient(slip_, bristle_) * factor;
    default:
      return 0.0;
  }
}

ModeSolution DriveDynamics::solve(const ModeSpec& spec) {
  const elements::Motor& motor = model_.motor();
  const int n = model_.coordinate_count();
  const Eigen::VectorXd& normal = model_.normal_direction();
  const Eigen::VectorXd& tangent = model_.tangent_direction();
  const bool normal_multiplier =
      spec.contact == ThreadContact::bilateral || spec.contact == ThreadContact::closed;
  const bool stick = spec.friction == FrictionMode::stick;

  // The law's viscous term, a force -viscous gamma along the helix where the
  // flank is in contact and not stuck.
  const bool in_contact =
      normal_multiplier || (spec.contact == ThreadContact::penalty && penalty_.normal_force != 0.0);
  const double viscous = in_contact && !stick && spec.friction != FrictionMode::none
                             ? -law_->viscous() * slip_
                             : 0.0;
  // A preloaded nut slipping: its preload half is a given flank force (N_B^s,
  // T_B^s) of the slip's direction, the multiplier half A's normal force.
  const elements::PreloadedNut* nut = model_.preloaded_nut();
  // Half B at the law's coefficient kappa' (a smooth law, or Stribeck's
  // curve in slip): its given force N_B(kappa') W_N + T_B(kappa') W_T.
  const bool kappa_half = nut && preload_at_kappa(spec);
  const bool preload_half =
      nut && normal_multiplier && spec.friction == FrictionMode::slip && !kappa_half;
  const bool smooth_half = kappa_half && normal_multiplier;
  double half_b_kappa = kappa_half ? half_b_coefficient(*nut, spec) : 0.0;  // (eq. 3.15: below)
  // A lift-off nut on penalty flanks: half B a given force in every mode,
  // the spring's along grad(e) (its slip force in slip).
  const bool lift_off_half = nut && nut->lift_off && spec.contact == ThreadContact::penalty;
  const bool lift_off_slip = lift_off_half && spec.friction == FrictionMode::slip && !kappa_half;
  // (at half_b_kappa when evaluated: eq. (3.15)'s moves, below)
  double lift_off_normal = 0.0, lift_off_friction = 0.0;
  auto lift_off_forces = [&] {
    lift_off_normal = !lift_off_half  ? 0.0
                      : kappa_half    ? nut->normal_at(half_b_kappa, preload_spring_)
                      : lift_off_slip ? nut->normal(spec.slip_sign, preload_spring_)
                                      : nut->side * preload_spring_ / nut->cos_lead;
    lift_off_friction = !lift_off_half  ? 0.0
                        : kappa_half    ? nut->friction_at(half_b_kappa, preload_spring_)
                        : lift_off_slip ? nut->split_friction(spec.slip_sign, preload_spring_)
                                        : 0.0;
  };
  lift_off_forces();
  // The rotor's friction contact (ModeSpec::rotor): a row of its own where
  // it fixes the rotor's acceleration, else eliminated into the rotor's
  // inverse mass and force (a self-locking stage back-driven: negative).
  const int rotor = model_.rotor();
  const bool rotor_fixed = spec.rotor.active && spec.rotor.a_q == 0.0;
  const bool rotor_eliminated = spec.rotor.active && spec.rotor.a_q != 0.0;
  CoordinateVector inverse_mass = inverse_mass_;
  if (rotor_eliminated) {
    const double effective = spec.rotor.a_q / inverse_mass_[rotor] - spec.rotor.a_w;
    if (!(std::abs(effective) > 1e-12 * std::abs(spec.rotor.a_q / inverse_mass_[rotor]))) {
      ModeSolution singular;
      singular.regular = false;  // (the stage's Painleve case, k J_s + R = 0)
      return singular;
    }
    inverse_mass[rotor] = spec.rotor.a_q / effective;
  }
  auto evaluate = [&](double kappa, double given_tangential, ModeSolution& out) {
    CoordinateVector f = forces_;
    if (rotor_eliminated) f[rotor] -= spec.rotor.r / spec.rotor.a_q;
    f += (given_tangential + viscous) * tangent;
    if (preload_half)
      f += nut->normal(spec.slip_sign) * normal + nut->friction(spec.slip_sign) * tangent;
    if (smooth_half)
      f += nut->normal_at(half_b_kappa, nut->preload) * normal +
           nut->friction_at(half_b_kappa, nut->preload) * tangent;
    if (lift_off_half) f += lift_off_normal * normal + lift_off_friction * tangent;
    double normal_force = 0.0;
    if (spec.contact == ThreadContact::penalty) {
      normal_force = penalty_.normal_force;
      f += normal_force * normal;
      if (!stick) f -= kappa * std::abs(normal_force) * tangent;
    }
    const int nc = (normal_multiplier ? 1 : 0) + (stick ? 1 : 0) + motor.constraint_count() +
                   (spec.held_load >= 0 ? 1 : 0) + (rotor_fixed ? 1 : 0);
    ColumnMatrix B = ColumnMatrix::Zero(n, nc);
    ConstraintMatrix C = ConstraintMatrix::Zero(nc, n);
    SmallVector r = SmallVector::Zero(nc);
    int row = 0, normal_row = -1, stick_row = -1, rotor_row = -1;
    if (normal_multiplier) {
      normal_row = row++;
      B.col(normal_row) = normal - spec.sigma * kappa * tangent;
      C.row(normal_row) = normal.transpose();
    }
    if (stick) {
      stick_row = row++;
      B.col(stick_row) = tangent;
      C.row(stick_row) = tangent.transpose();
    }
    if (motor.speed_controlled) {
      rotor_row = row++;
      B(motor.rotor, rotor_row) = 1.0;
      C(rotor_row, motor.rotor) = 1.0;
      if (std::isnan(rotor_acceleration_)) rotor_acceleration_ = motor.prescribed_acceleration(t_);
      r[rotor_row] = rotor_acceleration_;
    }
    int stop_row = -1;
    if (spec.held_load >= 0) {
      stop_row = row++;
      B(spec.held_load, stop_row) = 1.0;
      C(stop_row, spec.held_load) = 1.0;
    }
    int friction_row = -1;
    if (rotor_fixed) {
      friction_row = row++;
      B(rotor, friction_row) = -1.0;
      C(friction_row, rotor) = spec.rotor.a_w;
      r[friction_row] = spec.rotor.r;
    }
    SmallVector lambda;
    out.regular = solve_constrained(inverse_mass, f, B, C, r, out.acceleration, lambda);
    if (!out.regular) return;
    if (normal_multiplier) normal_force = lambda[normal_row];
    out.normal_force = normal_force;
    if (stick)
      out.friction_force = lambda[stick_row];
    else if (normal_multiplier)
      out.friction_force = -kappa * spec.sigma * normal_force;
    else if (spec.contact == ThreadContact::penalty)
      out.friction_force = -kappa * std::abs(normal_force);
    else
      out.friction_force = 0.0;
    out.friction_force += given_tangential + viscous;
    if (preload_half) {
      out.preload_normal = nut->normal(spec.slip_sign);
      out.normal_force += out.preload_normal;
      out.friction_force += nut->friction(spec.slip_sign);
    }
    if (smooth_half) {
      out.preload_normal = nut->normal_at(half_b_kappa, nut->preload);
      out.preload_friction = nut->friction_at(half_b_kappa, nut->preload);
      out.normal_force += out.preload_normal;
      out.friction_force += out.preload_friction;
    }
    if (lift_off_half) {
      out.preload_normal = lift_off_normal;
      if (kappa_half) out.preload_friction = lift_off_friction;
      out.normal_force += lift_off_normal;
      out.friction_force += lift_off_friction;
    }
    out.motor_torque = motor.speed_controlled ? lambda[rotor_row] : applied_torque_;
    out.stop_force = stop_row >= 0 ? lambda[stop_row] : 0.0;
    out.rotor_friction =
        rotor_fixed ? lambda[friction_row]
        : rotor_eliminated
            ? (spec.rotor.r - spec.rotor.a_w * out.acceleration[rotor]) / spec.rotor.a_q
            : 0.0;
    out.slip_acceleration = tangent.dot(out.acceleration);
  };

  ModeSolution solution;
  // A closed exact stop whose row and the thread's fix every velocity (the
  // rigid drive without play, or with its flank closed): the thread's
  // friction and the stop's force are one unknown too many. The rule
  // (docs/physics/end_stops.md, "The rigid drive at a closed stop"): the
  // stop carries what it can, the friction nothing while it holds; the
  // stop opens where its force would pull, and the thread decides then.
  if (spec.held_load >= 0 && normal_multiplier && spec.friction != FrictionMode::none &&
      2 + motor.constraint_count() >= n) {
    ModeSpec base = spec;
    base.friction = FrictionMode::none;
    base.given_tangential = 0.0;
    return solve(base);
  }
  if (stick && slip_prescribed_ && normal_multiplier) {
    // The stick row would repeat the others (every velocity is fixed): the
    // friction force is statically indeterminate, chosen as
    // prescribed_slip_decision does.
    ModeSpec base = spec;
    base.friction = FrictionMode::none;
    const friction::FlankLcpResult decision = prescribed_slip_decision(
        base, spec.contact == ThreadContact::closed ? spec.sigma : 0);
    base.given_tangential = decision.friction_force;
    solution = solve(base);
    if (nut) solution.preload_normal = nut->normal(nut->edge_of(solution.friction_force));
    return solution;
  }
  if ((smooth_half || (lift_off_half && kappa_half)) &&
      spec.friction == FrictionMode::regularized_acceleration) {
    // Eq. (3.15) on a preloaded nut's halves (preloaded_acceleration_law):
    // the mode at a given coefficient kappa', its slip acceleration.
    auto at = [&](double kappa) {
      half_b_kappa = kappa;
      lift_off_forces();
      evaluate(kappa, spec.given_tangential, solution);
      return solution.regular ? solution.slip_acceleration
                              : std::numeric_limits<double>::quiet_NaN();
    };
    at(preloaded_acceleration_law(spec, smooth_half, at));
    return solution;
  }
  if (spec.friction == FrictionMode::regularized_acceleration &&
      spec.contact == ThreadContact::bilateral && painleve_possible_)
    return solve_acceleration_law(spec);
  if (spec.friction != FrictionMode::regularized_acceleration ||
      spec.contact == ThreadContact::open) {
    evaluate(friction_factor(spec, 0.0), spec.given_tangential, solution);
    // In stick the multipliers are the net forces; half B at the edge the
    // friction force heads for (its preload_normal, for the sign of half A's).
    if (nut && stick && normal_multiplier && solution.regular)
      solution.preload_normal = nut->normal(nut->edge_of(solution.friction_force));
    return solution;
  }
  // Eq. (3.15) on the flank: kappa depends on the slip acceleration it
  // produces. With the friction force T as the unknown (the law's kappa set
  // to 0 and T given), the solution is affine in T: normal force N_0 +
  // alpha T, slip acceleration x_0 + d T, accelerations a_0 + T (a_1 - a_0).
  // The law T = -kappa(x) m with m = sigma N (a flank's multiplier) or |N|
  // (a penalty flank's given force) is one smooth scalar equation
  //   Phi(T) = T + kappa(x_0 + d T) m(T) = 0,
  // solved by Newton to round-off, safeguarded by bisection on a bracket:
  // |T| = |kappa| m < mu' (|N_0| + |alpha| |T|) bounds it by
  // mu' |N_0| / (1 - mu' |alpha|). (An Illinois iteration on x that the
  // rhs ran before stopped at 4e-16 of the bracket's slip accelerations,
  // 1e-7 relative to a small root: CVODE's difference-quotient Jacobian of
  // that noise failed Newton at every step, 225,000 failures in 0.2 s.)
  ModeSolution zero, unit;
  evaluate(0.0, spec.given_tangential, zero);
  evaluate(0.0, spec.given_tangential + 1.0, unit);
  if (!zero.regular || !unit.regular) {
    solution.regular = false;
    return solution;
  }
  const double mu = model_.effective_mu();
  const bool penalty = spec.contact == ThreadContact::penalty;
  const double n0 = zero.normal_force, alpha = unit.normal_force - n0;
  const double x0 = zero.slip_acceleration, d = unit.slip_acceleration - x0;
  const double k_v = law_->gain();
  auto multiplier = [&](double T) { return penalty ? std::abs(n0) : spec.sigma * (n0 + alpha * T); };
  auto phi = [&](double T) {
    return T + kTwoOverPi * mu * std::atan(k_v * (x0 + d * T)) * multiplier(T);
  };
  if (!(mu * std::abs(alpha) < 1.0) || !(d >= 0.0))
    throw SimulationError(t_, "eq. (3.15) has no unique friction force here (mu' |dN/dT| = " +
                                  format_value(mu * std::abs(alpha)) + ")",
                          "lower friction.mu or use arctan_velocity");
  const double bound = mu * std::abs(n0) / (1.0 - mu * std::abs(alpha));
  double low = -bound, high = bound, T = 0.0;
  double value = phi(T);
  for (int iteration = 0; iteration < 200 && value != 0.0; ++iteration) {
    (value < 0.0 ? low : high) = T;
    const double x = x0 + d * T;
    const double u = k_v * x;
    const double slope = 1.0 + kTwoOverPi * mu *
                                   (k_v * d / (1.0 + u * u) * multiplier(T) +
                                    std::atan(u) * (penalty ? 0.0 : spec.sigma * alpha));
    double next = slope > 0.0 ? T - value / slope : 0.5 * (low + high);
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (std::abs(next - T) <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(T) ||
        high - low <= 4.0 * std::numeric_limits<double>::epsilon() * bound) {
      T = next;
      break;
    }
    T = next;
    value = phi(T);
  }
  solution = zero;
  solution.acceleration = zero.acceleration + T * (unit.acceleration - zero.acceleration);
  solution.normal_force = n0 + alpha * T;
  solution.friction_force = zero.friction_force + T;
  solution.motor_torque = zero.motor_torque + T * (unit.motor_torque - zero.motor_torque);
  solution.slip_acceleration = x0 + d * T;
  return solution;
}

// Eq. (3.15) on the thread without play, every consistent solution. With
// the friction force T as the unknown, the normal force and the slip
// acceleration are affine in it (every other constraint enforced):
// N = N_0 + alpha T, x = x_0 + d T (d > 0), and the law with the normal
// force's sign sigma = sign N consistent by construction is
//   Phi(T) = T + kappa(x) |N| = 0,   kappa(x) = (2/pi) mu' atan(k_V x).
// Phi runs from -inf to +inf (|kappa| < mu' and kappa takes the sign of T for
// large |T|), so a solution always exists: the law never jams for lack of a
// consistent sign, unlike exact Coulomb in slip. Phi' = 1 + kappa' d |N| +
// kappa sigma alpha > 0 when mu' |alpha| = mu' |G_NT| / G_NN < 1, so the
// solution is unique outside the Painleve regime (the general solve above
// handles that case). Inside it several solutions can coexist: the friction
// factor of one slip acceleration cancels the inertia the normal force sees
// (|kappa| > G_NN / |G_NT| somewhere between them). All of them are found on
// the compact interval u = atan(k_V x) in (-pi/2, pi/2), where
//   H(u) = cos(u) Phi = C cos u + D sin u + (2/pi) mu' u |A cos u + B sin u|
// (C = -x_0 / d, D = 1 / (d k_V), A = N_0 - alpha x_0 / d, B = alpha / (d k_V))
// has H(-pi/2) < 0 < H(pi/2) and |H''| <= hypot(C, D) + (2/pi) mu' hypot(A, B)
// (2 + pi/2) between the kink of |N|: a scan with certified steps (no sign
// change passed unseen; a double root narrower than 1e-12 is taken for a
// touch) and Illinois at every sign change.
ModeSolution DriveDynamics::solve_acceleration_law(const ModeSpec& spec) {
  ModeSpec free = spec;
  free.friction = FrictionMode::none;
  free.given_tangential = 0.0;
  const ModeSolution without = solve(free);
  free.given_tangential = 1.0;
  const ModeSolution unit = solve(free);
  ModeSolution solution;
  if (!without.regular || !unit.regular) return solution;
  const double n0 = without.normal_force, x0 = without.slip_acceleration;
  const double alpha = unit.normal_force - n0, d = unit.slip_acceleration - x0;
  const double k_v = law_->gain(), mu = model_.effective_mu();
  if (!(d > 0.0)) return solution;
  const double C = -x0 / d, D = 1.0 / (d * k_v), A = n0 - alpha * x0 / d, B = alpha / (d * k_v);
  const double factor = kTwoOverPi * mu;
  auto H = [&](double u) {
    const double c = std::cos(u), s = std::sin(u);
    return C * c + D * s + factor * u * std::abs(A * c + B * s);
  };
  auto slope = [&](double u) {
    const double c = std::cos(u), s = std::sin(u);
    const double inner = A * c + B * s;
    const double sign = (inner > 0.0) - (inner < 0.0);
    return -C * s + D * c + factor * (std::abs(inner) + u * sign * (-A * s + B * c));
  };
  const double half_pi = 1.57079632679489661923;
  const double curvature =
      (std::hypot(C, D) + factor * std::hypot(A, B) * (2.0 + half_pi)) * (1.0 + 1e-9);
  // The kink of |N| splits the interval (the bound holds on each side).
  const double kink = B != 0.0 ? std::atan(-A / B) : half_pi;
  const double floor_step = 1e-12 * half_pi;
  // Roots of H in increasing u. Several make the drive jam (the caller
  // raises), so which one is returned then does not matter: the first.
  double chosen = 0.0;
  int count = 0;
  double u = -half_pi;
  double value = H(u);
  for (long step = 0; step < 1000000 && u < half_pi; ++step) {
    double h = floor_step;
    if (value != 0.0) {
      const double g = std::abs(slope(u)), f = std::abs(value);
      h = std::max(2.0 * f / (g + std::sqrt(g * g + 2.0 * curvature * f)), floor_step);
    }
    double next = std::min(u + h, half_pi);
    if (u < kink && next > kink) next = kink;
    const double next_value = H(next);
    const bool root_at_next = next_value == 0.0;
    const bool crossing = value != 0.0 && next_value != 0.0 && (next_value > 0.0) != (value > 0.0);
    if (root_at_next || crossing) {
      // (-H if H falls there: first_negative wants f(low) >= 0)
      const double direction = value > 0.0 ? 1.0 : -1.0;
      if (count++ == 0)
        chosen = root_at_next ? next
                              : first_negative([&](double x) { return direction * H(x); }, u,
                                               next, 1e-16);
    }
    u = next;
    value = next_value;
  }
  if (count == 0) return solution;  // unreachable: H changes sign on the interval
  const double x = std::tan(chosen) / k_v;
  free.given_tangential = (x - x0) / d;  // the friction force T
  solution = solve(free);
  solution.consistent_solutions = count;
  return solution;
}

friction::FlankLcpResult DriveDynamics::prescribed_slip_decision(const ModeSpec& base,
                                                                 int sigma) {
  ModeSpec spec = base;
  spec.given_tangential = 0.0;
  const ModeSolution without = solve(spec);
  spec.given_tangential = 1.0;
  const ModeSolution unit = solve(spec);
  friction::FlankLcpResult result;
  if (!without.regular || !unit.regular) return result;
  // The prescribed slip acceleration; zero within the round-off of its terms.
  const double c = without.slip_acceleration;
  const double noise = 64.0 * std::numeric_limits<double>::epsilon() *
                       model_.tangent_direction().cwiseProduct(without.acceleration).cwiseAbs().sum();
  // sigma 0: the thread without play, whose normal force takes either sign
  // (the one it has without friction; friction within the cone keeps it).
  if (const elements::PreloadedNut* nut = model_.preloaded_nut())
    return nut->prescribed_slip(c, std::abs(c) <= noise, unit.normal_force - without.normal_force,
                                without.normal_force, without.motor_torque,
                                unit.motor_torque - without.motor_torque);
  if (sigma == 0) sigma = without.normal_force >= 0.0 ? 1 : -1;
  return friction::solve_flank_prescribed_slip(
      c, std::abs(c) <= noise, unit.normal_force - without.normal_force, without.normal_force,
      model_.effective_mu(), sigma, without.motor_torque, unit.motor_torque - without.motor_torque);
}

ModeSolution DriveDynamics::solve_with_forces(const ModeSpec& spec,
                                             const CoordinateVector& forces) {
  const CoordinateVector own = forces_;
  forces_ = forces;
  const ModeSolution solution = solve(spec);
  forces_ = own;
  return solution;
}

void DriveDynamics::project_zero_slip(const ModeSpec& spec, CoordinateVector& v) {
  const elements::Motor& motor = model_.motor();
  const int n = model_.coordinate_count();
  const bool normal_row =
      spec.contact == ThreadContact::bilateral || spec.contact == ThreadContact::closed;
  const bool rotor_held = spec.rotor.active && spec.rotor.a_q == 0.0 && spec.rotor.r == 0.0;
  const int nc = 1 + (normal_row ? 1 : 0) + motor.constraint_count() + (rotor_held ? 1 : 0);
  ConstraintMatrix C = ConstraintMatrix::Zero(nc, n);
  SmallVector target = SmallVector::Zero(nc);  // the velocity constraints after the projection
  int row = 0;
  if (rotor_held) C(row++, model_.rotor()) = 1.0;  // a stuck rotor: phi_r' = 0
  C.row(row++) = model_.tangent_direction().transpose();  // zero slip
  // The thread without play and a closed flank have zero normal velocity
  // (the constraint; a closed flank's is set so when it closes).
  if (normal_row) C.row(row++) = model_.normal_direction().transpose();
  if (motor.speed_controlled) {
    C(row, motor.rotor) = 1.0;
    target[row++] = v[motor.rotor];  // the motor's prescribed speed
  }
  if (nc == n) {
    // The constraints fix every velocity (the rigid drive in stick): solve
    // them directly. A torque-driven rigid drive then stands exactly still,
    // where the projection v + dv would leave a round-off speed (~1e-28 rad/s)
    // that keeps the slip velocity off zero for the whole stick phase.
    Eigen::FullPivLU<SmallMatrix> lu(C.leftCols(n));
    if (lu.isInvertible()) {
      const SmallVector fixed = lu.solve(target);
      if (fixed.allFinite()) {
        v = fixed;
        return;
      }
    }
  }
  SmallVector r = target - C * v;
  ColumnMatrix B = C.transpose();
  CoordinateVector zero = CoordinateVector::Zero(n), change;
  SmallVector lambda;
  if (solve_constrained(inverse_mass_, zero, B, C, r, change, lambda)) v += change;
}

bool DriveDynamics::project_held(const HeldContact& held, CoordinateVector& q,
                                 CoordinateVector& v) const {
  const elements::Motor& motor = model_.motor();
  const elements::ThreadPair& thread = model_.thread_pair();
  const int n = model_.coordinate_count();
  const int nc = (held.normal ? 1 : 0) + (held.stick ? 1 : 0) + motor.constraint_count() +
                 (held.rotor ? 1 : 0);
  ConstraintMatrix C = ConstraintMatrix::Zero(nc, n);
  SmallVector on_q = SmallVector::Zero(nc);  // the rows' change of q; of v: -C v
  int row = 0;
  if (held.rotor) C(row++, model_.rotor()) = 1.0;  // its position kept, its speed 0
  if (held.normal) {
    C.row(row) = thread.play_gradient().transpose();
    on_q[row++] = held.play - thread.play(q);
  }
  if (held.stick) {
    C.row(row) = model_.tangent_direction().transpose();
    on_q[row++] = held.slip_position - model_.tangent_direction().dot(q);
  }
  if (motor.speed_controlled) C(row++, motor.rotor) = 1.0;  // kept: its change 0
  // Both are M-orthogonal projections: x + M^-1 C^T lambda with C (x + dx)
  // on target.
  const ColumnMatrix B = C.transpose();
  const CoordinateVector zero = CoordinateVector::Zero(n);
  CoordinateVector dq, dv;
  SmallVector lambda;
  if (!solve_constrained(inverse_mass_, zero, B, C, on_q, dq, lambda)) return false;
  SmallVector on_v = -(C * v);
  if (motor.speed_controlled) on_v[nc - 1] = 0.0;
  if (!solve_constrained(inverse_mass_, zero, B, C, on_v, dv, lambda)) return false;
  q += dq;
  v += dv;
  return true;
}

bool DriveDynamics::impact(int sigma, double restitution, CoordinateVector& v,
                           Impulses& impulses, lcp::Workspace& workspace,
                           const lcp::Options& options) {
  const bool speed_controlled = model_.motor().speed_controlled;
  const int n = model_.coordinate_count();
  const Eigen::VectorXd& normal = model_.normal_direction();
  const Eigen::VectorXd& tangent = model_.tangent_direction();
  // Velocity jump M dv = W_N P_N + W_T P_T (+ the rotor's impulse when speed
  // controlled) with Newton's law W_N (v + dv) = -e W_N v. The post-impact
  // slip velocity and both impulses are affine in P_T: two solves give the
  // maps, and the flank LCP on the impulse level decides stick or slip.
  double rotor_impulse = 0.0;
  auto jump = [&](double given_tangential, CoordinateVector& change, double& impulse) {
    const int nc = 1 + (speed_controlled ? 1 : 0);
    ColumnMatrix B = ColumnMatrix::Zero(n, nc);
    ConstraintMatrix C = ConstraintMatrix::Zero(nc, n);
    SmallVector r = SmallVector::Zero(nc);
    B.col(0) = normal;
    C.row(0) = normal.transpose();
    r[0] = -(1.0 + restitution) * normal.dot(v);
    if (speed_controlled) {
      B(model_.rotor(), 1) = 1.0;
      C(1, model_.rotor()) = 1.0;
    }
    const CoordinateVector f = given_tangential * CoordinateVector(tangent);
    SmallVector lambda;
    if (!solve_constrained(inverse_mass_, f, B, C, r, change, lambda)) return false;
    impulse = lambda[0];
    rotor_impulse = speed_controlled ? lambda[1] : 0.0;
    return true;
  };
  CoordinateVector without, unit;
  double beta = 0.0, unit_normal = 0.0;
  if (!jump(0.0, without, beta)) return false;
  const double rotor_without = rotor_impulse;
  if (!jump(1.0, unit, unit_normal)) return false;
  const double c = tangent.dot(v + without);
  const double d = tangent.dot(unit - without);
  const double alpha = unit_normal - beta;
  friction::FlankLcpResult r;
  if (slip_prescribed_) {
    // The motor and Newton's law fix the velocities after the impact: their
    // slip c decides (friction::solve_flank_prescribed_slip on the impulses).
    const CoordinateVector after = v + without;
    const double noise = 64.0 * std::numeric_limits<double>::epsilon() *
                         tangent.cwiseProduct(after).cwiseAbs().sum();
    r = friction::solve_flank_prescribed_slip(c, std::abs(c) <= noise, alpha, beta,
                                              model_.effective_mu(), sigma, rotor_without,
                                              rotor_impulse - rotor_without);
  } else {
    // A sticking impact where it is admissible (the law's static cone)
    // takes precedence where the law has a static coefficient above its
    // kinetic one, and where the LCP of the flank's sign finds no impulse (the
    // Painleve regime); otherwise the LCP at the law's coefficient at the
    // impact's slip speed.
    const friction::FlankLcpResult stick =
        friction::flank_stick(c, d, alpha, beta, model_.effective_mu_static(), sigma);
    if (!plain_coulomb_ && stick.consistent) {
      r = stick;
    } else {
      const double mu = plain_coulomb_
                            ? model_.effective_mu()
                            : law_->slip_mu(std::abs(tangent.dot(v))) * model_.flank_factor();
      r = solve_flank_lcp_scaled(c, d, alpha, beta, mu, sigma, workspace, options);
      if (!r.consistent && stick.consistent) r = stick;
    }
  }
  if (!r.consistent) return false;
  CoordinateVector change;
  double impulse = 0.0;
  if (!jump(r.friction_force, change, impulse)) return false;
  v += change;
  impulses.normal = impulse;
  impulses.tangential = r.friction_force;
  impulses.rotor = rotor_impulse;
  impulses.sticks = r.slip_acceleration == 0.0;  // the new slip velocity, exactly 0 in the stick basis
  return true;
}

std::string DriveDynamics::jamming_report(double regularized_factor) const {
  const DriveParameters& p = model_.parameters();
  const double g_nn = delassus_nn_, g_nt = delassus_nt_;
  const double mu = model_.effective_mu();
  const bool regularized = regularized_factor >= 0.0;
  // The friction factor in the condition: mu' for exact Coulomb, the
  // regularized law's kappa = (2/pi) mu' |atan(k_V ...)| at this state.
  const double kappa = regularized ? regularized_factor : mu;
  const std::string name = regularized ? "kappa" : "mu'";
  std::ostringstream out;
  out.precision(10);
  if (regularized) {
    out << "Painleve condition of the regularized law kappa |G_NT| >= G_NN with kappa = (2/pi) mu' "
        << "|atan(k_V "
        << (law_->resolution() == friction::Resolution::acceleration ? "gamma_T')|"
                                                                      : "gamma_T)|")
        << " = " << kappa << " (mu' = " << mu << "), G_NN = " << g_nn << ", G_NT = " << g_nt
        << " (" << (kappa * std::abs(g_nt) >= g_nn ? "holds" : "does not hold") << ")";
  } else {
    out << "Painleve condition mu' |G_NT| >= G_NN with mu' = " << mu << ", G_NN = " << g_nn
        << ", G_NT = " << g_nt << " (" << (mu * std::abs(g_nt) >= g_nn ? "holds" : "does not hold")
        << ")";
  }
  // The rigid drive (no spring: rotor and load the only bodies' coordinates).
  if (model_.elements().forces.empty() && !model_.motor().speed_controlled) {
    const double inertia = model_.mass()[model_.rotor()];
    const double mass = model_.mass()[model_.load()];
    const JammingMargins margins = rigid_jamming_margins(p.thread, kappa, inertia, mass);
    out << "; rigid drive: m r^2 tan(a) (" << name << " - tan a) = " << margins.lhs1
        << " vs J (1 + " << name << " tan a) = " << margins.rhs1 << ", J cot(a) (" << name
        << " - cot a) = " << margins.lhs2 << " vs m r^2 (1 + " << name
        << " cot a) = " << margins.rhs2 << " (J = " << inertia << " kg m^2, m = " << mass
        << " kg)";
  }
  out << "; state q = [";
  for (int i = 0; i < q_.size(); ++i) out << (i ? ", " : "") << q_[i];
  out << "], v = [";
  for (int i = 0; i < v_.size(); ++i) out << (i ? ", " : "") << v_[i];
  out << "]";
  return out.str();
}

}  // namespace leadscrew::model
