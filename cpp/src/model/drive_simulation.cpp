#include "leadscrew/model/drive_simulation.hpp"

#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model {

namespace {

enum Energy { kWorkDrive = 0, kWorkAxial, kFrictionLoss, kDampingLoss, kContactLoss, kEnergyCount };

// Between the ODE state y = [independent positions, their velocities (not the
// speed-controlled rotor's), work and loss integrals] and full coordinates.
class StateLayout {
 public:
  explicit StateLayout(const DriveModel& model) : model_(model) {
    const bool speed = model.parameters().speed_controlled;
    positions_ = model.independent();
    for (int i : positions_)
      if (!(speed && i == model.rotor())) velocities_.push_back(i);
  }
  int size() const { return energy_offset() + kEnergyCount; }
  int energy_offset() const {
    return static_cast<int>(positions_.size() + velocities_.size());
  }

  void expand(double t, const double* y, CoordinateVector& q, CoordinateVector& v) const {
    const int n = model_.coordinate_count();
    q.setZero(n);
    v.setZero(n);
    const int np = static_cast<int>(positions_.size());
    for (int k = 0; k < np; ++k) q[positions_[k]] = y[k];
    for (std::size_t k = 0; k < velocities_.size(); ++k) v[velocities_[k]] = y[np + k];
    if (model_.parameters().speed_controlled)
      v[model_.rotor()] = model_.parameters().drive_speed(t);
    const int d = model_.eliminated();
    if (d >= 0) {
      // The thread without play: e = grad e . q = 0 fixes coordinate d.
      const Eigen::VectorXd& w = model_.play_gradient();
      q[d] = -w.dot(q) / w[d];
      v[d] = -w.dot(v) / w[d];
    }
  }

  void compress(const CoordinateVector& q, const CoordinateVector& v, double* y) const {
    const int np = static_cast<int>(positions_.size());
    for (int k = 0; k < np; ++k) y[k] = q[positions_[k]];
    for (std::size_t k = 0; k < velocities_.size(); ++k) y[np + k] = v[velocities_[k]];
  }

  const std::vector<int>& positions() const { return positions_; }
  const std::vector<int>& velocities() const { return velocities_; }

 private:
  const DriveModel& model_;
  std::vector<int> positions_, velocities_;
};

struct Mode {
  ThreadContact contact = ThreadContact::bilateral;
  int flank = 1;  // sign of the normal force on a closed flank: +1 lower (e = -c/2), -1 upper
  FrictionMode friction = FrictionMode::none;
  int slip_sign = 0;
  bool operator==(const Mode& o) const {
    return contact == o.contact && flank == o.flank && friction == o.friction &&
           slip_sign == o.slip_sign;
  }
};

std::string describe(const Mode& m, bool backlash) {
  std::string friction;
  switch (m.friction) {
    case FrictionMode::stick:
      friction = "stick";
      break;
    case FrictionMode::slip:
      friction = m.slip_sign > 0 ? "slip+" : "slip-";
      break;
    case FrictionMode::none:
      friction = "free";
      break;
    default:
      friction = "regularized";
  }
  if (!backlash || m.contact == ThreadContact::penalty) return friction;
  if (m.contact == ThreadContact::open) return "open";
  return std::string(m.flank > 0 ? "lower flank " : "upper flank ") + friction;
}

int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

class DriveHybrid final : public integrate::HybridSystem {
 public:
  DriveHybrid(const DriveModel& model, double bounce_threshold)
      : model_(model),
        p_(model.parameters()),
        dynamics_(model),
        layout_(model),
        bounce_threshold_(bounce_threshold),
        backlash_(p_.backlash != BacklashContact::none) {
    const int n = model.coordinate_count();
    q_.setZero(n);
    v_.setZero(n);
    names_ = {"u_load", "v_load", "phi_drive", "omega_drive", "drive_torque", "axial_force",
              "normal_force", "friction_force", "slip_velocity", "stick"};
    if (backlash_) {
      names_.push_back("gap");
      names_.push_back("play");
    }
    for (int i = 1; i < n - 1; ++i) {
      const std::string& name = model.coordinate_names()[i];
      names_.push_back(name);
      names_.push_back((name[0] == 'u' ? "v" : "omega") + name.substr(name.find('_')));
    }
    for (const char* name : {"work_drive", "work_axial", "friction_loss", "damping_loss",
                             "contact_loss", "impact_loss", "kinetic", "elastic",
                             "energy_residual"})
      names_.push_back(name);
  }

  int size() const override { return layout_.size(); }
  int root_count() const override { return 4; }

  void rhs(double t, const double* y, double* ydot) override {
    set(t, y);
    const ModeSolution s = solve_current();
    const int np = static_cast<int>(layout_.positions().size());
    for (int k = 0; k < np; ++k) ydot[k] = v_[layout_.positions()[k]];
    for (std::size_t k = 0; k < layout_.velocities().size(); ++k)
      ydot[np + k] = s.acceleration[layout_.velocities()[k]];
    double* energy = ydot + layout_.energy_offset();
    energy[kWorkDrive] = s.motor_torque * v_[model_.rotor()];
    energy[kWorkAxial] = dynamics_.axial_force() * v_[model_.load()];
    energy[kFrictionLoss] = -s.friction_force * dynamics_.slip_velocity();
    energy[kDampingLoss] = dynamics_.damping_power();
    energy[kContactLoss] = dynamics_.contact_loss_power();
  }

  void roots(double t, const double* y, double* g) override {
    g[0] = g[1] = g[2] = g[3] = 1.0;
    set(t, y);
    const bool active = mode_.contact != ThreadContact::open;
    if (active && mode_.friction != FrictionMode::none) {
      if (mode_.friction == FrictionMode::slip) g[0] = dynamics_.slip_velocity();
      const bool need_forces = mode_.friction == FrictionMode::stick ||
                               mode_.contact == ThreadContact::closed ||
                               mode_.contact == ThreadContact::bilateral;
      if (need_forces) {
        const ModeSolution s = solve_current();
        const double mu = model_.effective_mu();
        if (mode_.friction == FrictionMode::stick)
          g[0] = (mu * s.normal_force - s.friction_force) * (mu * s.normal_force + s.friction_force);
        if (mode_.contact == ThreadContact::bilateral && mode_.friction != FrictionMode::stick)
          g[1] = s.normal_force;  // the contact changes flank
        if (mode_.contact == ThreadContact::closed) g[1] = mode_.flank * s.normal_force;
      }
    }
    if (mode_.contact == ThreadContact::open || mode_.contact == ThreadContact::penalty) {
      g[2] = dynamics_.play() - 0.5 * p_.clearance;
      g[3] = dynamics_.play() + 0.5 * p_.clearance;
    }
  }

  void root_directions(int* directions) const override {
    // g0: slip s ends when s gamma falls through 0; stick when the cone margin falls.
    directions[0] = mode_.friction == FrictionMode::slip ? -mode_.slip_sign : -1;
    // g1: a closed flank opens when its normal force falls; the bilateral
    // thread changes flank in either direction.
    directions[1] = mode_.contact == ThreadContact::closed ? -1 : 0;
    // g2, g3: an open thread hits the upper flank rising, the lower falling;
    // a penalty contact restarts at both crossings.
    const bool open = mode_.contact == ThreadContact::open;
    directions[2] = open ? 1 : 0;
    directions[3] = open ? -1 : 0;
  }

  void select_initial_mode(double t, double* y) override {
    set(t, y);
    kinetic0_ = dynamics_.kinetic_energy();
    elastic0_ = dynamics_.elastic_energy() + dynamics_.contact_energy();
    switch (p_.backlash) {
      case BacklashContact::none:
        mode_.contact = ThreadContact::bilateral;
        break;
      case BacklashContact::exact: {
        const double half = 0.5 * p_.clearance;
        if (dynamics_.play() >= half) {
          mode_.contact = ThreadContact::closed;
          mode_.flank = -1;
        } else if (dynamics_.play() <= -half) {
          mode_.contact = ThreadContact::closed;
          mode_.flank = 1;
        } else {
          mode_.contact = ThreadContact::open;
        }
        break;
      }
      default:
        mode_.contact = ThreadContact::penalty;
    }
    decide_friction(t, y, dynamics_.slip_velocity() == 0.0, 0);
    if (mode_.contact == ThreadContact::closed) {
      const ModeSolution s = solve_current();
      if (mode_.flank * s.normal_force < 0.0) {
        mode_.contact = ThreadContact::open;
        mode_.friction = FrictionMode::none;
      }
    }
  }

  std::string handle_event(double t, double* y, const std::vector<int>& root_info) override {
    set(t, y);
    const Mode before = mode_;
    bool zero_slip = false;
    int hint = 0;
    std::string kind;
    if (mode_.contact == ThreadContact::open && (root_info[2] > 0 || root_info[3] < 0)) {
      const int flank = root_info[2] > 0 ? -1 : 1;
      zero_slip = flank_impact(t, flank);
      kind = "impact on the " + std::string(flank > 0 ? "lower" : "upper") + " flank";
      if (mode_.contact == ThreadContact::open) {
        layout_.compress(q_, v_, y);
        return kind;
      }
    } else if (mode_.contact == ThreadContact::closed && root_info[1] < 0) {
      mode_.contact = ThreadContact::open;
      mode_.friction = FrictionMode::none;
    } else if (root_info[0] != 0) {
      zero_slip = true;
      if (mode_.friction == FrictionMode::stick) {
        // Leaving the friction cone: slip starts against the friction force
        // that stick needed.
        const ModeSolution s = solve_current();
        hint = -sign_of(s.friction_force);
      }
    } else if (mode_.contact == ThreadContact::bilateral && root_info[1] != 0) {
      layout_.compress(q_, v_, y);
      return "flank change";
    }
    if (mode_.contact != ThreadContact::open) decide_friction(t, y, zero_slip, hint);
    layout_.compress(q_, v_, y);
    if (mode_ == before) return kind;
    const std::string change = describe(before, backlash_) + "->" + describe(mode_, backlash_);
    return kind.empty() ? change : kind + ", " + change;
  }

  const std::vector<std::string>& channel_names() const override { return names_; }

  void channels(double t, const double* y, double* out) override {
    set(t, y);
    const ModeSolution s = solve_current();
    const double* energy = y + layout_.energy_offset();
    const int n = model_.coordinate_count();
    int k = 0;
    out[k++] = q_[model_.load()];
    out[k++] = v_[model_.load()];
    out[k++] = p_.rotor_angle + q_[model_.rotor()];
    out[k++] = v_[model_.rotor()];
    out[k++] = s.motor_torque;
    out[k++] = dynamics_.axial_force();
    out[k++] = s.normal_force;
    out[k++] = s.friction_force;
    out[k++] = dynamics_.slip_velocity();
    out[k++] = mode_.friction == FrictionMode::stick ? 1.0 : 0.0;
    if (backlash_) {
      out[k++] = 0.5 * p_.clearance - std::abs(dynamics_.play());
      out[k++] = dynamics_.play();
    }
    for (int i = 1; i < n - 1; ++i) {
      out[k++] = q_[i];
      out[k++] = v_[i];
    }
    const double kinetic = dynamics_.kinetic_energy();
    const double elastic = dynamics_.elastic_energy() + dynamics_.contact_energy();
    out[k++] = energy[kWorkDrive];
    out[k++] = energy[kWorkAxial];
    out[k++] = energy[kFrictionLoss];
    out[k++] = energy[kDampingLoss];
    out[k++] = energy[kContactLoss];
    out[k++] = impact_loss_;
    out[k++] = kinetic;
    out[k++] = elastic;
    out[k++] = energy[kWorkDrive] + energy[kWorkAxial] -
               (kinetic - kinetic0_ + elastic - elastic0_ + energy[kFrictionLoss] +
                energy[kDampingLoss] + energy[kContactLoss] + impact_loss_);
  }

  std::vector<double> breakpoints() const override {
    std::vector<double> times = p_.axial_force.breakpoints();
    const Excitation& drive = p_.speed_controlled ? p_.drive_speed : p_.drive_torque;
    times.insert(times.end(), drive.breakpoints().begin(), drive.breakpoints().end());
    return times;
  }

  long lcp_solves() const override { return lcp_solves_; }
  double max_step_hint() const override {
    const Excitation& drive = p_.speed_controlled ? p_.drive_speed : p_.drive_torque;
    return integrate::max_step_from_time_scales(
        {drive.time_scale(), p_.axial_force.time_scale()});
  }

 private:
  void set(double t, const double* y) {
    layout_.expand(t, y, q_, v_);
    dynamics_.set_state(t, q_, v_);
  }

  ModeSpec spec(int sigma) const {
    ModeSpec s;
    s.contact = mode_.contact;
    s.sigma = mode_.contact == ThreadContact::closed ? mode_.flank : sigma;
    s.friction = mode_.contact == ThreadContact::open ? FrictionMode::none : mode_.friction;
    s.slip_sign = mode_.slip_sign;
    return s;
  }

  [[noreturn]] void jam(const std::string& what) const {
    throw JammingError(dynamics_.time(),
                       "dynamic jamming: " + what + "; " + dynamics_.jamming_report(),
                       "the drive self-locks dynamically (Painleve paradox); reduce the "
                       "friction or change the inertia ratio");
  }

  // Accelerations and forces in the current mode; for the thread without
  // play the sign of the normal force is the one consistent with it (the
  // thesis's y+/y- procedure, section 4.3, done exactly).
  ModeSolution solve_current() {
    const bool friction_on_normal = mode_.friction == FrictionMode::slip ||
                                    mode_.friction == FrictionMode::regularized_velocity ||
                                    mode_.friction == FrictionMode::regularized_acceleration;
    if (mode_.contact == ThreadContact::bilateral && friction_on_normal) {
      const ModeSolution plus = dynamics_.solve(spec(1));
      const ModeSolution minus = dynamics_.solve(spec(-1));
      const bool plus_ok = plus.regular && plus.normal_force >= 0.0;
      const bool minus_ok = minus.regular && minus.normal_force <= 0.0;
      if (plus_ok && minus_ok) {
        if (plus.normal_force == 0.0) return plus;
        if (minus.normal_force == 0.0) return minus;
        jam("both signs of the flank normal force are consistent");
      }
      if (plus_ok) return plus;
      if (minus_ok) return minus;
      jam("no sign of the flank normal force is consistent");
    }
    const ModeSolution s = dynamics_.solve(spec(1));
    if (!s.regular)
      throw SimulationError(dynamics_.time(), "the constraint equations of the drive are singular",
                            "check masses, inertias and the thread geometry");
    return s;
  }

  // Stick or slip: from the slip velocity, or at zero slip by the flank LCP.
  void decide_friction(double t, double* y, bool at_zero_slip, int hint) {
    (void)t;
    if (mode_.contact == ThreadContact::open || model_.effective_mu() == 0.0) {
      // No contact, or a frictionless flank: no stick, no slip, no events.
      mode_.friction = FrictionMode::none;
      mode_.slip_sign = 0;
      return;
    }
    if (p_.friction == FrictionLaw::arctan_velocity) {
      mode_.friction = FrictionMode::regularized_velocity;
      solve_current();
      return;
    }
    if (p_.friction == FrictionLaw::arctan_acceleration) {
      mode_.friction = FrictionMode::regularized_acceleration;
      solve_current();
      return;
    }
    if (!at_zero_slip && dynamics_.slip_velocity() != 0.0) {
      mode_.friction = FrictionMode::slip;
      mode_.slip_sign = sign_of(dynamics_.slip_velocity());
      solve_current();  // raises JammingError if no normal-force sign is consistent
      return;
    }
    // Zero slip: project the velocities onto exactly zero slip (the root is
    // located to round-off), then let the LCP decide.
    ModeSpec base = spec(1);
    base.friction = FrictionMode::none;
    dynamics_.project_zero_slip(base, v_);
    layout_.compress(q_, v_, y);
    set(t, y);
    ModeSolution without = dynamics_.solve(base);
    base.given_tangential = 1.0;
    ModeSolution unit = dynamics_.solve(base);
    if (!without.regular || !unit.regular)
      throw SimulationError(t, "the constraint equations of the drive are singular",
                            "check masses, inertias and the thread geometry");
    const double c = without.slip_acceleration;
    const double d = unit.slip_acceleration - c;
    double alpha = 0.0, beta = dynamics_.penalty_normal_force();
    std::vector<int> sigmas;
    if (mode_.contact == ThreadContact::penalty) {
      sigmas = {beta >= 0.0 ? 1 : -1};
    } else {
      beta = without.normal_force;
      alpha = unit.normal_force - beta;
      if (mode_.contact == ThreadContact::closed)
        sigmas = {mode_.flank};
      else
        sigmas = {1, -1};
    }
    int found = 0;
    bool ambiguous = false;
    Mode chosen = mode_;
    for (int sigma : sigmas) {
      const friction::FlankLcpResult r =
          friction::solve_flank_lcp(c, d, alpha, beta, model_.effective_mu(), sigma, lcp_workspace_,
                                    lcp_options_);
      ++lcp_solves_;
      if (!r.consistent) continue;
      Mode candidate = mode_;
      const int direction = sign_of(r.slip_acceleration);
      if (direction == 0 && hint == 0) {
        candidate.friction = FrictionMode::stick;
        candidate.slip_sign = 0;
      } else {
        candidate.friction = FrictionMode::slip;
        candidate.slip_sign = direction != 0 ? direction : hint;
      }
      if (found > 0 && !(candidate == chosen)) ambiguous = true;
      chosen = candidate;
      ++found;
    }
    if (found == 0 || ambiguous) {
      // In the Painleve regime (mu' |G_NT| >= G_NN) the LCP of one normal-force
      // sign may have no solution or admit a spurious slip start. At zero slip
      // the drive keeps sticking whenever stick is admissible
      // (docs/physics/rigid_drive.md, "uniqueness"); otherwise it jams.
      const double stick_friction = -c / d;
      const double stick_normal = beta + alpha * stick_friction;
      if (hint == 0 && std::abs(stick_friction) <= model_.effective_mu() * std::abs(stick_normal)) {
        chosen = mode_;
        chosen.friction = FrictionMode::stick;
        chosen.slip_sign = 0;
      } else {
        jam(found == 0 ? "no flank-contact mode is consistent"
                       : "two flank-contact modes are consistent");
      }
    }
    mode_ = chosen;
  }

  // An exact flank closes: Newton's impact law with Coulomb friction on the
  // impulses. Returns true if the impact ends with zero slip.
  bool flank_impact(double t, int flank) {
    const double half = 0.5 * p_.clearance;
    const Eigen::VectorXd& w = model_.play_gradient();
    CoordinateVector weight = model_.mass().cwiseInverse();
    if (p_.speed_controlled) weight[model_.rotor()] = 0.0;
    const double metric = w.dot(weight.cwiseProduct(w));
    // Place the play exactly on the flank (the root is located to round-off).
    const double target = flank > 0 ? -half : half;
    q_ += weight.cwiseProduct(w) * ((target - dynamics_.play()) / metric);
    dynamics_.set_state(t, q_, v_);
    const double kinetic_before = dynamics_.kinetic_energy();
    const CoordinateVector v_before = v_;
    double normal_impulse = 0.0, tangential_impulse = 0.0;
    if (!dynamics_.impact(flank, p_.restitution, v_, normal_impulse, tangential_impulse))
      jam("no consistent frictional impact");
    // Work of the speed-controlled motor's impulse at constant speed.
    double motor_work = 0.0;
    if (p_.speed_controlled) {
      const int r = model_.rotor();
      const double contact = model_.normal_direction()[r] * normal_impulse +
                             model_.tangent_direction()[r] * tangential_impulse;
      motor_work = (model_.mass()[r] * (v_[r] - v_before[r]) - contact) * v_[r];
    }
    dynamics_.set_state(t, q_, v_);
    impact_loss_ += kinetic_before + motor_work - dynamics_.kinetic_energy();
    const double normal_after = dynamics_.play_rate();
    if (std::abs(normal_after) <= bounce_threshold_) {
      // Plastic (or too slow to bounce): the flank stays closed.
      v_ -= weight.cwiseProduct(w) * (normal_after / metric);
      dynamics_.set_state(t, q_, v_);
      mode_.contact = ThreadContact::closed;
      mode_.flank = flank;
      return dynamics_.slip_velocity() == 0.0 || std::abs(tangential_impulse) <
                 model_.effective_mu() * std::abs(normal_impulse);
    }
    mode_.contact = ThreadContact::open;
    mode_.friction = FrictionMode::none;
    return false;
  }

  const DriveModel& model_;
  const DriveParameters& p_;
  DriveDynamics dynamics_;
  StateLayout layout_;
  double bounce_threshold_;
  bool backlash_;
  Mode mode_;
  CoordinateVector q_, v_;
  std::vector<std::string> names_;
  double kinetic0_ = 0.0, elastic0_ = 0.0, impact_loss_ = 0.0;
  long lcp_solves_ = 0;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
};

}  // namespace

std::vector<std::string> drive_integrators(const DriveParameters& p) {
  if (p.friction == FrictionLaw::coulomb) return {"event_driven", "moreau"};
  if (p.backlash == BacklashContact::exact) return {"event_driven"};
  std::vector<std::string> names = integrate::integrator_names();
  names.push_back("event_driven");
  return names;
}

integrate::SimulationResult simulate(const DriveModel& model,
                                     const DriveSimulationOptions& options) {
  const DriveParameters& p = model.parameters();
  const std::vector<std::string> allowed = drive_integrators(p);
  bool fits = false;
  for (const auto& name : allowed) fits = fits || name == options.integrator;
  if (!fits) {
    std::string list;
    for (const auto& name : allowed) list += (list.empty() ? "\"" : ", \"") + name + "\"";
    std::string what = "friction.law = \"" + friction_law_name(p.friction) + "\"";
    if (p.backlash == BacklashContact::exact) what += " with exact backlash";
    throw InvalidArgument("integrator = \"" + options.integrator + "\" is invalid for " + what +
                          ": must be one of " + list);
  }
  if (options.integrator == "moreau")
    throw InvalidArgument("integrator = \"moreau\" is not available for drive models yet");
  require_nonnegative("bounce_threshold", options.bounce_threshold);

  DriveHybrid system(model, options.bounce_threshold);
  StateLayout layout(model);
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(layout.size());
  const double speed = p.speed_controlled ? p.drive_speed(0.0) : p.rotor_speed;
  const Eigen::VectorXd v0 = model.consistent_velocity(speed);
  CoordinateVector q = CoordinateVector::Zero(model.coordinate_count()), v = v0;
  layout.compress(q, v, y0.data());

  integrate::EventDrivenOptions driver;
  driver.integrator_options = options.integrator_options;
  driver.max_events = options.max_events;
  if (options.integrator == "event_driven") {
    driver.integrator = !options.smooth_integrator.empty() ? options.smooth_integrator
                        : p.concept == Concept::rigid     ? "rk_verner6"
                                                          : "cvode_bdf";
  } else {
    driver.integrator = options.integrator;
  }
  integrate::SimulationResult result =
      integrate::simulate_event_driven(system, 0.0, y0, options.output, driver);
  result.integrator = options.integrator;
  result.friction = friction_law_name(p.friction);
  return result;
}

}  // namespace leadscrew::model
