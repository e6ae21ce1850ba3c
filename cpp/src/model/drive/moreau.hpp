// Moreau-Jean time stepping of a drive (integrate::TimeSteppingSystem), the
// members in moreau.cpp (a penalty flank's: moreau_flanks.cpp). Internal to
// cpp/src/model.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "channels.hpp"
#include "leadscrew/integrate/moreau.hpp"
#include "leadscrew/lcp/workspace.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_dynamics.hpp"
#include "moreau_contacts.hpp"
#include "moreau_iteration.hpp"
#include "state_layout.hpp"

namespace leadscrew::model::drive {

// Moreau-Jean time stepping for the drive. On the velocity level, with the
// theta method for springs and dampers made implicit through the iteration
// matrix W = M + theta h C + theta^2 h^2 K (the flexible models are stiff):
//   W v+ = M v + h f - theta (1 - theta) h^2 K v + theta h C v + impulses,
//   q+   = q + h ((1 - theta) v + theta v+).
// Impulses: the thread's normal impulse (a multiplier: bilateral without play,
// or on a flank the predicted position closes, with Newton's law
// W_N v+ = -e W_N v, or that the step without it passes, W_N v+ = 0:
// exact_flank_closes), the friction impulse from the flank LCP on the velocity
// level (maximal dissipation), and the speed-controlled rotor's.
// Penalty flanks (docs/physics/drive_models.md, "Moreau-Jean on penalty
// flanks"): a force along the play, the discrete gradient of the flanks'
// potential over the step (moreau_contacts::PenaltyFlank), with the flank's
// friction an LCP whose normal impulse is that force's over the step.
// End stops (docs/physics/end_stops.md, "Moreau-Jean"): a penalty stop is a
// force element whose stiffness k and damping c enter W where the step
// engages it (its force over the step k (d0+ + theta dd) + c d'_theta > 0, a
// switch decided per step by an active set); an exact stop is a unilateral
// velocity constraint on the load, active where the step's predicted
// position closes its gap, with Newton's law u'+ = -e u' on the step that
// closes it and an impulse >= 0 (else released).
class DriveMoreau final : public integrate::TimeSteppingSystem {
 public:
  explicit DriveMoreau(const DriveModel& model);

  int size() const override { return layout_.size(); }
  const std::vector<std::string>& channel_names() const override { return names_; }
  long lcp_solves() const override { return lcp_solves_; }
  // For the checks (ResultCheckSpec): the play's largest rate over the
  // steps [m/s], the friction impulses' booking beyond the steps' work [J].
  double largest_play_rate() const { return play_rate_; }
  double friction_excess() const { return friction_excess_; }

  void initialize(double t, const double* y);
  void step(double t, double h, double theta, const double* y, double* y_next) override;
  void channels(double t, const double* y, double* out) override;
  // Refuses a step whose flank problem is Painleve-like at the start (see
  // step_too_long); initialize() first.
  void check_step(double h, double theta);
  // The default step h where it resolves the drive's stiffness (check_step
  // passes), else half the longest step that does; initialize() first.
  double default_step(double h, double theta);

 private:
  using Square = IterationMatrix::Square;

  // At most two stops of each kind (lower, upper).
  static constexpr int kMaxStops = 2;
  using Columns = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates,
                                3 + kMaxStops>;

  struct Impulses {
    CoordinateVector velocity;
    double normal = 0.0, friction = 0.0, rotor = 0.0;
    double stop[kMaxStops] = {0.0, 0.0};  // the exact stops' impulses P >= 0 [N s]
    // The rotor's friction impulse Q = P_c + Lambda (the motor's friction and
    // the stage's loss) on the rotor's coordinate, against +phi_r [N m s].
    double train = 0.0;
    // A preloaded nut with a smooth law: half B's normal impulse, part of
    // `normal` (moreau_smooth_friction.cpp); 0 otherwise.
    double preload_normal = 0.0;
    // The slip at which a smooth law took `friction` (its root's gamma+ =
    // c + d P_T, or a held stop's rows' c); NaN: none (set-valued, no
    // contact). The end state's slip differs from it by the round-off of
    // the step's solve, which LuGre's slope near zero slip amplifies
    // (moreau_smooth_friction.cpp, "The rows' slip").
    double law_slip = std::numeric_limits<double>::quiet_NaN();
  };

  // The energy a step from y to y_next creates: what the stored energy
  // gains beyond the work in less the losses booked (the residual's fall),
  // and the round-off of that account (of its largest term).
  struct StepAccount {
    double created = 0.0, round_off = 0.0;
  };

  // One step at restitution e, taken again in the modes its elements ask
  // for (model/element.hpp, Element::step_mode); true where it closes a
  // flank with e > 0.
  bool take_step(double t, double h, double theta, const double* y, double* y_next,
                 double restitution);
  // take_step in the elements' modes of step_modes_.
  bool take_step_held(double t, double h, double theta, const double* y, double* y_next,
                      double restitution);
  // The step of the model's element k from y at t (model/element.hpp).
  // One step's state between its parts (take_step_held): its start, the
  // contacts it plans, its impulses.
  struct StepState {
    double t = 0.0, h = 0.0, theta = 0.0;
    const double* y = nullptr;
    CoordinateVector q0, v0;
    double play0 = 0.0, play_rate0 = 0.0;
    double rotor_impulse = 0.0;  // the elements' impulse on the rotor (the train's balance)
    int sigma_fixed = 0;         // 0: bilateral (sign free); +-1: a flank
    bool contact_at_start = true;
    double normal_target = 0.0, rotor_target = 0.0;
    bool restituting = false;
    double u0 = 0.0, du0 = 0.0;  // the load at the start
    bool released[kMaxStops] = {false, false};
    moreau_contacts::RotorBalance balance;
    moreau_contacts::RotorMode rotor_mode;
    Impulses impulses;
    bool stick = false, contact = false;
  };
  // take_step_held's parts, in order: the start and the elements'
  // impulses; the thread's contact, the stops' active sets and the rotor's
  // balance; the passes of the step's solve (its matrix and right-hand
  // side: assemble_step); the end velocities; the end state and the
  // account (book_step, book_losses); what the row reports.
  void begin_step(StepState& s);
  void plan_contacts(StepState& s, double restitution);
  void plan_stops(StepState& s);
  void solve_step(StepState& s);
  void assemble_step(const StepState& s, Square& stiffness, Square& damping,
                     CoordinateVector& rhs_base);
  void finish_velocities(StepState& s);
  void book_step(StepState& s, double* y_next);
  void book_losses(StepState& s, const CoordinateVector& v_theta, double* y_next);
  void report_step(const StepState& s);
  ElementStep element_step(std::size_t k, double t, double h, double theta, const double* y,
                           const CoordinateVector& q0, const CoordinateVector& v0) const;
  StepAccount energy_created(double t, double h, const double* y, const double* y_next);
  // (`elements`: the elements' impulses' slopes of the step, element_slope_,
  // join W's diagonal: a DC motor's implicit back-EMF term h k_t
  // |di_mean/domega+|; the step check's W has the drive's own terms alone.)
  void assemble(double h, double theta, Square& stiffness, Square& damping,
                bool elements = false);
  // A penalty flank's force at v+ in W: s = h theta (h S' + c) along
  // grad e grad e^T (0: none).
  double flank_coefficient(double h, double theta) const {
    return model_.thread_pair().penalty() && flank_.active()
               ? h * theta * (h * flank_.slope + flank_.damping)
               : 0.0;
  }
  double step_coupling(double h, double theta);
  std::string step_too_long(double theta, double alpha);
  double resolving_step(double h, double theta);
  Impulses solve(bool thread, double normal_target, double rotor_target, double tangential);
  // The thread's contact and friction impulses of the step at free_ (the
  // flank LCP); contact false where no flank is active or it separates (a
  // penalty flank: where its force pulls; one that pushes carries its
  // friction, or SimulationError).
  bool stops_fix_every_velocity() const;
  bool restitution_through_thread() const;
  void limit_stop_restitution(double t, double h, double theta, const double* y, double* y_next,
                              double excess, double play_rate);
  Impulses stop_holds(const Impulses& without, const Impulses& unit, double normal_target,
                      double rotor_target, bool& stick);
  // LuGre's bristles at an exact stop whose row and the thread's fix every
  // velocity (moreau_held_bristles.cpp): the law's friction at the rows'
  // slip and the bristles' implicit Euler step, the stop carrying the rest;
  // false where no friction agrees with the rows (the stop lets go).
  bool stop_holds_bristles(double h, int sigma_fixed, const Impulses& without,
                           const Impulses& unit, double normal_target, double rotor_target,
                           Impulses& impulses, bool& stick);
  // The step there: stop_holds_bristles, else the step without the stops
  // (solve_thread), a JammingError where that step moves into a stop.
  Impulses bristles_at_held_stop(double t, double h, double theta, const CoordinateVector& v0,
                                 double normal_target, double rotor_target, int sigma_fixed,
                                 const Impulses& without, const Impulses& unit, bool& contact,
                                 bool& stick);
  Impulses solve_thread(double t, double h, double theta, const CoordinateVector& v0,
                        double normal_target, double rotor_target, int sigma_fixed,
                        bool& contact, bool& stick);
  // solve_thread's parts (moreau.cpp). The flank's maps over the step: the
  // slip velocity c + d P_T and the normal impulse beta + alpha P_T at a
  // friction impulse P_T.
  struct FlankMaps {
    double c = 0.0, d = 0.0, alpha = 0.0, beta = 0.0;
  };
  // Whether a constraint prescribes the slip (the motor's, or the rotor's
  // stuck contact's with every velocity fixed), c's round-off, and the
  // rotor's (or train's) impulse map motor0 + motor1 P_T.
  struct SlipPrescription {
    bool prescribed = false, rotor_prescribes = false;
    double noise = 0.0, motor0 = 0.0, motor1 = 0.0;
  };
  Impulses solve_coulomb_thread(double t, double h, double theta, const CoordinateVector& v0,
                                double normal_target, double rotor_target, int sigma_fixed,
                                bool row, const Impulses& without, const Impulses& unit,
                                FlankMaps maps, bool& contact, bool& stick);
  SlipPrescription slip_prescription(bool row, const Impulses& without,
                                     const Impulses& unit) const;
  int coulomb_flank_impulse(const CoordinateVector& v0, const FlankMaps& maps, int sigma_fixed,
                            bool row, const SlipPrescription& slip,
                            friction::FlankLcpResult& chosen);
  Impulses coulomb_step_impulses(double t, double h, double theta, const CoordinateVector& v0,
                                 double normal_target, double rotor_target, int sigma_fixed,
                                 bool row, int found, const friction::FlankLcpResult& chosen,
                                 double pushing, bool& contact, bool& stick);
  // A smooth law's step (moreau_smooth_friction.cpp): the friction impulse
  // P_T = -kappa(gamma+) |P_N| - h viscous gamma+ solved implicitly at the
  // step's end slip gamma+ = c + d P_T, P_N = beta + alpha P_T; contact
  // false where the flank's normal impulse pulls.
  // The preloaded nut's friction impulse of the step (moreau_preload.cpp):
  // the element's cone at the step's impulses decides stick and slip.
  // The law's viscous term over the step (solve_thread): h c, the unscaled
  // slip c and the scale 1 / (1 + h c d).
  struct ViscousStep {
    double step = 0.0, c = 0.0, scale = 1.0;
  };
  Impulses solve_preloaded_thread(const elements::PreloadedNut& nut, double t, double h,
                                  double c, double d, double alpha, double beta, bool prescribed,
                                  bool slip_zero, double motor0, double motor1,
                                  double normal_target, double rotor_target,
                                  const ViscousStep& viscous, bool& stick);
  // A preloaded nut that lifts off (moreau_lift_off.cpp): half B's spring
  // over the step, the discrete gradient G of V = S^2 / (2 k_p) along the
  // play linearised at the step's end estimate e1k (as PenaltyFlank's), and
  // the step's friction modes (stick, slip +-) each a linear step of its own.
  struct HalfBSpring {
    double e0 = 0.0, e1k = 0.0, secant = 0.0, slope = 0.0;
    double low = -std::numeric_limits<double>::infinity();
    double high = std::numeric_limits<double>::infinity();
    void linearise(const elements::PreloadedNut& nut, double end);
    double gradient(double end) const noexcept { return secant + slope * (end - e1k); }
  };
  double half_b_factor(const elements::PreloadedNut& nut, int m) const;
  Impulses lift_off_step(const elements::PreloadedNut& nut, int m, double h, double theta,
                         const CoordinateVector& v0, double normal_target, double rotor_target,
                         double tangential);
  double half_b_spring(const elements::PreloadedNut& nut, double h, double theta,
                       const CoordinateVector& v0, const CoordinateVector& v1,
                       bool clamped) const;
  struct LiftOffMaps {
    double c = 0.0, d = 0.0, beta = 0.0, alpha = 0.0, s0 = 0.0, sigma = 0.0;
  };
  LiftOffMaps lift_off_maps(const elements::PreloadedNut& nut, int m, double h, double theta,
                            const CoordinateVector& v0, double normal_target,
                            double rotor_target);
  Impulses solve_lift_off_thread(double t, double h, double theta, const CoordinateVector& v0,
                                 double normal_target, double rotor_target, bool& stick);
  elements::PreloadedNut lift_off_slipping(const CoordinateVector& v0) const;
  bool update_half_b(double h, double theta, const CoordinateVector& v0,
                     const Impulses& impulses);
  // Exact play closed by the preload: SimulationError where half A's normal
  // force on its flank is negative at the step's end.
  void check_half_a_bearing(const StepState& s) const;
  Impulses solve_smooth_thread(double t, double h, double theta, const CoordinateVector& v0,
                               double normal_target, double rotor_target, int sigma_fixed,
                               double c, double d, double alpha, double beta, bool& contact);
  // The law's coefficient over the step at the end slip (flank factor
  // applied): a velocity law's kappa(gamma+), LuGre's sigma0 z+ + sigma1 z'
  // with z+ its implicit Euler step from the step's start.
  double smooth_coefficient(double slip, double h) const;
  // LuGre's bristles over the step: z+ (implicit Euler) and the energy
  // they store, taken from the friction loss (moreau_smooth_friction.cpp).
  void book_bristles(double h, const double* y, double* y_next, double slip,
                     double normal_impulse);
  void book_planar_bristles(double h, const double* y, double* y_next, double slip,
                            double normal_impulse);
  // The slip LuGre's bristles take the step at and its row reports: the
  // law's (Impulses::law_slip), else end_slip (moreau_step.cpp).
  double bristle_slip(const StepState& s, double end_slip) const;
  // The cone's transverse impulse over the step at w+ (on the cone from
  // the helix impulse): its loss, the excitation's work that balances it,
  // the row's force (moreau_smooth_friction.cpp).
  void book_transverse(double h, const double* y, double* y_next, bool contact,
                       double friction_impulse, double normal_impulse, double slip);
  // A speed-controlled rotor with the train's friction: the step without
  // the rotor's friction row, then the motor's friction and the stage's
  // loss from the impulse the stage passes on (moreau_speed_train.cpp).
  Impulses solve_speed_train(double t, double h, double theta, const CoordinateVector& v0,
                             double normal_target, double rotor_target, int sigma_fixed,
                             bool contact_at_start, bool& contact, bool& stick,
                             moreau_contacts::RotorMode& mode);
  // The step's impulses with the rotor's friction contact (the thread's
  // LCP for each mode of the rotor's contact until one is consistent).
  Impulses solve_train(double t, double h, double theta, const CoordinateVector& v0,
                       double normal_target, double rotor_target, int sigma_fixed,
                       const moreau_contacts::RotorBalance& balance, bool contact_at_start,
                       bool& contact, bool& stick, moreau_contacts::RotorMode& mode);
  // A penalty flank's normal impulse over the step [N s] at the step's end
  // velocity v1 (moreau_contacts::PenaltyFlank, along the thread's normal).
  double flank_impulse(double h, double theta, const CoordinateVector& v0,
                       const CoordinateVector& v1) const;
  // The penalty flank's linearisation from the step's result: true where it
  // changed (released, or the step's end moved: solved again).
  bool update_flank(double h, double theta, const CoordinateVector& v0, const Impulses& impulses);
  // Exact play: a step planned with the flank open whose result ends beyond
  // it takes the flank's contact (moreau_flanks.cpp); true where it did.
  bool exact_flank_closes(StepState& s) const;
  // The target W_N v+ of an exact flank the step holds closed, its sigma
  // set (moreau_flanks.cpp): 0, or W_N v_theta = 0 where the start separates.
  double held_flank_target(const StepState& s) const;
  // The same of an exact end stop the step holds (its gap closed at the
  // start; moreau_stops.cpp): the row's target -side u'+ at the load's
  // start velocity du0.
  double held_stop_target(int side, double du0, double theta) const;
  // The end stops' active sets of the step from its result: true where
  // they changed (the step is solved again).
  bool update_stops(double h, double theta, const CoordinateVector& v0, const Impulses& impulses,
                    bool* released);

  const DriveModel& model_;
  const DriveParameters& p_;
  DriveDynamics dynamics_;
  StateLayout layout_;
  std::vector<std::string> names_;
  // Slots of the elements' states and channels (declaration.hpp; -1: none):
  // the model's elements' (model/element.hpp: first state and count, first
  // channel), the stops' force, the train's loss integrals and their channels.
  std::vector<std::pair<int, int>> element_slots_;
  std::vector<int> element_channels_;
  int stop_channel_, motor_friction_state_, gear_state_, motor_friction_channel_, gear_channel_;
  // LuGre's bristles (-1: another law): z / bristle_range in y, then the
  // energy they store; the deflection's channel.
  int bristle_state_ = -1, bristle_channel_ = -1;
  // A preloaded nut's channels (with a smooth law: hybrid_preloaded_nut.cpp's
  // declaration; -1: not declared): preload_force, its first.
  int preload_channel_ = -1;
  // Lift-off (moreau_lift_off.cpp): whether the model's nut lifts off, half
  // B's spring over the step, the pass's right-hand side without it, half
  // B's friction impulse and spring force of the last step.
  bool lift_off_ = false;
  HalfBSpring half_b_;
  CoordinateVector pass_rhs_;
  double half_b_friction_ = 0.0, half_b_spring_ = 0.0;
  // A transverse slip's cone (transverse_slip.cpp): w at the step's end,
  // the excitation's work integral in y (-1: none) and the last step's
  // transverse friction [N] (the friction channel's sign).
  // The cone's coefficient mu'(s0) at the step's start slip speed
  // s0 = |(gamma, w)| (Stribeck's curve explicit, as the 1-D step's).
  double transverse_next_ = 0.0, transverse_mu_ = 0.0;
  int transverse_state_ = -1;
  double last_transverse_ = 0.0;
  double bristle_range_ = 0.0;
  double bristle_z0_ = 0.0;  // z at the step's start [m] (step())
  // A transverse slip's 2-D bristles: z_w at the step's start [m], and the
  // transverse coefficient sigma0 z_w+ + sigma1 z_w+' (times the flank
  // factor) of the step's end (book_planar_bristles).
  double bristle_w0_ = 0.0, transverse_bristle_coefficient_ = 0.0;
  CoordinateVector q_, v_, free_;
  IterationMatrix iteration_;  // W, factorized while it holds (moreau_iteration.hpp)
  ContactForces last_;
  // The last step's Impulses::law_slip (NaN: none): LuGre's row reports it
  // as its slip_velocity, the slip of its friction and its bristles.
  double last_law_slip_ = std::numeric_limits<double>::quiet_NaN();
  // The end stops of this step: a penalty stop engaged (its k, c in W), an
  // exact one active (a constraint row), its Newton target u'+ [m/s].
  bool engaged_[kMaxStops] = {false, false};
  bool stop_active_[kMaxStops] = {false, false};
  double stop_target_[kMaxStops] = {0.0, 0.0};
  // Whether the step closes the stop (its gap open at the start: Newton's
  // target); a held one's target is 0, or held_stop_target's.
  bool stop_closing_[kMaxStops] = {false, false};
  // The share of the exact stops' restitution the step takes (1; less
  // where a rebound through the frictional thread would create energy:
  // limit_stop_restitution), and whether the step is such a rebound.
  double stop_share_ = 1.0;
  bool stop_restituting_ = false;
  double last_stop_force_ = 0.0;  // the exact stops' impulse / h on the load along +u [N]
  // The rotor's friction row of the step's constraint solve (active: the
  // model has train friction and a mode is being tried).
  bool rotor_row_ = false;
  // A penalty flank's force over this step (bistop, cubic).
  moreau_contacts::PenaltyFlank flank_;
  moreau_contacts::RotorRow rotor_;
  // The model's elements' modes at the step's start and in the step being
  // taken; their impulses over it beyond their start's force, constant +
  // slope . v+ (Element::step_impulse).
  std::vector<ElementMode> modes_at_start_, step_modes_;
  CoordinateVector element_constant_, element_slope_;
  double kinetic0_ = 0.0, stored0_ = 0.0;  // (write_drive_channels)
  double play_rate_ = 0.0, friction_excess_ = 0.0;
  long lcp_solves_ = 0;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
};

}  // namespace leadscrew::model::drive
