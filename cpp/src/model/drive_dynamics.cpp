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
#include "constrained_solve.hpp"

namespace leadscrew::model {

using detail::ColumnMatrix;
using detail::ConstraintMatrix;
using detail::SmallMatrix;
using detail::SmallVector;
using detail::solve_constrained;

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
  // The slip's response to a tangential force with the flank and the rotor
  // held: W_T . x with M x = W_T + B lambda, C x = 0. Zero (to round-off of
  // the unconstrained W_T M^-1 W_T) when those constraints fix every velocity:
  // held by a speed-controlled motor, or by the rotor's stuck friction
  // contact (the train's stages with a torque or DC motor).
  const bool rotor_contact = model.train_friction() && !model.motor().speed_controlled;
  if (model.motor().speed_controlled || rotor_contact) {
    const int n = model.coordinate_count();
    ColumnMatrix B = ColumnMatrix::Zero(n, 2);
    B.col(0) = normal;
    B(model.rotor(), 1) = 1.0;
    const ConstraintMatrix C = B.transpose();
    CoordinateVector x;
    SmallVector lambda;
    const CoordinateVector force = tangent;
    if (solve_constrained(inverse_mass_, force, B, C, SmallVector::Zero(2), x, lambda))
      (rotor_contact ? rotor_fixes_slip_ : slip_prescribed_) =
          std::abs(tangent.dot(x)) <= 1e-12 * tangent.dot(w_t);
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

double DriveDynamics::bristle_rate() const {
  if (!transverse_) return law_->bristle_rate(slip_, bristle_);
  return planar_bristle_rate(slip_, bristle_);
}

double DriveDynamics::bristle_storing_power() const {
  if (!transverse_) return law_->storing_power(slip_, bristle_);
  return law_->bristle_stiffness() *
         (bristle_ * bristle_rate() + transverse_bristle_ * transverse_bristle_rate());
}

double DriveDynamics::kinetic_energy() const {
  return 0.5 * v_.dot(model_.mass().cwiseProduct(v_));
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

// The rotor's inverse mass with its friction contact's row eliminated
// (a_q / (a_q M_r - a_w), as DriveDynamics::solve's); false where the
// stage's Painleve case leaves no finite one.
bool DriveDynamics::eliminated_rotor_inverse_mass(const ModeSpec::RotorRow& rotor_contact,
                                                  CoordinateVector& inverse_mass) const {
  const int rotor = model_.rotor();
  const double effective = rotor_contact.a_q / inverse_mass_[rotor] - rotor_contact.a_w;
  if (!(std::abs(effective) > 1e-12 * std::abs(rotor_contact.a_q / inverse_mass_[rotor])))
    return false;
  inverse_mass = inverse_mass_;
  inverse_mass[rotor] = rotor_contact.a_q / effective;
  return true;
}

// impact()'s friction impulse on the flank's line: the post-impact slip
// c + d P_T and the normal impulse beta + alpha P_T.
friction::FlankLcpResult DriveDynamics::impact_friction(const ImpactLine& line,
                                                        double slip_before, int sigma,
                                                        lcp::Workspace& workspace,
                                                        const lcp::Options& options) const {
  if (line.prescribed) {
    // The motor (or the rotor's stuck contact) and Newton's law fix the
    // velocities after the impact: their slip c decides
    // (friction::solve_flank_prescribed_slip on the impulses; in stick the
    // least rotor impulse).
    return friction::solve_flank_prescribed_slip(line.c, std::abs(line.c) <= line.noise,
                                                 line.alpha, line.beta, model_.effective_mu(),
                                                 sigma, line.held0, line.held1);
  }
  // A sticking impact where it is admissible (the law's static cone)
  // takes precedence where the law has a static coefficient above its
  // kinetic one, and where the LCP of the flank's sign finds no impulse (the
  // Painleve regime); otherwise the LCP at the law's coefficient at the
  // impact's slip speed.
  const friction::FlankLcpResult stick = friction::flank_stick(
      line.c, line.d, line.alpha, line.beta, model_.effective_mu_static(), sigma);
  if (!plain_coulomb_ && stick.consistent) return stick;
  const double mu = plain_coulomb_ ? model_.effective_mu()
                                   : law_->slip_mu(slip_before) * model_.flank_factor();
  const friction::FlankLcpResult r =
      solve_flank_lcp_scaled(line.c, line.d, line.alpha, line.beta, mu, sigma, workspace,
                             options);
  return (!r.consistent && stick.consistent) ? stick : r;
}

bool DriveDynamics::impact(int sigma, double restitution, CoordinateVector& v,
                           Impulses& impulses, lcp::Workspace& workspace,
                           const lcp::Options& options, const ModeSpec::RotorRow& rotor_contact) {
  const bool speed_controlled = model_.motor().speed_controlled;
  const int n = model_.coordinate_count();
  const Eigen::VectorXd& normal = model_.normal_direction();
  const Eigen::VectorXd& tangent = model_.tangent_direction();
  // Velocity jump M dv = W_N P_N + W_T P_T (+ the rotor's impulse when speed
  // controlled) with Newton's law W_N (v + dv) = -e W_N v. The post-impact
  // slip velocity and both impulses are affine in P_T: two solves give the
  // maps, and the flank LCP on the impulse level decides stick or slip.
  // The rotor's friction contact (gear.md, "Exact play through the rotor's
  // contact"): its row fixes w+ (a_q = 0) or eliminates Q into the rotor's
  // inverse mass and the given impulse -(r - a_w w-) / a_q on its coordinate.
  double rotor_impulse = 0.0, rotor_friction = 0.0;
  const int rotor = model_.rotor();
  const bool rotor_fixed = rotor_contact.fixes(1.0 / inverse_mass_[rotor]);
  const bool rotor_eliminated = rotor_contact.active && !rotor_fixed;
  CoordinateVector rotor_inverse_mass;
  if (rotor_eliminated && !eliminated_rotor_inverse_mass(rotor_contact, rotor_inverse_mass))
    return false;  // (the stage's Painleve case, k J_s + R = 0)
  auto jump = [&](double given_tangential, CoordinateVector& change, double& impulse) {
    const int nc = 1 + (speed_controlled ? 1 : 0) + (rotor_fixed ? 1 : 0);
    ColumnMatrix B = ColumnMatrix::Zero(n, nc);
    ConstraintMatrix C = ConstraintMatrix::Zero(nc, n);
    SmallVector r = SmallVector::Zero(nc);
    B.col(0) = normal;
    C.row(0) = normal.transpose();
    r[0] = -(1.0 + restitution) * normal.dot(v);
    if (speed_controlled) {
      B(rotor, 1) = 1.0;
      C(1, rotor) = 1.0;
    }
    if (rotor_fixed) {
      B(rotor, nc - 1) = -1.0;
      C(nc - 1, rotor) = rotor_contact.a_w;
      r[nc - 1] = rotor_contact.r - rotor_contact.a_w * v[rotor];
    }
    CoordinateVector f = given_tangential * CoordinateVector(tangent);
    if (rotor_eliminated) f[rotor] -= (rotor_contact.r - rotor_contact.a_w * v[rotor]) / rotor_contact.a_q;
    SmallVector lambda;
    if (!solve_constrained(rotor_eliminated ? rotor_inverse_mass : inverse_mass_, f, B, C, r,
                           change, lambda))
      return false;
    impulse = lambda[0];
    rotor_impulse = speed_controlled ? lambda[1] : 0.0;
    rotor_friction =
        rotor_fixed        ? lambda[nc - 1]
        : rotor_eliminated ? (rotor_contact.r - rotor_contact.a_w * (v[rotor] + change[rotor])) /
                                 rotor_contact.a_q
                           : 0.0;
    return true;
  };
  CoordinateVector without, unit;
  double beta = 0.0, unit_normal = 0.0;
  if (!jump(0.0, without, beta)) return false;
  const double rotor_without = rotor_impulse, friction_without = rotor_friction;
  if (!jump(1.0, unit, unit_normal)) return false;
  ImpactLine line{tangent.dot(v + without), tangent.dot(unit - without), unit_normal - beta,
                  beta, slip_prescribed_ || (rotor_fixed && rotor_fixes_slip_)};
  if (line.prescribed) {
    // (Held by the rotor's stuck contact after a plastic impact c is the
    // round-off of the jump from v: 64 ulp of the velocities before it too.)
    const CoordinateVector after = v + without;
    line.noise = 64.0 * std::numeric_limits<double>::epsilon() *
                 (tangent.cwiseProduct(after).cwiseAbs().sum() +
                  (speed_controlled ? 0.0 : tangent.cwiseProduct(v).cwiseAbs().sum()));
    line.held0 = speed_controlled ? rotor_without : friction_without;
    line.held1 = (speed_controlled ? rotor_impulse : rotor_friction) - line.held0;
  }
  const friction::FlankLcpResult r =
      impact_friction(line, std::abs(tangent.dot(v)), sigma, workspace, options);
  if (!r.consistent) return false;
  CoordinateVector change;
  double impulse = 0.0;
  if (!jump(r.friction_force, change, impulse)) return false;
  v += change;
  // (sticks: the new slip velocity, exactly 0 in the stick basis)
  impulses = {impulse, r.friction_force, rotor_impulse, rotor_friction,
              r.slip_acceleration == 0.0};
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
