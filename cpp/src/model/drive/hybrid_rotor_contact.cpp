// DriveHybrid (hybrid.hpp): the rotor's friction contact on the constrained
// solve, the train's stages (the motor's Coulomb friction, a lossy or worm
// stage: elements/train_friction.hpp) with a torque or DC motor on every
// drive the rigid train solver (TrainSolver, one degree of freedom) does
// not take: the flexible concepts, penalty and exact play (docs/physics/gear.md,
// "The event-driven rotor contact").
//
// The rotor (reflected inertia R) drives the rotor's coordinate through the
// stage: R phi_r'' = U - s B - x, x = k tau_b (U = n T on the coordinate, B
// = |n| T_c, k = 1 / eta forward, eta_b back-driven), and the rest of the
// rotor's coordinate, J_s phi_r'' = tau_b + f_r. Moreau-Jean's rotor row
// (moreau_contacts::RotorBalance::row) is the same law per impulse; at the
// rate level it is Q's row a_w phi_r'' + a_q Q = r with Q = U - R phi_r'' -
// tau_b along -e_rotor, the balance's inertia R, its start w0 = 0 and its
// impulse h0 = U (a DC motor's torque is its current's, a state: h1 = 0).
// In slip Q is eliminated: the coordinate's inverse mass k / (k J_s + R),
// its force f_r + (U - s B) / k (DriveDynamics::solve); in stick (and
// back-driven with eta_b = 0) the row fixes phi_r'' as a speed row does.
// k J_s + R <= 0 (a self-locking stage back-driving a large J_s) is the
// stage's Painleve case: JammingError.
//
// The mode is the element's: its roots are the rotor's speed in slip, the
// stage's torque tau_b (its power flow) in slip and the static margin in
// stick; at rest the modes are tried in Moreau-Jean's order (stick, the
// slips, the slips at breakaway), each with the thread's decision, and the
// first consistent one is kept (RotorBalance::consistent).
#include <algorithm>
#include <cmath>
#include <limits>

#include "driver_element.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "mode_solver.hpp"

namespace leadscrew::model::drive {

namespace {
// A stuck rotor's static margin this far (relative to the torques) below
// zero is its edge's round-off (settle_rotor).
constexpr double kRotorEdge = 1e-9;
// A stage's torque ratio k below this is no torque on the rotor (rotor_row).
constexpr double kNegligibleRatio = 1e-12;
}  // namespace

moreau_contacts::RotorBalance DriveHybrid::rotor_balance() const {
  moreau_contacts::RotorBalance balance;
  balance.inertia = rotor_train_->rotor_inertia;
  balance.h0 = dynamics_.applied_torque();
  balance.friction = rotor_train_->motor_friction_bound();
  return balance;
}

ModeSpec::RotorRow DriveHybrid::rotor_row() const {
  const moreau_contacts::RotorRow row = rotor_balance().row(*rotor_train_, rotor_mode_);
  ModeSpec::RotorRow out;
  out.active = true;
  out.a_w = row.a_w;
  out.a_q = row.a_q;
  out.r = row.r;
  if (row.a_q != 0.0 && std::abs(row.a_q) < kNegligibleRatio) {
    // A back-driven stage of |eta_b| below kNegligibleRatio passes the
    // rotor no torque to round-off: eta_b = 0's row, which fixes w' (the
    // eliminated form's force U / k swamped the thread's forces: with a
    // preloaded nut eta_b = 1e-20 jammed, 1e-100 ran CVODE out of steps;
    // 1e-12 and 0 ran).
    const moreau_contacts::RotorBalance balance = rotor_balance();
    out.a_w = -(balance.inertia - balance.h1);
    out.a_q = 0.0;
    out.r = rotor_mode_.slip * balance.friction - (balance.inertia * balance.w0 + balance.h0);
  }
  return out;
}

double DriveHybrid::rotor_stage_torque(const ModeSolution& s) const {
  return rotor_balance().at(s.acceleration[model_.rotor()]) - s.rotor_friction;
}

bool DriveHybrid::rotor_painleve_possible() const {
  const ModeSpec::RotorRow row = rotor_row();
  const Eigen::VectorXd& mass = model_.mass();
  const Eigen::VectorXd& normal = model_.normal_direction();
  const Eigen::VectorXd& tangent = model_.tangent_direction();
  const int r = model_.rotor();
  double nn = 0.0, nt = 0.0;
  for (int i = 0; i < mass.size(); ++i) {
    const double inverse = i != r ? 1.0 / mass[i]
                           : row.a_q == 0.0 ? 0.0
                                            : row.a_q / (row.a_q * mass[r] - row.a_w);
    nn += normal[i] * normal[i] * inverse;
    nt += normal[i] * tangent[i] * inverse;
  }
  return dynamics_.law().max_mu() * model_.flank_factor() * std::abs(nt) >= nn;
}

// The thread's torques on the rotor's coordinate in s (the round-off's
// scale of Q beside the rotor's own torques).
double DriveHybrid::thread_torque_scale(const ModeSolution& s) const {
  const int r = model_.rotor();
  // (A preloaded nut's halves: their forces, of the preload's size, cancel
  // to the net ones; their round-off is the preload's, hybrid_rotor_stops.cpp.)
  return std::abs(s.normal_force * model_.normal_direction()[r]) +
         std::abs(s.friction_force * model_.tangent_direction()[r]) + preload_torque_scale(s);
}

bool DriveHybrid::rotor_consistent(const ModeSolution& s, bool at_rest) const {
  if (!s.regular) return false;
  const int r = model_.rotor();
  const double other = thread_torque_scale(s);
  // (At rest a slip takes the acceleration's sign: the thread's decision
  // may have left the rotor's speed at a round-off of either sign.)
  const double moving = rotor_mode_.slip != 0 && !at_rest ? v_[r] : 0.0;
  return rotor_balance().consistent(*rotor_train_, rotor_mode_, s.acceleration[r],
                                    s.rotor_friction, other, moving);
}

// decide_rotor's trials: the rotor's modes in Moreau-Jean's order, each
// with the thread's own decision from its mode `thread`; true where one is
// consistent (rotor_mode_ and mode_ set), else the first failure's text.
bool DriveHybrid::try_rotor_modes(double t, double* y, bool leave_stick, bool at_rest,
                                  const Mode& thread, std::string& failure) {
  const int r = model_.rotor();
  for (const moreau_contacts::RotorMode& candidate : moreau_contacts::kRotorModes) {
    if (!rotor_train_->stage && candidate.flow < 0) continue;
    if (candidate.slip == 0 && (leave_stick || !at_rest)) continue;
    if (!at_rest && (candidate.breakaway || candidate.slip != sign_of(v_[r]))) continue;
    rotor_mode_ = candidate;
    mode_ = thread;
    try {
      if (mode_.contact != ThreadContact::open)
        decide_friction(t, y, mode_.friction == FrictionMode::stick, 0);
      const ModeSolution s = solve_current();
      // (A closed exact stop must push in the mode: hybrid_rotor_stops.cpp.)
      if ((candidate.slip == 0 ? stick_at_edge(s) : rotor_consistent(s, at_rest)) &&
          held_stop_presses(s)) {
        rotor_mode_.breakaway = false;  // (in slip the kinetic efficiencies)
        start_flow_root(s);
        return true;
      }
    } catch (const SimulationError& e) {  // (JammingError too)
      if (failure.empty()) failure = e.what();
    }
  }
  return false;
}

// The rotor's speed at the level of its round-off is at rest: projected to
// exactly zero (with the thread's held constraints), then the modes tried.
void DriveHybrid::decide_rotor(double t, double* y, bool leave_stick, bool stalled) {
  set(t, y);
  const int r = model_.rotor();
  const double noise = 64.0 * std::numeric_limits<double>::epsilon() * v_.cwiseAbs().sum();
  const bool at_rest = stalled || std::abs(v_[r]) <= noise;
  if (at_rest && v_[r] != 0.0) {
    DriveDynamics::HeldContact held = held_contact();
    held.rotor = true;
    dynamics_.project_held(held, q_, v_);
    layout_.compress(q_, v_, y);
    set(t, y);
  }
  if (at_rest) rest_held_drive(t, y);  // (hybrid_rotor_stops.cpp)
  const Mode thread = mode_;
  std::string failure;
  if (try_rotor_modes(t, y, leave_stick, at_rest, thread, failure)) return;
  // Coulomb's static coefficient above its kinetic one: at the cone's edge
  // the thread's friction jumps from mu_static' |N| (stick) to mu' |N|
  // (slip), and with the stage's power flow deciding on that friction
  // neither flow may be consistent (stuck, the stage passes its torque one
  // way; sliding, the other: 4 of 110 random trains with mu_static jammed
  // so, never with Stribeck's continuous curve). There the static excess
  // gives way: the thread decides at mu' (its slip at mu' is consistent
  // where no stick at mu_static' is).
  if (model_.effective_mu_static() > model_.effective_mu() && !kinetic_stick_) {
    kinetic_stick_ = true;
    const bool found = try_rotor_modes(t, y, leave_stick, at_rest, thread, failure);
    kinetic_stick_ = false;
    if (found) return;
  }
  if (leave_stick && at_rest) {
    // The margin's root fired on the edge's round-off, no slip starts: the
    // stick holds (within the band).
    rotor_mode_ = moreau_contacts::kRotorModes[0];
    rotor_mode_.breakaway = false;
    mode_ = thread;
    if (mode_.contact != ThreadContact::open)
      decide_friction(t, y, mode_.friction == FrictionMode::stick, 0);
    const ModeSolution s = solve_current();
    if (stick_at_edge(s) && held_stop_presses(s)) return;
  }
  mode_ = thread;
  if (held_load_ >= 0) {
    // No mode has the closed stop push: it opens, the modes tried again.
    release_held_load();
    decide_rotor(t, y, leave_stick, stalled);
    return;
  }
  // The stage's Painleve case: back-driven, a self-locking stage's k < 0
  // leaves the rotor's coordinate the inertia (k J_s + R) / k, none or a
  // negative one for k J_s + R <= 0.
  const double k = rotor_train_->torque_ratio(-1, false);
  const double driven = model_.mass()[r] - rotor_train_->rotor_inertia;  // J_s
  const std::string painleve =
      k * driven + rotor_train_->rotor_inertia <= 0.0
          ? "; the gear stage's Painleve case: back-driven, eta_b J_s + R = " +
                format_value(k * driven + rotor_train_->rotor_inertia) +
                " kg m^2 <= 0 (eta_b = " + format_value(k) + ")"
          : std::string();
  jam("the motor's friction and the gear stage admit no consistent stick/slip state with the "
      "thread's friction" + painleve + (failure.empty() ? std::string() : " (" + failure + ")"));
}

// A stick at its static set's edge (a torque equal to the breakaway
// torque) may miss it by the solve's round-off once the thread's mode
// changed: kept within kRotorEdge of the torques' scale, its margin's root
// measured from there (rotor_margin_offset_), as the thread's slip root
// from its round-off.
// The stage's power-flow root flow s tau_b at a slip's start: where the
// round-off leaves it below zero (a flow consistent within its slack, or
// just reversed at the root), it is measured from there, so that it starts
// at exactly 0 and any real reversal crosses it (as the thread's slip root
// from its round-off, start_mode).
void DriveHybrid::start_flow_root(const ModeSolution& s) {
  rotor_flow_offset_ = 0.0;
  if (rotor_mode_.slip == 0 || !rotor_train_->stage) return;
  rotor_flow_offset_ =
      std::min(0.0, rotor_mode_.flow * rotor_mode_.slip * rotor_stage_torque(s));
}

void DriveHybrid::settle_rotor(double t, double* y) {
  set(t, y);
  const ModeSolution s = solve_current();
  if ((rotor_mode_.slip == 0 ? stick_at_edge(s) : flow_at_edge(s)) && held_stop_presses(s))
    return;
  decide_rotor(t, y, rotor_mode_.slip == 0, false);
}

// A slip whose flow holds to within kRotorEdge of the torques' scale (a
// flow just reversed at its root, its torque at its round-off): kept, its
// root from there (start_flow_root).
bool DriveHybrid::flow_at_edge(const ModeSolution& s) {
  if (!s.regular || !(rotor_mode_.slip * v_[model_.rotor()] > 0.0)) return false;
  const moreau_contacts::RotorBalance balance = rotor_balance();
  const double band = kRotorEdge * (std::abs(balance.h0) + balance.friction +
                                    std::abs(s.rotor_friction) + thread_torque_scale(s));
  if (rotor_train_->stage &&
      rotor_mode_.flow * rotor_mode_.slip * rotor_stage_torque(s) < -band)
    return false;
  start_flow_root(s);
  return true;
}

// A stick consistent to within kRotorEdge of the torques' scale: its
// margin's root measured from that band's lower end where it starts in it
// (the root then fires where the margin leaves the band, not on round-off).
bool DriveHybrid::stick_at_edge(const ModeSolution& s) {
  if (!s.regular) return false;
  const moreau_contacts::RotorBalance balance = rotor_balance();
  const double margin = balance.stick_margin(*rotor_train_, s.rotor_friction);
  const double band = kRotorEdge * (std::abs(balance.h0) + balance.friction +
                                    std::abs(s.rotor_friction) + thread_torque_scale(s));
  if (margin < -band) return false;
  rotor_margin_offset_ = margin < band ? std::min(margin, 0.0) - band : 0.0;
  return true;
}

// The element: its roots and their events.
class DriveHybrid::RotorContact final : public DriveHybrid::Element {
 public:
  RotorContact(DriveHybrid& hybrid, const elements::TrainFriction& train)
      : Element(hybrid), hybrid_(hybrid) {
    hybrid.rotor_train_ = &train;
  }
  // g0: slip: s phi_r' (falls through 0 at a stall); stick: the static
  // margin. g1: slip with a stage: the stage's power flow, flow s tau_b.
  int root_count() const override { return 2; }
  void roots(double t, double* g) const override {
    (void)t;
    g[0] = g[1] = 1.0;
    const moreau_contacts::RotorMode& mode = hybrid_.rotor_mode_;
    const ModeSolution s = hybrid_.solve_current();
    if (mode.slip != 0) {
      g[0] = mode.slip * hybrid_.v_[hybrid_.model_.rotor()];
      if (hybrid_.rotor_train_->stage)
        g[1] = mode.flow * mode.slip * hybrid_.rotor_stage_torque(s) - hybrid_.rotor_flow_offset_;
    } else {
      g[0] = hybrid_.rotor_balance().stick_margin(*hybrid_.rotor_train_, s.rotor_friction) -
             hybrid_.rotor_margin_offset_;
    }
  }
  void root_directions(int* directions) const override { directions[0] = directions[1] = -1; }
  Event handle(double t, double* y, const int* root_info) override {
    const moreau_contacts::RotorMode before = hybrid_.rotor_mode_;
    if (root_info[0] != 0) {
      // (A slip's root: the rotor's speed through zero, located to the
      // root finder's tolerance, is at rest: projected to exactly zero.)
      hybrid_.decide_rotor(t, y, before.slip == 0, true);
    } else if (root_info[1] != 0) {
      // The stage's torque through zero: the flow reverses (its root from
      // the new flow's round-off).
      hybrid_.rotor_mode_.flow = -before.flow;
      hybrid_.set(t, y);
      hybrid_.start_flow_root(hybrid_.solve_current());
    }
    const moreau_contacts::RotorMode& after = hybrid_.rotor_mode_;
    if (after.slip == before.slip && after.flow == before.flow) return {"", true};
    return {after.slip == 0      ? "rotor stick"
            : before.slip == 0   ? "rotor breakaway"
            : after.slip != before.slip ? "rotor reversal"
                                 : "gear stage power flow reversal",
            true};
  }

 private:
  DriveHybrid& hybrid_;
};

// The registry's factory (element_registry.cpp): the stages with a torque or
// DC motor where TrainSolver does not run them (mode_solver.cpp).
std::unique_ptr<DriveHybrid::Element> make_train_friction_element(DriveHybrid& hybrid,
                                                                  const DriveModel& model) {
  const elements::TrainFriction* train = model.train_friction();
  if (!train || model.motor().speed_controlled || DriveHybrid::train_solver_applies(model))
    return nullptr;
  return DriveHybrid::make_rotor_contact(hybrid, *train);
}

std::unique_ptr<DriveHybrid::Element> DriveHybrid::make_rotor_contact(
    DriveHybrid& hybrid, const elements::TrainFriction& train) {
  return std::make_unique<RotorContact>(hybrid, train);
}

}  // namespace leadscrew::model::drive
