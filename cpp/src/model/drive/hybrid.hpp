// The event-driven system of a drive (integrate::HybridSystem): exact Coulomb
// friction and exact flank contacts by modes and events, the regularized and
// compliant formulations as smooth phases. Internal to cpp/src/model; its
// members are defined by concern (docs/architecture.md):
//   hybrid_rhs.cpp         construction, the right-hand side and output rows
//                          (by the mode solver), the loads' time scales
//   mode_solver.hpp        how the current mode is solved at y and how y maps
//                          to coordinates: the constrained solve for any
//                          model (constrained_solver.cpp), the rigid drive's
//                          one degree of freedom in closed form
//                          (rigid_solver.cpp), chosen from the model's
//                          structure (mode_solver.cpp)
//   hybrid_events.cpp      root functions, the initial mode, event handling
//   hybrid_load_roots.cpp  load-driven roots of the rigid drive's modes
//   hybrid_modes.cpp       the current mode's solution, stick or slip by the
//                          flank LCP and the two-step stick test
//   hybrid_impacts.cpp     flank impacts with restitution, free flights
//   hybrid_jamming.cpp     dynamic jamming (Painleve), the regularized
//                          law's fold
//   driver_element.hpp     DriveHybrid::Element: an element with events of
//                          its own (roots, events, start, rates, output),
//                          one file each:
//   model_element.cpp      a model's element behind model/element.hpp (the
//                          DC motor, the base excitation): one adapter
//   hybrid_end_stops.cpp   the end stops, penalty and exact: their roots,
//                          impacts, closed contacts and force
//   hybrid_preloaded_nut.cpp  a lift-off preloaded nut's channels; the guard of
//                             half A with exact play closed by the preload
//   hybrid_rotor_contact.cpp  the rotor's friction contact (the train's stages
//                             with a torque or DC motor on the flexible
//                             concepts): its mode, roots and decisions
//   hybrid_rotor_stops.cpp    the rotor's contact beside a closed exact stop
//                             and in a stop's impact through the thread
//   hybrid_rotor_impact.cpp   a flank's impact through the rotor's contact
//   element_registry.cpp   the elements' registry (declaration.hpp)
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "leadscrew/friction/law.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/lcp/workspace.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_dynamics.hpp"
#include "leadscrew/model/drive_rigid.hpp"
#include "moreau_contacts.hpp"
#include "modes.hpp"
#include "state_layout.hpp"

namespace leadscrew::model::drive {

struct ThreadForces;  // (mode_solver.hpp)

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

// A held constraint's violation is projected away (ConstrainedSolver::
// project) beyond this fraction of the integrator's error weights.
constexpr double kHeldResolution = 1e-3;

class DriveHybrid final : public integrate::HybridSystem {
 public:
  // `law`: the friction law that runs (the model's, or its regularization
  // for an ODE integrator); it outlives this.
  DriveHybrid(const DriveModel& model, const friction::Law& law, double bounce_threshold,
              double t_end, const integrate::IntegratorOptions& integrator_options);
  ~DriveHybrid() override;
  // Its mode solver refers to it: neither copied nor moved.
  DriveHybrid(const DriveHybrid&) = delete;
  DriveHybrid& operator=(const DriveHybrid&) = delete;

  int size() const override { return layout_.size(); }
  // g0..g3: friction and flank events (see roots); g4: the nut's end at the
  // screw's end, for every concept (the scene gives every screw its length);
  // then the elements' with events (elements_), each in a block of its own,
  // in the list's order.
  int root_count() const override { return root_count_; }
  // The work and loss integrals close the state; f does not depend on them.
  int quadrature_count() const override { return kEnergyCount; }

  // hybrid_rhs.cpp
  void rhs(double t, const double* y, double* ydot) override;
  void channels(double t, const double* y, double* out) override;
  std::vector<double> breakpoints() const override;
  double max_step_hint() const override;
  const std::vector<std::string>& channel_names() const override { return names_; }
  long lcp_solves() const override { return lcp_solves_; }

  // hybrid_events.cpp
  void roots(double t, const double* y, double* g) override;
  void root_directions(int* directions) const override;
  void select_initial_mode(double t, double* y) override;
  // The mode's constraints on the position and velocity level (OdeSystem::
  // project): the general solver's drives, whose closed flank and stick are
  // rows of the acceleration solve over coordinates of y.
  bool has_projection() const override;
  void project(double t, const double* y, double* correction) override;
  std::string handle_event(double t, double* y, const std::vector<int>& root_info) override;

  // hybrid_resume.cpp: a run advanced in pieces (model/drive_stepper.hpp).
  // The run, at (t, y), now goes on to t_end (> the last): the load-driven
  // roots are planned, and the regularized law's look-ahead toward jamming
  // runs, up to it.
  void extend_horizon(double t, const double* y, double t_end);
  // Continues the run of `before` (the same drive under other loads) at its
  // state (t, y): the mode chosen anew, as at a start, the energy account
  // carried on.
  void resume(const DriveHybrid& before, double t, double* y);

  // driver_element.hpp: an element with events of its own (a DC motor's
  // current limit, the end stops), held in elements_.
  class Element;
  // The rigid train solver (TrainSolver) runs the train's stages with a
  // torque or DC motor (the rigid concept without play); elsewhere the
  // rotor's friction contact does (make_rotor_contact).
  static bool train_solver_applies(const DriveModel& model);
  static std::unique_ptr<Element> make_rotor_contact(DriveHybrid& hybrid,
                                                     const elements::TrainFriction& train);

 private:
  // Expands y at t into q_, v_ and the dynamics' state (every right-hand
  // side, root and output row starts here: inline).
  void set(double t, const double* y) {
    layout_.expand(t, y, q_, v_);
    dynamics_.set_element_states(y);
    dynamics_.set_state(t, q_, v_);
    if (bristle_state_ >= 0) {
      dynamics_.set_bristle(y[bristle_state_] * bristle_range_);
      // (a transverse slip's: after the bristles' energy, lugre_bristles_kind)
      if (dynamics_.transverse())
        dynamics_.set_transverse_bristle(y[bristle_state_ + 2] * bristle_range_);
    }
  }

  // mode_solver.hpp: the current mode at a state y (the constrained solve,
  // or a specialisation chosen from the model's structure).
  class ModeSolver;
  class ConstrainedSolver;
  class RigidDofSolver;  // RigidSolver's and TrainSolver's shared part
  class RigidSolver;
  class TrainSolver;
  static std::unique_ptr<ModeSolver> make_mode_solver(DriveHybrid& hybrid);

  // The thread's roots g0..g4; the elements' follow (root_count_).
  static constexpr int kThreadRoots = 5;
  // hybrid_rhs.cpp: the elements with events of the model, one line per kind.
  void make_elements();
  void add_element(std::unique_ptr<Element> element, int kind);

  // hybrid_events.cpp
  void start_mode(double t, const double* y);
  // The constraints a stuck contact holds (project): the stick's at its slip
  // position, with the thread's normal one on its flank's play.
  DriveDynamics::HeldContact held_contact() const;
  std::string change_mode(double t, double* y, const std::vector<int>& root_info);
  // change_mode's parts (hybrid_events.cpp): a free flight reaching a
  // flank (true where the play bounces off), and a touch below resolution
  // undone.
  bool end_flight(double t, double* y, int flank, bool& touch, bool& zero_slip, std::string& kind);
  void undo_touch(double t, double* y, const Mode& before, int bounced_before);

  // hybrid_load_roots.cpp
  bool load_driven() const;
  void plan_load_roots(double t);
  bool load_scan_horizon(double t, const std::vector<int>& root_info);
  double load_root_value(double t) const {
    return std::isfinite(load_root_time_) ? load_root_time_ - t : 1.0;
  }

  // hybrid_modes.cpp
  ModeSpec spec(int sigma) const {
    ModeSpec s;
    s.contact = mode_.contact;
    s.sigma = mode_.contact == ThreadContact::closed ? mode_.flank : sigma;
    s.friction = mode_.contact == ThreadContact::open ? FrictionMode::none : mode_.friction;
    s.slip_sign = mode_.slip_sign;
    s.half_b_edge = mode_.friction == FrictionMode::stick ? mode_.half_b_edge : 0;
    s.half_b_share = std::clamp(half_b_edge_.share, 0.0, 1.0);
    s.held_load = held_load_;
    if (rotor_train_) s.rotor = rotor_row();
    return s;
  }

  // hybrid_events.cpp: the root that ends a stick in the forces s.
  double stick_root(const double* y, const ThreadForces& s);

  // The stick limit mu_static' of the law (mu' itself for one coefficient).
  double stick_mu() const {
    return dynamics_.plain_coulomb() || kinetic_stick_ ? model_.effective_mu()
                                                       : model_.effective_mu_static();
  }

  // The motor prescribes the slip (DriveDynamics::slip_prescribed) while the
  // thread's normal constraint is active.
  bool slip_prescribed_now() const {
    const bool held = dynamics_.slip_prescribed() ||
                      (rotor_train_ && rotor_mode_.slip == 0 && dynamics_.rotor_fixes_slip());
    return held && (mode_.contact == ThreadContact::bilateral ||
                                           mode_.contact == ThreadContact::closed);
  }
  ModeSolution solve_current();
  // solve_current's solution as an output row reports it (hybrid_modes.cpp).
  ModeSolution on_the_law(const ModeSolution& own);
  void open_if_pulling();
  void decide_friction(double t, double* y, bool at_zero_slip, int hint);
  // decide_friction's parts at zero slip (hybrid_modes.cpp): the flank
  // LCP's data, slip acceleration c + d lambda_T and normal force
  // beta + alpha lambda_T, and the normal-force signs to try.
  struct ZeroSlipLcp {
    double c = 0.0, d = 0.0, alpha = 0.0, beta = 0.0;
    int sigmas[2] = {1, -1};
    int sigma_count = 2;
  };
  void decide_at_zero_slip(double t, double* y, int hint, const elements::PreloadedNut* lift_off);
  void decide_prescribed_slip(const ModeSpec& base);
  void decide_preloaded_nut(const elements::PreloadedNut& nut, const ZeroSlipLcp& lcp, int hint,
                            const elements::PreloadedNut* lift_off);
  void decide_flank_lcp(const ZeroSlipLcp& lcp, int hint);
  void stick_at_half_b_edge();
  double half_b_edge_share();
  void start_normal_side();
  double flank_change_root(double normal_force);
  // A preloaded nut closing exact play (hybrid_preloaded_nut.cpp): the nut
  // where the thread is closed by it (nullptr otherwise), half A's normal
  // force on its own flank in the current mode at the net normal force (the
  // root g1, >= 0 while it bears), and the SimulationError where it lifts off.
  const elements::PreloadedNut* closing_nut() const;
  double half_a_bearing(double normal_force, double preload_normal) const;
  [[noreturn]] void half_a_lifts_off(double t) const;
  // The train's friction stages (TrainSolver): stick or slip at zero slip by
  // the breakaway test; the stage's power flow reversing in slip (the root
  // of its torque on the driven part, as flank_change_root's).
  void decide_train(double t, double* y, bool at_zero_slip, int hint);
  double stage_reversal_root(double stage_torque);

  // hybrid_rotor_contact.cpp: the rotor's friction contact (the motor's
  // Coulomb friction and a lossy or worm stage with a torque or DC motor on
  // a drive TrainSolver does not take): its mode feeds every solve
  // (ModeSpec::rotor), an element of its own watches its roots.
  class RotorContact;
  // The rotor's balance at the state set (rate form: U on the coordinate,
  // R, B) and its mode's row.
  moreau_contacts::RotorBalance rotor_balance() const;
  ModeSpec::RotorRow rotor_row() const;
  // Whether the solution s fits the rotor's mode; the mode chosen anew
  // (at rest: stick first, then the slips, each with the thread's
  // decision; leave_stick: a stick's margin fell through zero).
  bool rotor_consistent(const ModeSolution& s, bool at_rest) const;
  // The thread's Painleve test (DriveDynamics::painleve_possible) with the
  // rotor's inertia its mode's row gives (held: none on the thread).
  bool rotor_painleve_possible() const;
  void decide_rotor(double t, double* y, bool leave_stick, bool stalled);
  bool try_rotor_modes(double t, double* y, bool leave_stick, bool at_rest, const Mode& thread,
                       std::string& failure);
  // After the thread's mode changed: the rotor's decided anew where the
  // new mode does not fit it.
  void settle_rotor(double t, double* y);
  bool stick_at_edge(const ModeSolution& s);
  void start_flow_root(const ModeSolution& s);
  bool flow_at_edge(const ModeSolution& s);
  double thread_torque_scale(const ModeSolution& s) const;
  // The rotor's friction torque Q and the stage's torque on the driven part
  // tau_b in the solution s (the stages' losses' rates: Q phi_r' in all).
  double rotor_stage_torque(const ModeSolution& s) const;
  // hybrid_rotor_stops.cpp: the rotor's contact beside a closed exact stop
  // (its reaction a sign of the mode's decision: the stop pushes in s; the
  // stop opened where no mode has it push) and in a stop's impact through
  // the thread (a rotor's mode per impulse: dw the rotor's speed change per
  // unit impulse of the stop).
  bool held_stop_presses(const ModeSolution& s) const;
  void release_held_load();
  // A held load's drive whose every speed is below the integrator's
  // resolution is at rest: its speeds set to exactly zero.
  void rest_held_drive(double t, double* y);
  // A preloaded nut's half B's torques on the rotor's coordinate in s (0:
  // none): the round-off's scale they add to thread_torque_scale.
  double preload_torque_scale(const ModeSolution& s) const;
  bool rotor_impulse_consistent(const moreau_contacts::RotorMode& mode, double dw,
                                bool at_rest) const;
  // hybrid_rotor_impact.cpp: a flank's impact with the rotor's friction
  // contact (exact play): the impulses from v_before at restitution e, the
  // rotor's mode tried in Moreau-Jean's order on the impulse level (v_ and
  // rotor_mode_ set; false: no consistent one); the stage's share of the
  // impact's dissipation (Q w+ in slip, booked in gear_loss).
  bool flank_impulses(int flank, double restitution, const CoordinateVector& v_before,
                      DriveDynamics::Impulses& impulses);
  double stage_impact_loss(const DriveDynamics::Impulses& impulses, double dissipated) const;

  // hybrid_impacts.cpp
  // The direction in which an impact and put_back_inside move the
  // coordinates to change the play: M^-1 grad e (the least kinetic energy
  // for a given play rate), with a speed-controlled rotor held at its
  // imposed speed; and the metric grad e . M^-1 grad e.
  struct PlayDirection {
    CoordinateVector along;
    double metric;
  };
  PlayDirection play_direction() const;
  void move_play_to(double t, const PlayDirection& direction, double target);
  double stop_play(double t, const PlayDirection& direction);
  void put_back_inside(double t, double* y);
  // Books a speed-controlled motor's impulsive work W (its impulse passed
  // to the driven part at the held speed) in work_drive, and behind a
  // friction stage the stage's loss (k - 1) W besides, in gear_loss.
  void book_motor_impulse(double* y, double motor_work) const;
  void note_flight_start(double t, const double* y);
  void check_flight(double t) const;
  double free_flight_play_acceleration();
  bool flank_impact(double t, double* y, int flank);

  // hybrid_jamming.cpp
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
  double fold_margin() const;
  [[noreturn]] void jam_regularized(const std::string& what) const;
  void approach_fold(double t, const double* y);
  class FoldApproach;  // the drive's equations in the time s with dt/ds = S
  [[noreturn]] void jam_acceleration_law(int count);
  [[noreturn]] void jam(const std::string& what) const;

  const DriveModel& model_;
  const DriveParameters& p_;
  DriveDynamics dynamics_;
  StateLayout layout_;
  // The declared states DriveDynamics reads (set): a DC motor's current
  // and LuGre's bristle state (-1: none), found once by name. The bristle
  // state is z / bristle_range_ (friction::Law::bristle_range): a
  // deflection of nanometres, carried in metres, had its error controlled
  // by atol alone and left its invariant bound (issue 31, reproduction 3).
  int bristle_state_;
  double bristle_range_;
  double bounce_threshold_;
  bool backlash_;
  bool touching_ = false;  // a penalty flank is penetrated
  int held_load_ = -1;     // a closed exact end stop's coordinate (ModeSpec::held_load)
  // The stick with half B toward its slip's edge (Mode::half_b_edge): the
  // share that holds the stick force at the cone's edge (unclamped) and the
  // roots' margins g0, g1 (half_b_edge_share).
  struct HalfBEdge {
    double share = 1.0, edge_margin = 0.0, spring_margin = 0.0;
  } half_b_edge_;
  int sigma_guess_ = 1;    // last consistent sign of the bilateral normal force
  int bounced_from_ = 0;   // the flank of the last bounce until the flight's apex
  std::vector<double> saved_state_;  // y before a touch below resolution (handle_event)
  double saved_impact_loss_ = 0.0;   // and impact_loss_
  moreau_contacts::RotorMode saved_rotor_mode_;  // and the rotor's mode (an impact sets it)
  double flight_start_excess_ = 0.0;  // the play beyond a flank at the start of a flight
  int normal_side_ = 0;    // sign of the bilateral normal force in this mode (0: not left zero)
  int stage_side_ = 0;     // sign of the friction stage's torque on the driven part (train_)
  double last_unique_time_ = 0.0;  // eq. (3.15) last seen with one solution (jam_acceleration_law)
  // round-off of the slip velocity against a slip mode's sign at its start
  double slip_offset_ = 0.0;
  bool slip_noise_event_ = false;  // an event of g0 kept the same slip mode (start_mode)
  bool stick_from_zero_ = false;  // a stick mode whose cone margin has not left zero
  double stick_position_ = 0.0;   // W_T . q where the stick mode began [m] (held_contact)
  int load_root_ = -1;     // the root function replaced by a load-driven crossing (-1: none)
  double load_root_time_ = std::numeric_limits<double>::infinity();  // its time
  bool load_root_horizon_ = false;  // load_root_time_ is the scan's horizon, no crossing
  double t_end_;
  integrate::IntegratorOptions integrator_options_;
  Mode mode_;
  CoordinateVector q_, v_;
  std::vector<std::string> names_;
  double kinetic0_ = 0.0, stored0_ = 0.0, impact_loss_ = 0.0;  // (write_drive_channels)
  long lcp_solves_ = 0;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
  // The elements with events (empty: none), and the roots with theirs.
  std::vector<std::unique_ptr<Element>> elements_;
  int root_count_ = kThreadRoots;
  TrainSolver* train_ = nullptr;  // solver_, where the model has friction stages
  // The rotor's friction contact (RotorContact; nullptr: none) and its mode.
  const elements::TrainFriction* rotor_train_ = nullptr;
  moreau_contacts::RotorMode rotor_mode_;
  double rotor_margin_offset_ = 0.0;
  // The thread's stick test at mu' for a moment (decide_rotor: the static
  // excess gives way where it leaves the rotor no consistent mode).
  bool kinetic_stick_ = false;
  double rotor_flow_offset_ = 0.0;    // the flow root's at a slip's start where below 0  // a stick's margin at its start where below 0 (settle_rotor)
  std::unique_ptr<ModeSolver> solver_;  // last: it refers to the fields above
};

}  // namespace leadscrew::model::drive
