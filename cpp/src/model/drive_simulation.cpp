#include "leadscrew/model/drive_simulation.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/friction/law.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/integrate/moreau.hpp"
#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/integrate/simulation_result.hpp"
#include "leadscrew/model/drive_dynamics.hpp"
#include "leadscrew/model/drive_rigid.hpp"
#include "leadscrew/model/result_checks.hpp"
#include "leadscrew/model/simulation_checks.hpp"

namespace leadscrew::model {

namespace {

enum Energy { kWorkDrive = 0, kWorkAxial, kFrictionLoss, kDampingLoss, kContactLoss, kEnergyCount };

// Between the ODE state y = [independent positions, their velocities (not the
// speed-controlled rotor's), work and loss integrals] and full coordinates.
class StateLayout {
 public:
  // `bristle`: the friction law has LuGre's bristle deflection z, a state
  // of its own after the velocities, followed by the bristles' stored energy
  // (DriveHybrid::rhs).
  StateLayout(const DriveModel& model, bool bristle) : model_(model), bristle_(bristle) {
    const bool speed = model.parameters().speed_controlled;
    positions_ = model.independent();
    for (int i : positions_)
      if (!(speed && i == model.rotor())) velocities_.push_back(i);
  }
  int size() const { return energy_offset() + kEnergyCount; }
  // The bristle deflection's index (-1: none).
  int bristle() const {
    return bristle_ ? static_cast<int>(positions_.size() + velocities_.size()) : -1;
  }
  int energy_offset() const {
    return static_cast<int>(positions_.size() + velocities_.size()) + (bristle_ ? 2 : 0);
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
  bool bristle_;
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

// A bounce whose flight would rise less than this fraction of the clearance is
// plastic: such flights (1e-6 of a 0.1 mm play is 0.1 nm) are far below the
// flanks' roughness, and a geometric sequence of them only costs events.
constexpr double kPlasticHeight = 1e-6;

// A free flight whose play goes beyond a flank by more than this fraction of
// the clearance (beyond where the flight started: a closed flank drifts, by
// 1.6e-4 of a 0.2 mm play in 0.4 s) passed through it unseen: far above the
// events' resolution (kPlasticHeight; roots are located to round-off).
constexpr double kFlankTolerance = 1e-3;

// The regularized law's branch is watched for the onset of jamming once its
// denominator falls below this fraction of G_NN (DriveHybrid::approach_fold).
constexpr double kFoldWatch = 0.1;

std::vector<std::string> drive_channel_names(const DriveModel& model) {
  std::vector<std::string> names = {"u_load",        "v_load",      "phi_drive",
                                    "omega_drive",   "drive_torque", "axial_force",
                                    "normal_force",  "friction_force", "slip_velocity",
                                    "stick"};
  if (model.parameters().backlash != BacklashContact::none) {
    names.push_back("gap");
    names.push_back("play");
  }
  if (model.law().resolution() == friction::Resolution::bristle)
    names.push_back("bristle_deflection");
  const int n = model.coordinate_count();
  for (int i = 1; i < n - 1; ++i) {
    const std::string& name = model.coordinate_names()[i];
    names.push_back(name);
    names.push_back((name[0] == 'u' ? "v" : "omega") + name.substr(name.find('_')));
  }
  for (const char* name : {"work_drive", "work_axial", "friction_loss", "damping_loss",
                           "contact_loss", "impact_loss", "kinetic", "elastic",
                           "energy_residual"})
    names.push_back(name);
  return names;
}

// Thread and motor forces at an output point.
struct ContactForces {
  double normal = 0.0, friction = 0.0, motor_torque = 0.0;
  bool stick = false;
};

// The state of an output row besides the thread and motor forces.
struct ChannelState {
  const CoordinateVector& q;
  const CoordinateVector& v;
  double axial_force = 0.0, slip_velocity = 0.0, play = 0.0, kinetic = 0.0, elastic = 0.0;
  double bristle = 0.0;  // LuGre's bristle deflection z [m]
};

// From the state last set in dynamics.
ChannelState channel_state(const DriveDynamics& dynamics) {
  return {dynamics.q(),
          dynamics.v(),
          dynamics.axial_force(),
          dynamics.slip_velocity(),
          dynamics.play(),
          dynamics.kinetic_energy(),
          dynamics.elastic_energy() + dynamics.contact_energy()};
}

// Writes one output row.
void write_drive_channels(const DriveModel& model, const ChannelState& state,
                          const ContactForces& forces, const double* energy, double impact_loss,
                          double kinetic0, double elastic0, double* out) {
  const DriveParameters& p = model.parameters();
  const CoordinateVector& q = state.q;
  const CoordinateVector& v = state.v;
  const int n = model.coordinate_count();
  int k = 0;
  out[k++] = q[model.load()];
  out[k++] = v[model.load()];
  out[k++] = p.rotor_angle + q[model.rotor()];
  out[k++] = v[model.rotor()];
  out[k++] = forces.motor_torque;
  out[k++] = state.axial_force;
  out[k++] = forces.normal;
  out[k++] = forces.friction;
  out[k++] = state.slip_velocity;
  out[k++] = forces.stick ? 1.0 : 0.0;
  if (p.backlash != BacklashContact::none) {
    out[k++] = 0.5 * p.clearance - std::abs(state.play);
    out[k++] = state.play;
  }
  if (model.law().resolution() == friction::Resolution::bristle) out[k++] = state.bristle;
  for (int i = 1; i < n - 1; ++i) {
    out[k++] = q[i];
    out[k++] = v[i];
  }
  const double kinetic = state.kinetic;
  const double elastic = state.elastic;
  for (int e = 0; e < kEnergyCount; ++e) out[k++] = energy[e];
  out[k++] = impact_loss;
  out[k++] = kinetic;
  out[k++] = elastic;
  out[k++] = energy[kWorkDrive] + energy[kWorkAxial] -
             (kinetic - kinetic0 + elastic - elastic0 + energy[kFrictionLoss] +
              energy[kDampingLoss] + energy[kContactLoss] + impact_loss);
}

// A run ends where the nut's end reaches the screw's
// (DriveModel::screw_end_margin), for every concept: beyond it the thread no
// longer holds the nut, and the results would describe a drive that does not
// exist. The flexible screw needs it besides: its stiffness grows as 1/a
// toward an end (eq. 4.24), and a run that wound the nut there took ever
// smaller steps (CVODE ground to max_steps within a millimetre of the end).
[[noreturn]] void nut_left_the_screw(const DriveModel& model, double t, double nut_position) {
  throw SimulationError(t, model.nut_off_screw(nut_position), DriveModel::kNutOffScrewHint);
}

class DriveHybrid final : public integrate::HybridSystem {
 public:
  // `law`: the friction law that runs (the model's, or its regularization
  // for an ODE integrator); it outlives this.
  DriveHybrid(const DriveModel& model, const friction::Law& law, double bounce_threshold,
              double t_end, const integrate::IntegratorOptions& integrator_options)
      : model_(model),
        p_(model.parameters()),
        dynamics_(model, &law),
        layout_(model, law.resolution() == friction::Resolution::bristle),
        bounce_threshold_(bounce_threshold),
        backlash_(p_.backlash != BacklashContact::none),
        t_end_(t_end),
        integrator_options_(integrator_options) {
    const int n = model.coordinate_count();
    q_.setZero(n);
    v_.setZero(n);
    names_ = drive_channel_names(model);
    saved_state_.resize(static_cast<std::size_t>(layout_.size()));
    if (RigidDriveModes::applies(model, dynamics_)) rigid_.emplace(model, dynamics_);
  }

  int size() const override { return layout_.size(); }
  // g0..g3: friction and flank events (see roots); g4: the nut's end at the
  // screw's end, for every concept (the scene gives every screw its length).
  int root_count() const override { return 5; }
  // The work and loss integrals close the state; f does not depend on them.
  int quadrature_count() const override { return kEnergyCount; }

  void rhs(double t, const double* y, double* ydot) override {
    if (rigid_) {
      // One degree of freedom: y = [phi_rotor, omega_rotor, energy integrals].
      const RigidSolution s = solve_rigid(t, y);
      const double omega = y[1];
      ydot[0] = omega;
      ydot[1] = s.acceleration;
      double* energy = ydot + layout_.energy_offset();
      energy[kWorkDrive] = s.torque * omega;
      energy[kWorkAxial] = s.axial_force * rigid_->load_per_angle() * omega;
      energy[kFrictionLoss] = -s.friction_force * rigid_->slip_per_speed() * omega;
      energy[kDampingLoss] = 0.0;
      energy[kContactLoss] = 0.0;
      return;
    }
    set(t, y);
    const ModeSolution s = solve_current();
    const int np = static_cast<int>(layout_.positions().size());
    for (int k = 0; k < np; ++k) ydot[k] = v_[layout_.positions()[k]];
    for (std::size_t k = 0; k < layout_.velocities().size(); ++k)
      ydot[np + k] = s.acceleration[layout_.velocities()[k]];
    double* energy = ydot + layout_.energy_offset();
    energy[kWorkDrive] = s.motor_torque * v_[model_.rotor()];
    energy[kWorkAxial] = dynamics_.axial_force() * v_[model_.load()];
    energy[kFrictionLoss] =
        mode_.friction == FrictionMode::stick ? 0.0 : -s.friction_force * dynamics_.slip_velocity();
    const int bristle = layout_.bristle();
    if (bristle >= 0) {
      // LuGre's bristles: z' of the law. Of the friction's power, the part
      // |N|' sigma0 z z' is stored in the bristles, not lost; it is
      // integrated (the state after z) rather than taken as |N|' sigma0 z^2
      // / 2, which would miss the work of a changing normal force on a
      // deflected bristle. What remains, |N|' (sigma0^2 |gamma| z^2 / mu(|gamma|)
      // + sigma1 z' gamma) + viscous gamma^2, is the loss (sigma1 z' gamma can be
      // negative: LuGre is passive only for small sigma1).
      const double z = y[bristle];
      const double rate = dynamics_.law().bristle_rate(dynamics_.slip_velocity(), z);
      const double stored = std::abs(s.normal_force) * model_.flank_factor() *
                            dynamics_.law().bristle_stiffness() * z * rate;
      ydot[bristle] = rate;
      ydot[bristle + 1] = stored;
      energy[kFrictionLoss] -= stored;
    }
    energy[kDampingLoss] = dynamics_.damping_power();
    energy[kContactLoss] = dynamics_.contact_loss_power();
  }

  void roots(double t, const double* y, double* g) override {
    g[0] = g[1] = g[2] = g[3] = g[4] = 1.0;
    if (rigid_) {
      layout_.expand(t, y, q_, v_);  // for the nut's position alone
      g[4] = model_.screw_end_margin(model_.nut_position(q_.data()));
      if (mode_.friction == FrictionMode::none) return;
      const RigidSolution s = solve_rigid(t, y);
      const double mu = stick_mu();
      if (mode_.friction == FrictionMode::slip) {
        g[0] = rigid_->slip_per_speed() * y[1] - slip_offset_;
        g[1] = load_root_ == 1 ? load_root_value(t) : flank_change_root(s.normal_force);
      } else {
        const double margin =
            (mu * s.normal_force - s.friction_force) * (mu * s.normal_force + s.friction_force);
        if (margin > 0.0) stick_from_zero_ = false;  // the margin left zero into the cone
        g[0] = load_root_ == 0 ? load_root_value(t) : margin;
      }
      return;
    }
    set(t, y);
    g[4] = model_.screw_end_margin(model_.nut_position(q_.data()));
    const bool active = mode_.contact != ThreadContact::open;
    // A closed flank is watched for its normal force falling through zero
    // whatever the friction (a frictionless one too: it must open).
    if (active && (mode_.friction != FrictionMode::none || mode_.contact == ThreadContact::closed)) {
      if (mode_.friction == FrictionMode::slip) g[0] = dynamics_.slip_velocity() - slip_offset_;
      const bool need_forces = mode_.friction == FrictionMode::stick ||
                               mode_.contact == ThreadContact::closed ||
                               mode_.contact == ThreadContact::bilateral;
      if (need_forces) {
        const ModeSolution s = solve_current();
        const double mu = stick_mu();
        if (mode_.friction == FrictionMode::stick && slip_prescribed_now()) {
          // The motor holds the slip at zero (the friction force stays in the
          // cone by construction): the stick ends where the prescribed slip
          // leaves zero, either way.
          g[0] = std::abs(dynamics_.slip_velocity());
        } else if (mode_.friction == FrictionMode::stick) {
          g[0] = (mu * s.normal_force - s.friction_force) * (mu * s.normal_force + s.friction_force);
          if (g[0] > 0.0) stick_from_zero_ = false;  // the margin left zero into the cone
        }
        if (mode_.contact == ThreadContact::bilateral && mode_.friction != FrictionMode::stick)
          g[1] = flank_change_root(s.normal_force);
        if (watch_fold()) {
          // The regularized law's paradox: the margin min over sigma of
          // G_NN - sigma kappa G_NT, and the current branch's denominator
          // approaching zero (see approach_fold).
          g[2] = fold_margin();
          g[3] = dynamics_.thread_denominator(sigma_guess_, current_kappa()) /
                     dynamics_.delassus_normal() -
                 kFoldWatch;
        }
        if (mode_.contact == ThreadContact::closed) g[1] = mode_.flank * s.normal_force;
        if (load_root_ >= 0) g[load_root_] = load_root_value(t);
      }
    }
    if (mode_.contact == ThreadContact::open || mode_.contact == ThreadContact::penalty) {
      g[2] = dynamics_.play() - 0.5 * p_.clearance;
      g[3] = dynamics_.play() + 0.5 * p_.clearance;
    }
    // After a bounce the flight's apex (the play rate through zero) is an
    // event: a weak bounce leaves the flank and comes back within one step,
    // and the gap alone would show no sign change at the step ends.
    if (mode_.contact == ThreadContact::open && bounced_from_ != 0) {
      g[1] = dynamics_.play_rate();
      // Until the apex the play moves away from the flank it bounced off, so
      // gap + tau * gap rate stays strictly on the open side (it starts at
      // tau * rate, not at zero, which would mislead the root finder) and
      // equals the gap at the apex: continuous where the ordinary gap takes over.
      constexpr double tau = 1e-3;  // [s]; any positive time works
      if (bounced_from_ > 0)
        g[3] += tau * dynamics_.play_rate();
      else
        g[2] += tau * dynamics_.play_rate();
    }
  }

  void root_directions(int* directions) const override {
    // g0: slip s ends when s gamma falls through 0; stick when the cone margin falls.
    directions[0] = mode_.friction == FrictionMode::slip ? -mode_.slip_sign
                    : slip_prescribed_now()                ? 1
                                                           : -1;
    // g1: a closed flank opens when its normal force falls; the bilateral
    // thread changes flank when the normal force falls through zero on its
    // side (see flank_change_root).
    directions[1] = mode_.contact == ThreadContact::closed ||
                            mode_.contact == ThreadContact::bilateral
                        ? -1
                        : 0;
    if (mode_.contact == ThreadContact::open && bounced_from_ != 0)
      directions[1] = bounced_from_ > 0 ? -1 : 1;  // leaving the lower flank: e' falls at the apex
    // g2, g3: an open thread hits the upper flank rising, the lower falling;
    // a penalty contact restarts at both crossings.
    // A penalty flank is entered rising (upper) or falling (lower) and left
    // the other way: a root that starts at exactly 0 (a nut placed on the
    // flank) must see which crossing comes (RootGuard; with either direction
    // it saw neither entering, and the flank carried no friction).
    const bool open = mode_.contact == ThreadContact::open;
    const bool penalty = mode_.contact == ThreadContact::penalty;
    const bool upper = penalty && touching_ && dynamics_.play() > 0.0;
    const bool lower = penalty && touching_ && dynamics_.play() < 0.0;
    directions[2] = open || (penalty && !upper) ? 1 : (penalty ? -1 : 0);
    directions[3] = open || (penalty && !lower) ? -1 : (penalty ? 1 : 0);
    directions[4] = -1;  // the nut reaches an end of the screw
    if (watch_fold()) directions[2] = directions[3] = -1;  // both fall towards jamming
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
        touching_ = std::abs(dynamics_.play()) > 0.5 * p_.clearance;
    }
    decide_friction(t, y, std::abs(dynamics_.slip_velocity()) <= dynamics_.slip_noise(), 0);
    if (mode_.contact == ThreadContact::closed) {
      const ModeSolution s = solve_current();
      if (mode_.flank * s.normal_force < 0.0) {
        mode_.contact = ThreadContact::open;
        mode_.friction = FrictionMode::none;
      }
    }
    note_flight_start(t, y);
    start_normal_side();
    if (watch_fold()) {
      set(t, y);
      // A start inside the regularized law's Painleve regime (kappa |G_NT| >=
      // G_NN at the initial slip velocity: both signs of the flank normal
      // force consistent, or neither) jams where it starts, as exact
      // Coulomb's does; its roots only see the regime being entered.
      if (fold_margin() <= 0.0)
        jam_regularized("the drive starts inside the regime where both signs of the flank "
                        "normal force are consistent, or neither");
      solve_current();
      if (dynamics_.thread_denominator(sigma_guess_, current_kappa()) <
          kFoldWatch * dynamics_.delassus_normal())
        approach_fold(t, y);
    }
    start_mode(t, y);
  }

  std::string handle_event(double t, double* y, const std::vector<int>& root_info) override {
    if (root_info[4] != 0) {
      set(t, y);
      nut_left_the_screw(model_, t, model_.nut_position(q_.data()));
    }
    const bool from_zero = stick_from_zero_ && mode_.friction == FrictionMode::stick &&
                           root_info[0] != 0;
    std::string kind = change_mode(t, y, root_info);
    note_flight_start(t, y);
    start_mode(t, y);
    // A stick whose cone margin never left zero was no stick phase: the thread
    // carried no force (a flexible drive's relaxed springs at t = 0) and the
    // forces, once they grow, leave the cone at once. The slip that follows is
    // the drive's motion from the start, not an event.
    return from_zero ? std::string() : kind;
  }

  // After the mode is chosen (at the start and at every event).
  void start_mode(double t, const double* y) {
    plan_load_roots(t);
    // A slip mode starts at zero slip (projected to round-off) or with the
    // slip velocity's sign. Where the projection's round-off leaves the slip
    // velocity on the other side of zero than the mode's sign (-2.4e-38 m/s
    // with slip+), the root g0 would start beyond its own zero and never
    // fall through it: the drive slipped the other way for the rest of the
    // run with friction pushing it. The root is measured from that
    // round-off instead, so it starts at exactly 0 (on its uncrossed side,
    // RootGuard) and any slip against the mode's sign ends the mode.
    //
    // Where an event of g0 kept the same slip mode (the flank LCP at zero
    // slip chose the same direction again), the slip velocity crossed zero
    // only by the integrator's noise: forces of 1e-15 N at the start of a
    // flexible drive, whose slip acceleration of 1e-11 m/s^2 no step resolves,
    // restarted CVODE at every crossing of its noise, a million steps within
    // 7 ns. Then the root waits for the slip to pass the integrator's
    // resolution against the mode's sign (slip_resolution), which any real
    // reversal does; friction may do positive work within that band only,
    // at most mu' |N| times it (the result's checks allow for it).
    slip_offset_ = 0.0;
    if (mode_.friction == FrictionMode::slip) {
      const double slip = rigid_ ? rigid_->slip_per_speed() * y[1]
                                 : (set(t, y), dynamics_.slip_velocity());
      if (mode_.slip_sign * slip < 0.0) slip_offset_ = slip;
      if (slip_noise_event_) slip_offset_ = -mode_.slip_sign * slip_resolution();
    }
    slip_noise_event_ = false;
    stick_from_zero_ = false;
    if (mode_.friction == FrictionMode::stick) {
      const ModeSolution s = solve_current();
      stick_from_zero_ = s.normal_force == 0.0 && s.friction_force == 0.0;
    }
  }

  // handle_event without the planning of the next mode's load-driven roots.
  std::string change_mode(double t, double* y, const std::vector<int>& root_info) {
    set(t, y);
    const Mode before = mode_;
    if (watch_fold() && root_info[2] != 0) {
      solve_current();
      // The other sign's denominator passes through zero (the current branch
      // stays regular): beyond, that sign is consistent too.
      jam_regularized("from here both signs of the flank normal force are consistent (the "
                      "regularized friction factor reached the Painleve bound)");
    }
    if (watch_fold() && root_info[3] != 0) {
      approach_fold(t, y);
      return "";  // the branch recovers: no event
    }
    bool zero_slip = false;
    int hint = 0;
    std::string kind;
    bool touch = false;
    const int bounced_before = bounced_from_;
    if (mode_.contact == ThreadContact::open && (root_info[2] > 0 || root_info[3] < 0)) {
      const int flank = root_info[2] > 0 ? -1 : 1;
      // A touch below resolution: the play reaches the flank without
      // approaching it, or so slowly against a free flight that pulls it
      // back that it would go less than kPlasticHeight of the clearance
      // beyond (rate^2 / (2 |e''|)).
      const double rate = dynamics_.play_rate();
      touch = flank * rate >= 0.0;
      if (!touch) {
        const double acceleration = free_flight_play_acceleration();
        touch = flank * acceleration > 0.0 &&
                rate * rate <= 2.0 * flank * acceleration * kPlasticHeight * p_.clearance;
      }
      if (touch) {
        std::copy(y, y + size(), saved_state_.begin());
        saved_impact_loss_ = impact_loss_;
      }
      zero_slip = flank_impact(t, y, flank);
      kind = "impact on the " + std::string(flank > 0 ? "lower" : "upper") + " flank";
      if (mode_.contact == ThreadContact::open) {
        bounced_from_ = flank;
        layout_.compress(q_, v_, y);
        return kind;
      }
      bounced_from_ = 0;
    } else if (mode_.contact == ThreadContact::open && root_info[1] != 0) {
      bounced_from_ = 0;  // the apex: the flight now only comes back
      layout_.compress(q_, v_, y);
      return "";
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
      normal_side_ = -normal_side_;
      layout_.compress(q_, v_, y);
      return "flank change";
    } else if (mode_.contact == ThreadContact::penalty && (root_info[2] != 0 || root_info[3] != 0)) {
      // A penalty flank is entered (upper rising, lower falling) or left.
      touching_ = root_info[2] > 0 || root_info[3] < 0;
      kind = touching_ ? "flank contact" : "flank separation";
    }
    if (mode_.contact != ThreadContact::open) decide_friction(t, y, zero_slip, hint);
    slip_noise_event_ = root_info[0] != 0 && before.friction == FrictionMode::slip &&
                        mode_ == before;
    if (touch && mode_.contact == ThreadContact::open) {
      // A touch below resolution of a flank that cannot push: no contact,
      // nothing changes (y is left as it was). This is the integrator's noise
      // at the flank just left: a flank opens when its normal force falls
      // through zero, so the play leaves it at third order in time, and a
      // multistep method's first steps after the restart (CVODE) can show it
      // a round-off beyond the flank, even approaching it at a round-off rate.
      // That round-off goes back inside (put_back_inside): left beyond the
      // flank, it would start the flight on the crossed side of its root.
      mode_ = before;
      bounced_from_ = bounced_before;
      std::copy(saved_state_.begin(), saved_state_.end(), y);
      impact_loss_ = saved_impact_loss_;
      put_back_inside(t, y);
      return "";
    }
    layout_.compress(q_, v_, y);
    start_normal_side();
    if (mode_ == before) return kind;
    const std::string change = describe(before, backlash_) + "->" + describe(mode_, backlash_);
    return kind.empty() ? change : kind + ", " + change;
  }

  const std::vector<std::string>& channel_names() const override { return names_; }

  void channels(double t, const double* y, double* out) override {
    ContactForces forces;
    forces.stick = mode_.friction == FrictionMode::stick;
    if (rigid_) {
      const RigidSolution s = solve_rigid(t, y);
      forces.normal = s.normal_force;
      forces.friction = s.friction_force;
      forces.motor_torque = s.torque;
      const double phi = y[0], omega = y[1];
      const double v_load = rigid_->load_per_angle() * omega;
      q_[model_.rotor()] = phi;
      q_[model_.load()] = rigid_->load_per_angle() * phi;
      v_[model_.rotor()] = omega;
      v_[model_.load()] = v_load;
      const ChannelState state{q_,
                               v_,
                               s.axial_force,
                               rigid_->slip_per_speed() * omega,
                               0.0,
                               0.5 * (rigid_->inertia() * omega * omega + rigid_->mass() * v_load * v_load),
                               0.0};
      write_drive_channels(model_, state, forces, y + layout_.energy_offset(), impact_loss_,
                           kinetic0_, elastic0_, out);
      return;
    }
    set(t, y);
    if (p_.backlash == BacklashContact::exact && mode_.contact == ThreadContact::open)
      check_flight(t);
    const ModeSolution s = solve_current();
    forces.normal = s.normal_force;
    forces.friction = s.friction_force;
    forces.motor_torque = s.motor_torque;
    ChannelState state = channel_state(dynamics_);
    if (layout_.bristle() >= 0) {
      state.bristle = y[layout_.bristle()];
      state.elastic += y[layout_.bristle() + 1];  // the bristles' stored energy
    }
    // Stick holds the slip velocity at zero; the state carries the integrator's
    // error in this linear invariant (CVODE's Newton tolerance, ~1e-15 m/s).
    if (forces.stick) state.slip_velocity = 0.0;
    write_drive_channels(model_, state, forces, y + layout_.energy_offset(), impact_loss_,
                         kinetic0_, elastic0_, out);
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
    if (layout_.bristle() >= 0) dynamics_.set_bristle(y[layout_.bristle()]);
  }

  // The open thread's flank roots, g[2] = e - c/2 and g[3] = e + c/2, see a
  // contact as the play crossing a flank from inside the clearance: a flight
  // that starts with the play beyond a flank has its root on the crossed side
  // from the start, and if the play moves on, no sign change ever shows. A
  // touch below resolution (change_mode) restored the state as it was, a
  // round-off beyond the flank, approaching it at a round-off rate; where the
  // flight then turned back to the flank, the nut passed through it unseen
  // (flexible_nut, 5 N mm, axial force -100 + 30 sin(2 pi 20 t) N from the
  // upper flank: its flight of the first nanosecond, 1 ulp beyond it at
  // 1.04 ns, turned back at 1.16 ns; the load was 7.87 m off after 0.4 s,
  // with no event and no error). The play goes back onto the flank: the
  // positions along M^-1 grad e (as flank_impact places an impact), and a
  // rate into the flank (below resolution: see change_mode) is taken out as
  // by a plastic frictionless touch.
  void put_back_inside(double t, double* y) {
    set(t, y);
    const double half = 0.5 * p_.clearance;
    const int beyond = dynamics_.play() > half ? 1 : (dynamics_.play() < -half ? -1 : 0);
    if (beyond == 0) return;
    const PlayDirection direction = play_direction();
    const double kinetic_before = dynamics_.kinetic_energy();
    const double motor_work = beyond * dynamics_.play_rate() > 0.0 ? stop_play(t, direction) : 0.0;
    // The play sums several coordinates: where rounding leaves it beyond the
    // flank, aim inside by as much, then twice as much, and so on.
    double target = beyond * half, shift = 0.0;
    for (int attempt = 0; attempt < 16; ++attempt) {
      move_play_to(t, direction, target);
      const double excess = beyond * dynamics_.play() - half;
      if (!(excess > 0.0)) break;
      shift = std::max(2.0 * shift, excess);
      target = beyond * (half - shift);
    }
    impact_loss_ += kinetic_before + motor_work - dynamics_.kinetic_energy();
    layout_.compress(q_, v_, y);
    y[layout_.energy_offset() + kWorkDrive] += motor_work;
    set(t, y);
  }

  // The direction in which an impact and put_back_inside move the
  // coordinates to change the play: M^-1 grad e (the least kinetic energy
  // for a given play rate), with a speed-controlled rotor held at its
  // imposed speed; and the metric grad e . M^-1 grad e.
  struct PlayDirection {
    CoordinateVector along;
    double metric;
  };
  PlayDirection play_direction() const {
    const Eigen::VectorXd& w = model_.play_gradient();
    CoordinateVector along = model_.mass().cwiseInverse();
    if (p_.speed_controlled) along[model_.rotor()] = 0.0;
    along = along.cwiseProduct(w);
    return {along, w.dot(along)};
  }

  // Moves the positions along `direction` until the play is `target` (to
  // round-off), the state set.
  void move_play_to(double t, const PlayDirection& direction, double target) {
    q_ += direction.along * ((target - dynamics_.play()) / direction.metric);
    dynamics_.set_state(t, q_, v_);
  }

  // Takes the play rate out of the velocities along `direction` (a plastic
  // frictionless touch), the state set.
  // Returns the work of a speed-controlled motor's impulse at its held
  // speed: the rotor does not yield, so the thread's impulse on it, grad e_r
  // times the play impulse, is the motor's (a flank met by a moving screw
  // takes kinetic energy from the motor: booked, the account lost 1.5e-6 J).
  double stop_play(double t, const PlayDirection& direction) {
    const double impulse = dynamics_.play_rate() / direction.metric;
    v_ -= direction.along * impulse;
    dynamics_.set_state(t, q_, v_);
    if (!p_.speed_controlled) return 0.0;
    const int r = model_.rotor();
    return model_.play_gradient()[r] * impulse * v_[r];
  }

  // How far beyond a flank a free flight starts (a closed flank's drift where
  // it opens), the baseline of check_flight.
  void note_flight_start(double t, const double* y) {
    flight_start_excess_ = 0.0;
    if (p_.backlash != BacklashContact::exact || mode_.contact != ThreadContact::open) return;
    set(t, y);
    flight_start_excess_ = std::max(0.0, std::abs(dynamics_.play()) - 0.5 * p_.clearance);
  }

  // A free flight (the state set) whose play went beyond a flank by more than
  // kFlankTolerance of the clearance passed through it unseen: an error, never
  // an answer.
  void check_flight(double t) const {
    const double beyond = std::abs(dynamics_.play()) - 0.5 * p_.clearance - flight_start_excess_;
    const double tolerance =
        std::max(kFlankTolerance * p_.clearance, 10.0 * integrator_options_.atol);
    if (!(beyond <= tolerance))
      throw SimulationError(
          t,
          "the nut passed through the " + std::string(dynamics_.play() > 0.0 ? "upper" : "lower") +
              " flank of the backlash unseen: in free flight the play is " +
              format_value(beyond + flight_start_excess_) + " m beyond it (tolerance " +
              format_value(tolerance) + " m)",
          "a flank contact was missed; tighten rtol and atol, and please report the scene");
  }

  ModeSpec spec(int sigma) const {
    ModeSpec s;
    s.contact = mode_.contact;
    s.sigma = mode_.contact == ThreadContact::closed ? mode_.flank : sigma;
    s.friction = mode_.contact == ThreadContact::open ? FrictionMode::none : mode_.friction;
    s.slip_sign = mode_.slip_sign;
    return s;
  }

  // The bilateral thread's normal force at the start of a mode (the state is
  // set): its sign is the flank in contact; exactly zero leaves it open.
  void start_normal_side() {
    normal_side_ = 0;
    if (mode_.contact == ThreadContact::bilateral && mode_.friction != FrictionMode::stick &&
        mode_.friction != FrictionMode::none)
      normal_side_ = sign_of(solve_current().normal_force);
  }

  // Root function of a flank change of the thread without play: the normal
  // force on the side it pushes, falling through zero. A normal force that is
  // exactly zero at the start of a mode (a flexible drive whose springs are
  // relaxed at t = 0 transmits no load yet) has no side: until it leaves zero
  // the root is |N|, which cannot change sign, and the side it leaves to
  // becomes the flank (|N| = side N there, so the root stays continuous).
  // Leaving zero is not a flank change; passing through it is.
  double flank_change_root(double normal_force) {
    if (normal_side_ == 0) normal_side_ = sign_of(normal_force);
    return normal_side_ != 0 ? normal_side_ * normal_force : 0.0;
  }

  // The stick limit mu_static' of the law (mu' itself for one coefficient).
  double stick_mu() const {
    return dynamics_.law().plain_coulomb() ? model_.effective_mu() : model_.effective_mu_static();
  }

  // The motor prescribes the slip (DriveDynamics::slip_prescribed) while the
  // thread's normal constraint is active.
  bool slip_prescribed_now() const {
    return dynamics_.slip_prescribed() && (mode_.contact == ThreadContact::bilateral ||
                                           mode_.contact == ThreadContact::closed);
  }

  // True if the thread forces of the current mode depend on the loads alone
  // (linearly): the rigid drive (no springs, no dampers) with a
  // torque-driven rotor and exact Coulomb friction on the thread without play
  // or a closed flank, in stick (every coordinate locked) or slip (the
  // friction factor +-mu' is constant).
  bool load_driven() const {
    return p_.concept == Concept::rigid && model_.springs().empty() && !p_.speed_controlled &&
           dynamics_.law().plain_coulomb() &&
           (mode_.contact == ThreadContact::bilateral || mode_.contact == ThreadContact::closed) &&
           (mode_.friction == FrictionMode::stick || mode_.friction == FrictionMode::slip);
  }

  // The thread forces of the current mode per unit drive torque and axial
  // force (normal-force sign sigma where it matters).
  RigidModeCoefficients mode_coefficients(int sigma) {
    if (rigid_) return rigid_->coefficients(mode_.friction, mode_.slip_sign, sigma);
    const int n = model_.coordinate_count();
    CoordinateVector unit_torque = CoordinateVector::Zero(n), unit_force = unit_torque;
    unit_torque[model_.rotor()] = 1.0;
    unit_force[model_.load()] = 1.0;
    const ModeSolution torque = dynamics_.solve_with_forces(spec(sigma), unit_torque);
    const ModeSolution force = dynamics_.solve_with_forces(spec(sigma), unit_force);
    RigidModeCoefficients c;
    if (!torque.regular || !force.regular) return c;
    c.normal_force = {torque.normal_force, force.normal_force};
    c.friction_force = {torque.friction_force, force.friction_force};
    return c;
  }

  // At the start of a mode whose thread forces are load-driven, the stick
  // cone's margin (stick) or the normal force on its side (slip) is a function
  // of time alone: its first zero is found by first_load_crossing, and the
  // root function becomes the time left until it, load_root_time_ - t, which
  // falls through zero exactly there however short the excursion beyond it.
  // (The margin sampled at the integrator's steps missed a 13 ms excursion out
  // of the cone with steps of 21 ms.)
  void plan_load_roots(double t) {
    load_root_ = -1;
    load_root_time_ = std::numeric_limits<double>::infinity();
    if (!load_driven()) return;
    const double torque = p_.drive_torque(t), force = p_.axial_force(t);
    LoadCoefficients functions[2];
    int count = 0, slot = -1;
    if (mode_.friction == FrictionMode::stick) {
      // |T| <= mu' |N| as the two factors mu' s N -+ T, with s the side of N
      // at the start: before N could change sides, |T| would have to fall to
      // zero with it, so one factor crosses first.
      const RigidModeCoefficients c = mode_coefficients(1);
      int side = sign_of(c.normal_force(torque, force));
      if (side == 0)
        side = sign_of(c.normal_force(p_.drive_torque.derivative(t), p_.axial_force.derivative(t)));
      if (side == 0) return;  // no load on the thread: the sampled margin decides
      const double mu = stick_mu();
      for (int s : {1, -1})
        functions[count++] = {mu * side * c.normal_force.per_torque - s * c.friction_force.per_torque,
                              mu * side * c.normal_force.per_force - s * c.friction_force.per_force};
      slot = 0;
    } else {
      // The normal force leaving its side: a flank change (bilateral) or the
      // flank opening (closed).
      const int side = mode_.contact == ThreadContact::closed ? mode_.flank : normal_side_;
      if (side == 0) return;  // not left zero yet (flank_change_root)
      const RigidModeCoefficients c = mode_coefficients(side);
      functions[count++] = {side * c.normal_force.per_torque, side * c.normal_force.per_force};
      slot = 1;
    }
    const std::optional<double> crossing =
        first_load_crossing(p_.drive_torque, p_.axial_force, functions, count, t, t_end_);
    if (!crossing) return;  // a callable load: no curvature bound
    load_root_ = slot;
    load_root_time_ = *crossing;
  }

  // The slip velocity the integrator resolves: its absolute tolerance on the
  // velocities through the slip's gradient (|W_T| atol).
  double slip_resolution() const {
    if (rigid_) return std::abs(rigid_->slip_per_speed()) * integrator_options_.atol;
    return model_.tangent_direction().cwiseAbs().sum() * integrator_options_.atol;
  }

  double load_root_value(double t) const {
    return std::isfinite(load_root_time_) ? load_root_time_ - t : 1.0;
  }

  struct RigidSolution {
    double torque = 0.0, axial_force = 0.0;
    double acceleration = 0.0, normal_force = 0.0, friction_force = 0.0;
  };

  // The rigid drive's forces and acceleration at (t, y) from the coefficients
  // of its mode (RigidDriveModes): the decisions of solve_current without the
  // constrained solve. Outside the Painleve regime at most one normal-force
  // sign is consistent: try the last one first.
  RigidSolution solve_rigid(double t, const double* y) {
    RigidSolution s;
    if (t != loads_time_) {  // the roots at a step's end follow its last stage
      loads_time_ = t;
      torque_ = p_.drive_torque(t);
      axial_force_ = p_.axial_force(t);
    }
    s.torque = torque_;
    s.axial_force = axial_force_;
    const bool slip = mode_.friction == FrictionMode::slip;
    for (int attempt = 0; attempt < 2; ++attempt) {
      const RigidModeCoefficients& c =
          rigid_->coefficients(mode_.friction, mode_.slip_sign, slip ? sigma_guess_ : 1);
      s.normal_force = c.normal_force(s.torque, s.axial_force);
      if (slip && sigma_guess_ * s.normal_force < 0.0) {
        sigma_guess_ = -sigma_guess_;
        continue;
      }
      s.acceleration = c.acceleration(s.torque, s.axial_force);
      s.friction_force = c.friction_force(s.torque, s.axial_force);
      return s;
    }
    set(t, y);  // the state for the report
    jam("no sign of the flank normal force is consistent");
  }

  // The regularized law on the thread without play in a model where the
  // Painleve paradox is possible (mu' |G_NT| >= G_NN): its friction factor
  // kappa = (2/pi) mu' atan(k_V gamma_T) depends on the slip velocity, and
  // the paradox begins where kappa |G_NT| reaches G_NN.
  bool watch_fold() const {
    return mode_.contact == ThreadContact::bilateral &&
           (mode_.friction == FrictionMode::regularized_velocity ||
            mode_.friction == FrictionMode::bristle) &&
           dynamics_.painleve_possible();
  }
  double current_kappa() const { return dynamics_.friction_factor(spec(sigma_guess_), 0.0); }
  // The regularized law's Painleve margin at the state set: min over sigma of
  // G_NN - sigma kappa G_NT, relative to G_NN (<= 0: both signs of the flank
  // normal force consistent, or neither).
  double fold_margin() const {
    const double kappa = current_kappa();
    return std::min(dynamics_.thread_denominator(1, kappa),
                    dynamics_.thread_denominator(-1, kappa)) /
           dynamics_.delassus_normal();
  }

  [[noreturn]] void jam_regularized(const std::string& what) const {
    throw JammingError(dynamics_.time(),
                       "dynamic jamming: " + what + "; " +
                           dynamics_.jamming_report(std::abs(current_kappa())),
                       "the drive self-locks dynamically (Painleve paradox of the regularized "
                       "friction law); reduce the friction or change the inertia ratio");
  }

  // The denominator S of the current branch fell below kFoldWatch G_NN. If it
  // reaches zero, the slip velocity stays finite while the acceleration grows
  // like 1/S: the trajectory ends there in finite time with a square-root
  // singularity, the onset of jamming, which no step in t can cross or
  // resolve. In the time s with dt/ds = S the same trajectory is smooth
  // through it (dz/ds = S (1, f(t, y)), S f finite), and S = 0 is an ordinary
  // root: integrate it from (t, y) until S = 0 (JammingError at that time and
  // state, to the integration tolerance), S back above 2 kFoldWatch G_NN or
  // t_end (the main integration then continues: no event).
  void approach_fold(double t, const double* y) {
    // The branch's denominator at or below zero here: the onset is now (in
    // the time s, t would run backwards from here: a JammingError 0.23 s
    // before the run began).
    if (!(dynamics_.thread_denominator(sigma_guess_, current_kappa()) > 0.0))
      jam_regularized("the branch of the flank normal force ends here (its denominator "
                      "G_NN - sigma kappa G_NT is not positive)");
    FoldApproach fold(*this);
    integrate::IntegratorOptions options;
    options.rtol = integrator_options_.rtol;
    options.atol = integrator_options_.atol;
    options.max_steps = integrator_options_.max_steps;
    std::unique_ptr<integrate::Integrator> integrator =
        integrate::make_integrator("rk_verner6", options);
    Eigen::VectorXd z(size() + 1);
    z[0] = t;
    for (int k = 0; k < size(); ++k) z[k + 1] = y[k];
    const int saved_sigma = sigma_guess_;
    integrator->initialize(fold, 0.0, z);
    // dt/ds >= S, which stays above zero until the onset: every s beyond
    // (t_end - t) / S_min reaches t_end; S_min is only bounded by the root.
    const double s_end = 1e12 * (t_end_ - t + 1.0) / dynamics_.delassus_normal();
    integrate::AdvanceResult step;
    try {
      step = integrator->advance(s_end, z);
    } catch (const JammingError&) {
      throw;
    } catch (const SimulationError& e) {
      // The integrator's time is s: report the drive's own, t.
      throw SimulationError(fold.time(), e.reason(),
                            "while following the regularized law toward its Painleve regime");
    }
    if (step.status == integrate::AdvanceStatus::root_found && integrator->root_info()[0] != 0) {
      set(z[0], z.data() + 1);
      solve_current();
      jam_regularized("the branch of the flank normal force ends (its denominator "
                      "G_NN - sigma kappa G_NT reaches zero, the acceleration grows without "
                      "bound)");
    }
    sigma_guess_ = saved_sigma;
    set(t, y);
  }

  // The drive's equations in the time s with dt/ds = S (approach_fold).
  class FoldApproach final : public integrate::OdeSystem {
   public:
    explicit FoldApproach(DriveHybrid& drive) : drive_(drive) {}
    int size() const override { return drive_.size() + 1; }
    double time() const { return time_; }  // t of the last right-hand side
    void rhs(double /*s*/, const double* z, double* dz) override {
      time_ = z[0];
      drive_.rhs(z[0], z + 1, dz + 1);
      const double denominator = branch();
      dz[0] = denominator;
      for (int k = 1; k < size(); ++k) dz[k] *= denominator;
    }
    int root_count() const override { return 3; }
    void roots(double /*s*/, const double* z, double* g) override {
      drive_.set(z[0], z + 1);
      drive_.solve_current();
      const double relative = branch() / drive_.dynamics_.delassus_normal();
      // The onset, within round-off of G_NN: a branch that approaches it
      // asymptotically in s (reaching it only as t tends to a limit) took a
      // million steps and ended at an 's' of 1178 'seconds'.
      g[0] = relative - 64.0 * std::numeric_limits<double>::epsilon();
      g[1] = 2.0 * kFoldWatch - relative;    // the branch recovers
      g[2] = drive_.t_end_ - z[0];           // the end of the simulation
    }

   private:
    double branch() const {
      return drive_.dynamics_.thread_denominator(drive_.sigma_guess_, drive_.current_kappa());
    }
    DriveHybrid& drive_;
    double time_ = 0.0;
  };

  // Eq. (3.15) has `count` consistent flank forces at the state set. For the
  // rigid drive (no springs, no dampers) they depend on the time alone (the
  // loads; the law does not depend on the velocity), so the onset of the
  // ambiguity lies between the last time with one solution and now: located
  // by bisection on the count, to round-off. (A flexible drive's depend on
  // its state: raised where first seen, at the integrator's resolution.)
  [[noreturn]] void jam_acceleration_law(int count) {
    double onset = dynamics_.time();
    if (model_.springs().empty() && last_unique_time_ < onset) {
      const CoordinateVector q = q_, v = v_;
      double low = last_unique_time_, high = onset;
      for (int iteration = 0; iteration < 200 && high - low > 2.0 * std::numeric_limits<double>::epsilon() * std::abs(high); ++iteration) {
        const double middle = 0.5 * (low + high);
        dynamics_.set_state(middle, q, v);
        const int n = dynamics_.solve(spec(sigma_guess_)).consistent_solutions;
        (n == 1 ? low : high) = middle;
        if (n != 1) count = n;
      }
      onset = high;
      dynamics_.set_state(onset, q, v);
    }
    throw JammingError(
        onset,
        "dynamic jamming: eq. (3.15) admits " + std::to_string(count) +
            " consistent flank forces from here: its friction factor kappa = (2/pi) mu' "
            "atan(k_V gamma_T') depends on the slip acceleration it produces, so a solution "
            "always exists, and it is unique unless mu' |G_NT| >= G_NN (the exact law's "
            "Painleve condition; then several exist where |kappa| exceeds G_NN / |G_NT| "
            "between them); " + dynamics_.jamming_report(),
        "the drive self-locks dynamically (Painleve paradox of the acceleration-dependent "
        "friction law); reduce the friction or change the inertia ratio");
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
                                    mode_.friction == FrictionMode::regularized_acceleration ||
                                    mode_.friction == FrictionMode::bristle;
    if (mode_.contact == ThreadContact::bilateral &&
        mode_.friction == FrictionMode::regularized_acceleration && dynamics_.painleve_possible()) {
      // Eq. (3.15): every consistent flank force at once (DriveDynamics::
      // solve_acceleration_law); there is always one, several are jamming.
      const ModeSolution s = dynamics_.solve(spec(sigma_guess_));
      if (!s.regular)
        throw SimulationError(dynamics_.time(), "the constraint equations of the drive are singular",
                              "check masses, inertias and the thread geometry");
      if (s.consistent_solutions != 1) jam_acceleration_law(s.consistent_solutions);
      if (s.normal_force != 0.0) sigma_guess_ = sign_of(s.normal_force);
      last_unique_time_ = std::max(last_unique_time_, dynamics_.time());
      return s;
    }
    if (mode_.contact == ThreadContact::bilateral && friction_on_normal &&
        !dynamics_.painleve_possible()) {
      // At most one sign can be consistent: try the last one first.
      for (int attempt = 0; attempt < 2; ++attempt) {
        const ModeSolution s = dynamics_.solve(spec(sigma_guess_));
        if (s.regular && sigma_guess_ * s.normal_force >= 0.0) return s;
        sigma_guess_ = -sigma_guess_;
      }
      jam("no sign of the flank normal force is consistent");
    }
    if (mode_.contact == ThreadContact::bilateral && friction_on_normal) {
      const ModeSolution plus = dynamics_.solve(spec(1));
      const ModeSolution minus = dynamics_.solve(spec(-1));
      const bool plus_ok = plus.regular && plus.normal_force >= 0.0;
      const bool minus_ok = minus.regular && minus.normal_force <= 0.0;
      if (watch_fold()) {
        // The paradox of the regularized law is located by its roots (the
        // margin, the branch's denominator; approach_fold). Between them keep
        // the current sign's branch: where both are consistent it is the
        // continuous one, and where neither is (a trial state of the
        // integrator beyond the onset) its continuation, so that the step is
        // rejected, not the simulation ended at a state off the trajectory.
        const ModeSolution& current = sigma_guess_ > 0 ? plus : minus;
        const bool current_ok = sigma_guess_ > 0 ? plus_ok : minus_ok;
        const bool other_ok = sigma_guess_ > 0 ? minus_ok : plus_ok;
        if (current_ok || (!other_ok && current.regular)) return current;
        if (other_ok) {
          sigma_guess_ = -sigma_guess_;
          return sigma_guess_ > 0 ? plus : minus;
        }
        jam("the constraint equations of the thread are singular");
      }
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

  // A flank closed by an impact (or a grazing touch) whose normal force would
  // pull opens at once: the contact is unilateral, as a closed flank opens
  // where its normal force falls through zero (the root g[1] cannot see a
  // force that starts on the wrong side). Solves the current mode.
  void open_if_pulling() {
    const ModeSolution s = solve_current();
    if (mode_.contact != ThreadContact::closed || mode_.flank * s.normal_force >= 0.0) return;
    mode_.contact = ThreadContact::open;
    mode_.friction = FrictionMode::none;
    mode_.slip_sign = 0;
  }

  // Stick or slip: from the slip velocity, or at zero slip by the flank LCP.
  void decide_friction(double t, double* y, bool at_zero_slip, int hint) {
    (void)t;
    const friction::Resolution resolution = dynamics_.law().resolution();
    const bool regularized = resolution != friction::Resolution::set_valued;
    // A regularized law's friction on a penalty flank follows its penetration
    // (zero where it has none): no contact mode to track.
    if (mode_.contact == ThreadContact::open || model_.effective_mu() == 0.0 ||
        (mode_.contact == ThreadContact::penalty && !touching_ && !regularized)) {
      // No contact (an open play, or a penalty flank not penetrated), or a
      // frictionless flank: no stick, no slip, no friction events.
      mode_.friction = FrictionMode::none;
      mode_.slip_sign = 0;
      open_if_pulling();
      return;
    }
    if (regularized) {
      mode_.friction = resolution == friction::Resolution::velocity ? FrictionMode::regularized_velocity
                       : resolution == friction::Resolution::acceleration
                           ? FrictionMode::regularized_acceleration
                           : FrictionMode::bristle;
      open_if_pulling();
      return;
    }
    // A slip velocity at the level of its own round-off has no sign to take.
    if (!at_zero_slip && std::abs(dynamics_.slip_velocity()) > dynamics_.slip_noise()) {
      mode_.friction = FrictionMode::slip;
      mode_.slip_sign = sign_of(dynamics_.slip_velocity());
      open_if_pulling();  // raises JammingError if no normal-force sign is consistent
      return;
    }
    ModeSpec base = spec(1);
    base.friction = FrictionMode::none;
    if (slip_prescribed_now()) {
      // The motor prescribes every velocity: its slip acceleration decides
      // (no projection: the velocities are the motor's).
      const friction::FlankLcpResult r = dynamics_.prescribed_slip_decision(
          base, mode_.contact == ThreadContact::closed ? mode_.flank : 0);
      ++lcp_solves_;
      if (!r.consistent && mode_.contact == ThreadContact::closed) {
        mode_.contact = ThreadContact::open;  // the flank cannot push: it opens
        mode_.friction = FrictionMode::none;
        mode_.slip_sign = 0;
        return;
      }
      if (!r.consistent)
        jam("the prescribed motion needs a flank normal force of neither sign");
      mode_.friction = r.slip_acceleration == 0.0 ? FrictionMode::stick : FrictionMode::slip;
      mode_.slip_sign = sign_of(r.slip_acceleration);
      return;
    }
    // Zero slip: project the velocities onto exactly zero slip (the root is
    // located to round-off), then let the LCP decide.
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
    // The normal-force signs to try: the penalty force's, the closed flank's, or both.
    int sigmas[2] = {1, -1};
    int sigma_count = 2;
    if (mode_.contact == ThreadContact::penalty) {
      sigmas[0] = beta >= 0.0 ? 1 : -1;
      sigma_count = 1;
    } else {
      beta = without.normal_force;
      alpha = unit.normal_force - beta;
      if (mode_.contact == ThreadContact::closed) {
        sigmas[0] = mode_.flank;
        sigma_count = 1;
      }
    }
    // One coefficient: the thesis's LCP decides stick and slip at once. A
    // static coefficient above the kinetic one: stick wherever the force
    // that sticks lies in mu_static''s cone (its normal force on the
    // flank's side); otherwise the LCP at the slip's coefficient at zero
    // speed, mu(0+)', gives the slip's direction (no stick: it is not
    // admissible even with the larger coefficient).
    const friction::Law& law = dynamics_.law();
    double lcp_mu = model_.effective_mu();
    const int stick_side = mode_.contact == ThreadContact::closed ? mode_.flank
                           : mode_.contact == ThreadContact::penalty ? sigmas[0]
                                                                     : 0;
    const bool stick_admissible =
        hint == 0 && friction::flank_stick(c, d, alpha, beta, stick_mu(), stick_side).consistent;
    if (!law.plain_coulomb()) {
      if (stick_admissible) {
        mode_.friction = FrictionMode::stick;
        mode_.slip_sign = 0;
        return;
      }
      lcp_mu = law.slip_mu(0.0) * model_.flank_factor();
    }
    int found = 0;
    bool ambiguous = false;
    Mode chosen = mode_;
    for (int k = 0; k < sigma_count; ++k) {
      const friction::FlankLcpResult r =
          solve_flank_lcp_scaled(c, d, alpha, beta, lcp_mu, sigmas[k], lcp_workspace_,
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
    if (found == 0 && mode_.contact == ThreadContact::closed && !stick_admissible) {
      // No friction mode keeps the normal force on this flank's side: the
      // flank opens (the contact is unilateral). (In the Painleve regime the
      // LCP of the flank's sign can miss a stick that holds it: a rigid
      // drive at rest on its loaded flank opened and jammed at its first
      // impact, 2.6e-11 s later.)
      mode_.contact = ThreadContact::open;
      mode_.friction = FrictionMode::none;
      mode_.slip_sign = 0;
      return;
    }
    if (found == 0 || ambiguous) {
      // In the Painleve regime (mu' |G_NT| >= G_NN) the LCP of one normal-force
      // sign may have no solution or admit a spurious slip start. At zero slip
      // the drive keeps sticking whenever stick is admissible
      // (docs/physics/rigid_drive.md, "uniqueness"); otherwise it jams.
      if (stick_admissible) {
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

  // The play's acceleration e'' in free flight (the thread open) at the state
  // set: how far a flight would rise (flank_impact) or a slow approach go
  // beyond a flank (change_mode's touch below resolution).
  double free_flight_play_acceleration() {
    const Mode saved = mode_;
    mode_.contact = ThreadContact::open;
    mode_.friction = FrictionMode::none;
    const ModeSolution flight = solve_current();
    mode_ = saved;
    return model_.play_gradient().dot(flight.acceleration);
  }

  // An exact flank closes: Newton's impact law with Coulomb friction on the
  // impulses. Returns true if the impact ends with zero slip.
  bool flank_impact(double t, double* y, int flank) {
    const PlayDirection direction = play_direction();
    // Place the play exactly on the flank (the root is located to round-off).
    move_play_to(t, direction, flank > 0 ? -0.5 * p_.clearance : 0.5 * p_.clearance);
    const double kinetic_before = dynamics_.kinetic_energy();
    auto close_flank = [&]() {
      // Plastic, grazing or too weak to fly: the flank stays closed with zero
      // normal velocity (the closed flank opens again at once if it cannot push).
      // The normal velocity taken out is the impact's loss too (unbooked, a
      // weak bounce's energy went missing from the account: 5e-4 of the work
      // of a rattling nut with restitution 0.5).
      const double kinetic_open = dynamics_.kinetic_energy();
      const double closing_work = stop_play(t, direction);
      y[layout_.energy_offset() + kWorkDrive] += closing_work;
      impact_loss_ += kinetic_open + closing_work - dynamics_.kinetic_energy();
      mode_.contact = ThreadContact::closed;
      mode_.flank = flank;
    };
    if (flank * dynamics_.play_rate() >= 0.0) {
      // Grazing: the play touches the flank without approaching it; no impulse.
      close_flank();
      return dynamics_.slip_velocity() == 0.0;
    }
    DriveDynamics::Impulses impulses;
    // The impact at restitution e: v_ from before it, and the energy it
    // dissipates (kinetic energy lost plus the speed-controlled motor's
    // impulsive work at its held speed).
    const CoordinateVector v_before = v_;
    double motor_work = 0.0;
    auto collide = [&](double e) {
      v_ = v_before;
      ++lcp_solves_;
      if (!dynamics_.impact(flank, e, v_, impulses, lcp_workspace_, lcp_options_))
        jam("no consistent frictional impact");
      motor_work = p_.speed_controlled ? impulses.rotor * v_[model_.rotor()] : 0.0;
      dynamics_.set_state(t, q_, v_);
      return kinetic_before + motor_work - dynamics_.kinetic_energy();
    };
    double dissipated = collide(p_.restitution);
    const double round_off = 64.0 * std::numeric_limits<double>::epsilon() *
                             (kinetic_before + std::abs(motor_work));
    if (dissipated < -round_off) {
      // Newton's restitution with Coulomb friction can create energy (Kane
      // and Levinson's paradox: a rigid nut's first impact at e = 0.48 gained
      // 0.0155 J): the impact takes the largest restitution up to e that
      // creates none, as an energetic coefficient of restitution would
      // (Stronge). A plastic frictional impact dissipates (its impulses
      // solve the LCP of maximal dissipation), so bisection on [0, e] finds it.
      double low = 0.0, high = p_.restitution;
      for (int iteration = 0; iteration < 60; ++iteration) {
        const double middle = 0.5 * (low + high);
        (collide(middle) >= -round_off ? low : high) = middle;
      }
      dissipated = collide(low);
    }
    // The motor's work enters the drive's work as well as the impact's loss
    // (booked in the loss alone, 4 % of the work went missing from the account).
    y[layout_.energy_offset() + kWorkDrive] += motor_work;
    impact_loss_ += dissipated;
    const double normal_after = dynamics_.play_rate();
    // Height of the flight the bounce would start: v^2 / (2 |e''|) with the
    // play's acceleration in free flight; see kPlasticHeight.
    const double play_acceleration = free_flight_play_acceleration();
    const bool pushed_back = flank * play_acceleration < 0.0;
    const double height = pushed_back ? normal_after * normal_after / (2.0 * std::abs(play_acceleration))
                                      : std::numeric_limits<double>::infinity();
    if (std::abs(normal_after) <= bounce_threshold_ || height <= kPlasticHeight * p_.clearance) {
      close_flank();
      // Zero slip only where the impulse LCP chose stick (its post-impact
      // slip velocity carries round-off, which decide_friction projects away).
      return impulses.sticks || dynamics_.slip_velocity() == 0.0;
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
  bool touching_ = false;  // a penalty flank is penetrated
  int sigma_guess_ = 1;    // last consistent sign of the bilateral normal force
  int bounced_from_ = 0;   // the flank of the last bounce until the flight's apex
  std::vector<double> saved_state_;  // y before a touch below resolution (handle_event)
  double saved_impact_loss_ = 0.0;   // and impact_loss_
  double flight_start_excess_ = 0.0;  // the play beyond a flank at the start of a flight
  int normal_side_ = 0;    // sign of the bilateral normal force in this mode (0: not left zero)
  double last_unique_time_ = 0.0;  // eq. (3.15) last seen with one solution (jam_acceleration_law)
  double slip_offset_ = 0.0;
  bool slip_noise_event_ = false;  // an event of g0 kept the same slip mode (start_mode)  // round-off of the slip velocity against a slip mode's sign at its start
  bool stick_from_zero_ = false;  // a stick mode whose cone margin has not left zero
  int load_root_ = -1;     // the root function replaced by a load-driven crossing (-1: none)
  double load_root_time_ = std::numeric_limits<double>::infinity();  // its time
  double t_end_;
  integrate::IntegratorOptions integrator_options_;
  std::optional<RigidDriveModes> rigid_;  // the one-degree-of-freedom rigid drive
  double loads_time_ = std::numeric_limits<double>::quiet_NaN();  // the loads last evaluated
  double torque_ = 0.0, axial_force_ = 0.0;
  Mode mode_;
  CoordinateVector q_, v_;
  std::vector<std::string> names_;
  double kinetic0_ = 0.0, elastic0_ = 0.0, impact_loss_ = 0.0;
  long lcp_solves_ = 0;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
};

// ---------------------------------------------------------------------------
// Moreau-Jean time stepping for the drive. On the velocity level, with the
// theta method for springs and dampers made implicit through the iteration
// matrix W = M + theta h C + theta^2 h^2 K (the flexible models are stiff):
//   W v+ = M v + h f - theta (1 - theta) h^2 K v + theta h C v + impulses,
//   q+   = q + h ((1 - theta) v + theta v+).
// Impulses: the thread's normal impulse (a multiplier: bilateral without play,
// or on a flank the predicted position closes, with Newton's law
// W_N v+ = -e W_N v), the friction impulse from the flank LCP on the velocity
// level (maximal dissipation), and the speed-controlled rotor's.
class DriveMoreau final : public integrate::TimeSteppingSystem {
 public:
  explicit DriveMoreau(const DriveModel& model)
      : model_(model), p_(model.parameters()), dynamics_(model), layout_(model, false),
        names_(drive_channel_names(model)) {
    const int n = model.coordinate_count();
    q_.setZero(n);
    v_.setZero(n);
  }

  int size() const override { return layout_.size(); }
  const std::vector<std::string>& channel_names() const override { return names_; }
  long lcp_solves() const override { return lcp_solves_; }
  // For the checks (ResultCheckSpec): the play's largest rate over the
  // steps [m/s], the friction impulses' booking beyond the steps' work [J].
  double largest_play_rate() const { return play_rate_; }
  double friction_excess() const { return friction_excess_; }

  void initialize(double t, const double* y) {
    layout_.expand(t, y, q_, v_);
    dynamics_.set_state(t, q_, v_);
    kinetic0_ = dynamics_.kinetic_energy();
    elastic0_ = dynamics_.elastic_energy();
  }

  void step(double t, double h, double theta, const double* y, double* y_next) override {
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

  // One step at restitution e; true where it closes a flank with e > 0.
  bool take_step(double t, double h, double theta, const double* y, double* y_next,
                 double restitution) {
    layout_.expand(t, y, q_, v_);
    const CoordinateVector q0 = q_, v0 = v_;
    bool restituting = false;
    dynamics_.set_state(t + theta * h, q_, v_);
    const double play0 = dynamics_.play();
    const double play_rate0 = dynamics_.play_rate();

    // Iteration matrix and free velocity.
    Square stiffness, damping;
    assemble(h, theta, stiffness, damping);
    CoordinateVector rhs = model_.mass().cwiseProduct(v0) + h * dynamics_.forces() -
                           theta * (1.0 - theta) * h * h * (stiffness * v0) +
                           theta * h * (damping * v0);
    free_ = solver_.solve(rhs);

    // Which thread contact is active in this step.
    int sigma_fixed = 0;  // 0: bilateral (sign free); +-1: a flank
    bool contact = true;
    double normal_target = 0.0;
    if (p_.backlash == BacklashContact::exact) {
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
    const double rotor_target = p_.speed_controlled ? p_.drive_speed(t + h) : 0.0;

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
    if (p_.backlash == BacklashContact::exact && !contact)
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
                                             : p_.drive_torque(t + theta * h) *
                                                   (q_[model_.rotor()] - q0[model_.rotor()]);
    energy[kWorkDrive] += motor;
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
    for (const Spring& spring : model_.springs()) {
      const double rate = v_theta[spring.first] - (spring.second >= 0 ? v_theta[spring.second] : 0.0);
      damping_power += spring.damping * rate * rate;
    }
    energy[kDampingLoss] += h * damping_power;
    last_.normal = impulses.normal / h;
    last_.friction = impulses.friction / h;
    last_.motor_torque =
        p_.speed_controlled ? impulses.rotor / h : p_.drive_torque(t + h);
    last_.stick = contact && stick;
    return restituting;
  }

  // The energy a step from y to y_next creates: what the stored energy
  // gains beyond the work in less the losses booked (the residual's fall),
  // and the round-off of that account (of its largest term).
  struct StepAccount {
    double created = 0.0, round_off = 0.0;
  };
  StepAccount energy_created(double t, double h, const double* y, const double* y_next) {
    double largest = 0.0;
    auto account = [&](double time, const double* state) {
      layout_.expand(time, state, q_, v_);
      dynamics_.set_state(time, q_, v_);
      const double* energy = state + layout_.energy_offset();
      const double stored = dynamics_.kinetic_energy() + dynamics_.elastic_energy();
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

  void channels(double t, const double* y, double* out) override {
    layout_.expand(t, y, q_, v_);
    dynamics_.set_state(t, q_, v_);
    const double* energy = y + layout_.energy_offset();
    // The Moreau-Jean scheme's numerical dissipation (and impacts) closes the
    // account: what the work and the named losses leave over.
    ChannelState state = channel_state(dynamics_);
    if (last_.stick) state.slip_velocity = 0.0;  // the step's stick: zero slip (as above)
    write_drive_channels(model_, state, last_, energy, 0.0, kinetic0_,
                         elastic0_, out);
  }

 private:
  using Square =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates, kMaxCoordinates>;

  struct Impulses {
    CoordinateVector velocity;
    double normal = 0.0, friction = 0.0, rotor = 0.0;
  };

  // The iteration matrix W = M + theta h C + theta^2 h^2 K at the positions
  // q_ (factored into solver_), and its stiffness and damping matrices.
  void assemble(double h, double theta, Square& stiffness, Square& damping) {
    const int n = model_.coordinate_count();
    stiffness = Square::Zero(n, n);
    damping = Square::Zero(n, n);
    const double a = model_.nut_position(q_.data());
    for (const Spring& spring : model_.springs()) {
      double derivative = 0.0;
      const double k = model_.spring_stiffness(spring, a, &derivative);
      add_pair(stiffness, spring.first, spring.second, k);
      add_pair(damping, spring.first, spring.second, spring.damping);
    }
    Square iteration = theta * h * damping + theta * theta * h * h * stiffness;
    iteration.diagonal() += model_.mass();
    solver_.compute(iteration);
  }

  // The step's coupling of the flank's friction impulse into its normal
  // impulse, alpha = dP_N / dP_T, at the positions q_: W^-1 in place of
  // M^-1 in the Delassus terms, alpha = -G~_NT / G~_NN (the rotor held
  // where speed-controlled). For h -> 0 it is the drive's own.
  double step_coupling(double h, double theta) {
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
  std::string step_too_long(double theta, double alpha) {
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
  double resolving_step(double h, double theta) {
    const CoordinateVector free = free_;
    double low = 0.0, high = h;
    for (int iteration = 0; iteration < 60; ++iteration) {
      const double middle = 0.5 * (low + high);
      (model_.effective_mu() * std::abs(step_coupling(middle, theta)) < 1.0 ? low : high) = middle;
    }
    free_ = free;
    return low;
  }

 public:
  // Refuses a step whose flank problem is Painleve-like at the start (see
  // step_too_long); initialize() first.
  void check_step(double h, double theta) {
    if (dynamics_.painleve_possible()) return;  // the drive's own condition decides
    const double alpha = step_coupling(h, theta);
    if (model_.effective_mu() * std::abs(alpha) >= 1.0)
      throw InvalidArgument("dt = " + format_value(h) + " is invalid: must be < " +
                            format_value(resolving_step(h, theta)) +
                            " s for the stiffness of this drive: " +
                            step_too_long(theta, alpha));
  }

 private:
  static void add_pair(Square& matrix, int i, int j, double value) {
    matrix(i, i) += value;
    if (j >= 0) {
      matrix(j, j) += value;
      matrix(i, j) -= value;
      matrix(j, i) -= value;
    }
  }

  // v+ = free + W^-1 (B lambda + tangential W_T) with the active velocity
  // constraints: W_N v+ = normal_target (thread), e_rotor v+ = rotor_target.
  Impulses solve(bool thread, double normal_target, double rotor_target, double tangential) {
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

  const DriveModel& model_;
  const DriveParameters& p_;
  DriveDynamics dynamics_;
  StateLayout layout_;
  std::vector<std::string> names_;
  CoordinateVector q_, v_, free_;
  Eigen::LLT<Square> solver_;
  ContactForces last_;
  double kinetic0_ = 0.0, elastic0_ = 0.0;
  double play_rate_ = 0.0, friction_excess_ = 0.0;
  long lcp_solves_ = 0;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
};

}  // namespace

const std::vector<std::string>& drive_integrators(const DriveParameters& p) {
  // From the law's type (friction/law.hpp): a set-valued law runs in the
  // event-driven scheme, in Moreau-Jean's time stepping, and where it has a
  // regularization in the ODE methods; a smooth law in the ODE methods and
  // the event-driven scheme. Moreau-Jean's step handles exact flank contacts
  // only (not penalty flanks), and exact play needs the event-driven
  // scheme's flank events with every law but for Moreau-Jean's.
  static const std::vector<std::string> event_driven_only = {"event_driven"};
  static const std::vector<std::string> with_moreau = {"event_driven", "moreau"};
  static const std::vector<std::string> smooth = [] {
    std::vector<std::string> names = integrate::integrator_names();
    names.push_back("event_driven");
    return names;
  }();
  static const std::vector<std::string> set_valued_all = [] {
    std::vector<std::string> names = {"event_driven", "moreau"};
    for (const std::string& name : integrate::integrator_names()) names.push_back(name);
    return names;
  }();
  static const std::vector<std::string> set_valued_ode = [] {
    std::vector<std::string> names = {"event_driven"};
    for (const std::string& name : integrate::integrator_names()) names.push_back(name);
    return names;
  }();
  const friction::LawType& type = friction::law_type(p.friction);
  const bool penalty = p.backlash == BacklashContact::bistop || p.backlash == BacklashContact::cubic;
  const bool exact_play = p.backlash == BacklashContact::exact;
  if (type.time_stepping) {  // set-valued
    if (penalty) return type.ode ? set_valued_ode : event_driven_only;
    if (exact_play) return with_moreau;
    return type.ode ? set_valued_all : with_moreau;
  }
  if (exact_play) return event_driven_only;
  return smooth;
}

namespace {

// The integrator simulate() runs ("" in the options: the model's default).
const std::string& chosen_integrator(const DriveParameters& p,
                                     const DriveSimulationOptions& options) {
  return options.integrator.empty() ? drive_integrators(p).front() : options.integrator;
}

// The ODE method of the smooth phases: the integrator itself, or inside
// "event_driven" the smooth_integrator option (default: our Verner 6(5)
// with exact event location for the rigid concept, an order of magnitude
// cheaper than CVODE; BDF for the stiff flexible ones. CVODE used to lose
// flank events of a rattling nut, 3 to 8 of 36 at rtol 1e-12; with
// handle_event's touch below resolution it finds the same ones:
// tests/test_integrate_flank_events.py).
std::string ode_method(const DriveParameters& p, const std::string& integrator,
                       const DriveSimulationOptions& options) {
  if (integrator != "event_driven") return integrator;
  if (!options.smooth_integrator.empty()) return options.smooth_integrator;
  return p.concept == Concept::rigid ? "rk_verner6" : "cvode_bdf";
}

integrate::MoreauOptions moreau_options(const DriveSimulationOptions& options) {
  return {options.dt, options.theta, options.integrator_options.max_steps};
}

// The checks of a drive's result (model/result_checks.hpp), raised unless
// options.check is off.
// `step_play_rate`, `step_friction_excess`: Moreau-Jean's (ResultCheckSpec).
void check_drive_result(const DriveModel& model, const friction::Law& law,
                        const DriveSimulationOptions& options, bool time_stepping,
                        integrate::SimulationResult& result, double step_play_rate = 0.0,
                        double step_friction_excess = 0.0) {
  const DriveParameters& p = model.parameters();
  ResultCheckSpec spec;
  spec.work = {"work_drive", "work_axial"};
  spec.stored = {"kinetic", "elastic"};
  spec.losses = {"friction_loss", "damping_loss", "contact_loss", "impact_loss"};
  spec.t_end = options.output.t_end;
  spec.law = &law;
  spec.coefficient_scale = model.flank_factor();
  // Eq. (3.15)'s law can do positive work (its friction follows the slip
  // acceleration), and LuGre's bristles give back what they stored.
  spec.friction_dissipates = law.resolution() != friction::Resolution::acceleration &&
                             law.resolution() != friction::Resolution::bristle;
  spec.clearance = p.backlash == BacklashContact::exact ? p.clearance : 0.0;
  spec.time_step = time_stepping ? options.dt : 0.0;
  spec.step_play_rate = step_play_rate;
  spec.step_friction_excess = step_friction_excess;
  spec.slip_resolution =
      model.tangent_direction().cwiseAbs().sum() * options.integrator_options.atol;
  spec.time_stepping = time_stepping;
  spec.rtol = options.integrator_options.rtol;
  spec.atol = options.integrator_options.atol;
  spec.momentum_factor = std::sqrt(2.0 * model.mass().sum());
  // sum |k x| <= sqrt(2 E sum k) for the springs at their stiffest over the
  // screw's length (the stiffness of eq. 4.24 grows toward its ends; the
  // nut's whole length stays on it), and the flank's force for a penalty
  // contact, whose energy is not quadratic: taken as its largest stiffness.
  double stiffness = p.contact_stiffness;
  for (const Spring& s : model.springs()) {
    double k = 0.0;
    for (const double a : {0.5 * p.nut_length, p.nut_position,
                           p.screw_length - 0.5 * p.nut_length}) {
      double derivative = 0.0;
      k = std::max(k, model.spring_stiffness(s, a, &derivative));
    }
    stiffness += k;
  }
  spec.force_factor = std::sqrt(2.0 * stiffness);
  spec.quadratures = kEnergyCount + 1;  // and the impact loss, booked at events
  spec.load_forces = {"axial_force"};
  spec.load_torques = {"drive_torque"};
  spec.lever = p.thread.mean_radius();
  spec.length_scale = p.screw_length;
  check_result(spec, result);
  if (options.check) integrate::enforce_checks(result);
}

}  // namespace

void check_simulation_options(const DriveModel& model, const DriveSimulationOptions& options) {
  const DriveParameters& p = model.parameters();
  const std::vector<std::string>& allowed = drive_integrators(p);
  const std::string& integrator = chosen_integrator(p, options);
  if (std::find(allowed.begin(), allowed.end(), integrator) == allowed.end())
    require_choice("integrator", integrator, allowed,
                   (p.backlash != BacklashContact::none
                        ? "backlash.contact = \"" + backlash_contact_name(p.backlash) + "\" with "
                        : std::string()) +
                       "friction.law = \"" + p.friction + "\"");
  require_nonnegative("bounce_threshold", options.bounce_threshold);
  integrate::validate_output_request(options.output, 0.0);
  if (options.max_events < 0)
    throw InvalidArgument("max_events = " + std::to_string(options.max_events) +
                          " is invalid: must be an integer >= 0");
  if (!options.smooth_integrator.empty() && integrator != "event_driven")
    throw InvalidArgument("smooth_integrator = \"" + options.smooth_integrator +
                          "\" is invalid with integrator = \"" + integrator +
                          "\": only \"event_driven\" takes one (the method between its events)");
  if (integrator == "moreau") {  // what simulate_moreau checks, from t = 0
    integrate::check_moreau_options(options.output.t_end, moreau_options(options));
    check_step_resolves_loads(options.dt, options.output.t_end,
                              {p.speed_controlled ? &p.drive_speed : &p.drive_torque,
                               &p.axial_force});
    return;
  }
  check_meaningful_tolerances(options.integrator_options, options.output.t_end);
  if (!options.smooth_integrator.empty())
    require_choice("smooth_integrator", options.smooth_integrator, integrate::integrator_names());
  // What make_integrator checks as the smooth phases start, the method's
  // own limits included (max_order of a one-step method, CVODE's orders).
  integrate::validate_options(options.integrator_options);
  const std::string method = ode_method(p, integrator, options);
  try {
    integrate::check_method_limits(method, options.integrator_options);
  } catch (const InvalidArgument& e) {
    if (method == integrator || !options.smooth_integrator.empty()) throw;  // the user named it
    // The default method between events: say which it is.
    throw InvalidArgument(std::string(e.what()) + "; integrator \"event_driven\" runs \"" +
                          method + "\" between events here (smooth_integrator chooses another)");
  }
}

integrate::SimulationResult simulate(const DriveModel& model,
                                     const DriveSimulationOptions& options) {
  check_simulation_options(model, options);
  const DriveParameters& p = model.parameters();
  const std::string& integrator = chosen_integrator(p, options);

  // The law that runs: the model's, or a set-valued law's regularization
  // where an ODE method runs it alone.
  const bool ode_alone = integrator != "event_driven" && integrator != "moreau";
  std::unique_ptr<friction::Law> regularization;
  if (ode_alone && model.law().resolution() == friction::Resolution::set_valued) {
    regularization = model.law().regularized();
    if (!regularization)
      throw InvalidArgument("integrator = \"" + integrator + "\" is invalid with friction.law = \"" +
                            p.friction + "\": the law has no regularization for an ODE method");
  }
  const friction::Law& law = regularization ? *regularization : model.law();

  StateLayout layout(model, law.resolution() == friction::Resolution::bristle);
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(layout.size());
  const double speed = p.speed_controlled ? p.drive_speed(0.0) : p.rotor_speed;
  const Eigen::VectorXd v0 = model.consistent_velocity(speed);
  CoordinateVector q = CoordinateVector::Zero(model.coordinate_count()), v = v0;
  layout.compress(q, v, y0.data());

  if (integrator == "moreau") {
    DriveMoreau system(model);
    system.initialize(0.0, y0.data());
    system.check_step(options.dt, options.theta);
    integrate::SimulationResult result =
        integrate::simulate_moreau(system, 0.0, y0, options.output, moreau_options(options));
    result.friction = p.friction;
    check_drive_result(model, law, options, true, result, system.largest_play_rate(),
                       system.friction_excess());
    return result;
  }

  DriveHybrid system(model, law, options.bounce_threshold, options.output.t_end,
                     options.integrator_options);
  integrate::EventDrivenOptions driver;
  driver.integrator_options = options.integrator_options;
  driver.max_events = options.max_events;
  driver.integrator = ode_method(p, integrator, options);
  // The regularized friction laws are stiff near zero slip, and with the
  // flexible models' lightly damped modes BDF above order 3 is not stable
  // enough there: capped at 3 it was faster in every case measured
  // (flexible_nut and flexible, no play and bistop, rtol 1e-4 ... 1e-8: 1.1 to
  // 2.1x) and it no longer fails at loose tolerances (order 5: CV_ERR_FAILURE
  // at rtol 1e-4). Tighter than 1e-9 the higher orders pay again. The smooth
  // phases of exact Coulomb carry no such law: there order 5 took 1.4 to 2.5x
  // fewer steps at the same error (no play and exact backlash, rtol 1e-6 and
  // 1e-8), and order 3 ran past a million steps for a rattling flexible nut at
  // rtol 1e-9.
  if (driver.integrator == "cvode_bdf" && p.concept != Concept::rigid &&
      law.resolution() != friction::Resolution::set_valued &&
      driver.integrator_options.max_order == 0 &&
      driver.integrator_options.rtol >= 1e-9)
    driver.integrator_options.max_order = 3;
  // Eq. (3.15)'s friction follows the slip acceleration, which carries the
  // stiff modes of the flexible drives: the tangential inertia the law adds,
  // (2/pi) mu' k_V |N| d / (1 + (k_V gamma_T')^2), switches on and off
  // within one period of the fastest mode. CVODE's modified Newton, its
  // Jacobian frozen over several steps, then needs more than its default 3
  // iterations: with 3 it failed at every step (a nut-driven flexible drive,
  // 0.2 s: 229,147 steps, 225,258 convergence failures, 14 s), with 10 it
  // took 10,985 steps and 0.13 s.
  if (law.resolution() == friction::Resolution::acceleration && p.concept != Concept::rigid)
    driver.integrator_options.max_nonlinear_iterations = 10;
  integrate::SimulationResult result =
      integrate::simulate_event_driven(system, 0.0, y0, options.output, driver);
  result.integrator = integrator;
  result.friction = p.friction;
  check_drive_result(model, law, options, false, result);
  return result;
}

}  // namespace leadscrew::model
