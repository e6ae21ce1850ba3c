// Element: a permanent-magnet DC motor on the rotor (elements/dc_motor.hpp,
// its physics; docs/physics/dc_motor.md), the whole of it behind the
// element interface (model/element.hpp): its declaration (the current with
// inductance and the copper loss in y; motor_current [A], motor_voltage [V],
// copper_loss [J] a loss, magnetic_energy [J] stored), its torque k_t i on
// the rotor (the drive's torque), the rates of its current and copper loss
// and the electrical work, the current limiter's root and modes (free,
// holding, saturated beyond the driver's supply), its Moreau-Jean step (the
// armature integrated exactly over the step, DcMotor::armature_step; the
// step taken again with the current held at the limit, then saturated),
// its channels and its result checks (driver_voltage, motor_torque,
// armature); its section (its parameters, their rules, its input the
// voltage, its FMU variables: dc_motor_section). One line in the registry
// (drive/element_registry.cpp, S(dc_motor)).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "../check_rows.hpp"
#include "../drive/declaration.hpp"
#include "../drive/state_layout.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/simulation_result.hpp"
#include "leadscrew/model/drive_simulation.hpp"
#include "leadscrew/model/element.hpp"
#include "leadscrew/model/element_section.hpp"
#include "leadscrew/model/elements/dc_motor.hpp"

namespace leadscrew::model {

namespace drive {
const ElementKind& dc_motor_kind();
}

namespace {

using elements::DcMotor;
using Limiter = DcMotor::Limiter;

// Its channels (the declaration's, in this order).
enum Channel { kCurrent, kVoltage, kCopperLoss, kMagnetic };

Limiter limiter_of(const ElementMode& m) { return {static_cast<Limiter::Mode>(m.mode), m.side}; }
void set_limiter(ElementMode& m, Limiter l) {
  m.mode = l.mode;
  m.side = l.side;
}

class DcMotorElement final : public Element {
 public:
  // `rotor_torque_constant`, `rotor_back_emf_constant`: the motor's own, at
  // its shaft (dc's are the rotor's coordinate's, behind a gear: gear.hpp).
  DcMotorElement(const DcMotor& dc, double rotor_torque_constant, double rotor_back_emf_constant)
      : dc_(dc),
        limit_root_(dc.has_state() && dc.limited()),
        rotor_torque_constant_(rotor_torque_constant),
        rotor_back_emf_constant_(rotor_back_emf_constant) {}

  const char* name() const override { return "dc_motor"; }

  void declare(drive::Declaration& d) const override {
    // With inductance its current is a state; the copper loss is an integral.
    if (dc_.has_state()) d.states.push_back("motor_current");
    d.states.push_back("copper_loss");
    d.channels = drive::dc_motor_kind().catalog;
    // (The magnetic energy L i^2 / 2 is kinetic-like: |L i| <= sqrt(2 E L).)
    d.momentum_mass = dc_.inductance;
  }

  // The current: the state with inductance, else quasi-static at the speed.
  double current(const ElementState& s) const {
    return dc_.has_state() ? s.own[0] : dc_.quasi_static_current(s.t, s.v[dc_.rotor]);
  }

  // In a static equilibrium the armature is steady at rest (omega = 0, no
  // back-EMF): i = U(0) / R, the driver holding it at side i_max where that
  // passes its limit (U(0) drives it further there; R i_max < |U(0)| lies
  // within the supply). Exactly +-i_max, so that the limiter starts holding
  // (start: at the limit, decided), not a round-off beyond it, saturated.
  // Without inductance the current is quasi-static, no state: its torque at
  // rest is the same. The relaxed start: the driver switched on at t = 0,
  // the current at 0.
  void initial_states(const ElementState& s, bool at_equilibrium, double* own) const override {
    if (!at_equilibrium || !dc_.has_state()) return;
    const double steady = (dc_.voltage(s.t) - dc_.back_emf_constant * s.v[dc_.rotor]) /
                          dc_.resistance;
    own[0] = dc_.limited() && std::abs(steady) > dc_.current_limit
                 ? std::copysign(dc_.current_limit, steady)
                 : steady;
  }

  void add_forces(const ElementState& s, const ElementMode& mode, double* forces) const override {
    (void)mode;
    forces[dc_.rotor] += dc_.torque(current(s));
  }
  bool drives_rotor() const override { return true; }
  // Its torque k_t i depends on the state: its roots are the state's.
  bool forces_from_loads_alone() const override { return false; }

  // Its current's rate, its copper loss rate and the electrical work's rate
  // (which replaces the motor torque's power in the drive's work).
  void rates(const ElementState& s, const ElementMode& mode, double* own_rates,
             double* energy) const override {
    const double i = current(s), omega = s.v[dc_.rotor];
    const Limiter limiter = limiter_of(mode);
    if (dc_.has_state()) own_rates[0] = dc_.rate(s.t, i, omega, limiter);
    own_rates[copper()] = dc_.copper_loss_rate(i);
    energy[drive::kWorkDrive] = dc_.work_rate(s.t, i, omega, limiter);
  }
  void output(const ElementState& s, const ElementMode& mode, double* values) const override {
    const double i = current(s);
    values[kCurrent] = i;
    values[kVoltage] = dc_.terminal_voltage(s.t, i, s.v[dc_.rotor], limiter_of(mode));
    values[kCopperLoss] = s.own[copper()];
    values[kMagnetic] = dc_.magnetic_energy(i);
  }
  // The magnetic energy and the copper loss booked (Moreau-Jean's step account).
  double energy_terms(const ElementState& s) const override {
    return dc_.magnetic_energy(dc_.has_state() ? s.own[0] : 0.0) + s.own[copper()];
  }

  // One root with inductance and a current limit: free, the margin to the
  // limit [A]; holding, the driver's push beyond it or its supply's margin
  // beyond the hold, whichever ends first [V]; saturated, the current's
  // excess over the limit [A].
  int root_count() const override { return limit_root_ ? 1 : 0; }
  void roots(const ElementState& s, const ElementMode& mode, double* g) const override {
    if (limit_root_) g[0] = limit_margin(s, limiter_of(mode));
  }
  void root_directions(int* directions) const override {
    if (limit_root_) directions[0] = -1;  // each margin ends falling through zero
  }
  // The event changes the limiter's mode (the current snapped onto the
  // limit where it reaches it); the thread's mode changes only with another
  // root.
  ElementEvent handle(const ElementState& s, ElementMode& mode, double* own) const override {
    const Limiter before = limiter_of(mode);
    Limiter after = before;
    int side = before.side;
    const double omega = s.v[dc_.rotor];
    if (before.mode == Limiter::holding) {
      // Which margin ended: the push (released) or the supply's (saturated).
      after = dc_.push_beyond(s.t, side, omega) <= dc_.supply_margin(s.t, side, omega)
                  ? Limiter{}
                  : Limiter{Limiter::saturated, side};
    } else {
      // The current reached the limit (free), or came back to it (saturated).
      if (before.mode == Limiter::free) side = own[0] >= 0.0 ? 1 : -1;
      own[0] = side * dc_.current_limit;  // at the limit, to round-off
      after = decide_at_limit(s.t, side, omega);
    }
    set_limiter(mode, after);
    return {describe(before, after), false};
  }
  // After a mechanical event: an impact's jump of the rotor's speed may end
  // the driver's push, or its supply's reach, at once (the root would start
  // beyond its zero).
  void after_mode_change(const ElementState& s, ElementMode& mode) const override {
    const Limiter limiter = limiter_of(mode);
    if (limiter.mode != Limiter::holding) return;
    if (limit_margin(s, limiter) < 0.0)
      set_limiter(mode, decide_at_limit(s.t, limiter.side, s.v[dc_.rotor]));
  }
  // At a start (the run's, or a resumed piece's new element after an input
  // changed): the limiter's mode from the state, as its events leave it:
  // beyond the limit saturated (until the current is back at it), at the
  // limit decided as at the event, else free. (Started free, a current
  // beyond the limit lost its limiter: its root starts below zero.)
  void start(const ElementState& s, ElementMode& mode) const override {
    set_limiter(mode, {});
    if (!limit_root_) return;
    const double i = s.own[0];
    const int side = i >= 0.0 ? 1 : -1;
    const double excess = std::abs(i) - dc_.current_limit;
    if (excess > 0.0) set_limiter(mode, {Limiter::saturated, side});
    else if (excess == 0.0) set_limiter(mode, decide_at_limit(s.t, side, s.v[dc_.rotor]));
  }

  // Moreau-Jean. A step is taken free, with the driver's voltage u at
  // t + theta h; where its current passes the limit it is taken again with
  // the current held there, and where holding it needs more than the
  // driver's supply |u| (a back-EMF beyond it) once more with the driver
  // saturated at -side |u|: the current then passes the limit
  // (docs/physics/dc_motor.md, "Moreau-Jean"). mode.last: the step's
  // current (DcMotor::step_current) and its driver's voltage.
  ElementMode step_first(const ElementMode& mode) const override {
    ElementMode first = mode;
    set_limiter(first, {});
    return first;
  }
  // Its mean current over the step, i_mean = mean + mean_slope omega+: its
  // torque's impulse h k_t i_mean in place of the start's h k_t i (the
  // step's right-hand side has that), its slope an implicit damping.
  void step_impulse(const ElementStep& step, const ElementMode& mode, double* constant,
                    double* slope) const override {
    const DcMotor::ArmatureStep a = armature(step, mode);
    constant[dc_.rotor] += step.h * (dc_.torque(a.mean) - dc_.torque(current(step.start)));
    slope[dc_.rotor] += step.h * dc_.torque(a.mean_slope);
  }
  double step_rotor_impulse(const ElementStep& step, const ElementMode& mode) const override {
    return step.h * dc_.torque(armature(step, mode).mean);
  }
  // The armature over the step (exact for its driver voltage and back-EMF):
  // its mean current, its end, the driver's voltage over it, the electrical
  // work and the copper loss, which with the magnetic energy's change close
  // the circuit's account: h U_d i_mean = copper + d(L i^2 / 2) + h k_e
  // omega_theta i_mean.
  void step_end(const ElementStep& step, const double* q_next, const double* v_next,
                ElementMode& mode, double* own_next, double* energy) const override {
    (void)q_next;
    const DcMotor::ArmatureStep a = armature(step, mode);
    const double omega_next = v_next[dc_.rotor];
    const double omega_theta =
        (1.0 - step.theta) * step.start.v[dc_.rotor] + step.theta * omega_next;
    const double i_mean = a.mean_current(omega_next);
    const double voltage = dc_.step_voltage(a, omega_theta, omega_next);
    energy[drive::kWorkDrive] +=
        step.h * (voltage * i_mean +
                  (dc_.torque_constant - dc_.back_emf_constant) * i_mean * omega_theta);
    own_next[copper()] = step.start.own[copper()] + dc_.step_copper_loss(a, step.h, omega_next);
    if (dc_.has_state()) own_next[0] = a.end_current(omega_next);
    mode.last[0] = dc_.step_current(a, omega_next);
    mode.last[1] = voltage;
  }
  bool step_mode(const ElementStep& step, const ElementMode& taken,
                 ElementMode& retake) const override {
    const Limiter limiter = limiter_of(taken);
    if (!dc_.limited() || limiter.mode == Limiter::saturated) return false;
    const double u = dc_.voltage(step.start.t);
    if (limiter.mode == Limiter::free) {
      if (!(std::abs(taken.last[0]) > dc_.current_limit)) return false;
      retake = taken;
      set_limiter(retake, {Limiter::holding, taken.last[0] > 0.0 ? 1 : -1});
      return true;
    }
    if (limiter.side * taken.last[1] >= -std::abs(u)) return false;
    retake = taken;
    set_limiter(retake, {Limiter::saturated, limiter.side});
    return true;
  }
  // At a run's start: the current of its state and its driver's voltage.
  void step_start(const ElementState& s, ElementMode& mode) const override {
    mode = {};
    const double i = current(s);
    mode.last[0] = i;  // (row 0's: the initial state's)
    mode.last[1] = dc_.terminal_voltage(s.t, i, s.v[dc_.rotor], {});
  }
  // The current of the last step's armature, with its driver voltage: L > 0
  // its end i+ (the state), L = 0 its quasi-static current at omega_theta
  // (the limit x -> infinity), not the one at the row's speed: a step that
  // held the limit and ended where the free current is below it reported
  // the hold's voltage with a free current, no armature relation.
  void step_output(const ElementState& s, const ElementMode& mode, double* values) const override {
    values[kCurrent] = dc_.has_state() ? s.own[0] : mode.last[0];
    values[kVoltage] = mode.last[1];  // over the last step
    values[kCopperLoss] = s.own[copper()];
    values[kMagnetic] = dc_.has_state() ? dc_.magnetic_energy(values[kCurrent]) : 0.0;
  }
  double step_drive_torque(const ElementState& s, const ElementMode& mode) const override {
    return dc_.torque(dc_.has_state() ? s.own[0] : mode.last[0]);
  }

  void check_result(const DriveSimulationOptions& options, bool time_stepping,
                    integrate::SimulationResult& result) const override;

 private:
  // Its copper loss's index among its states (after the current, with inductance).
  int copper() const { return dc_.has_state() ? 1 : 0; }

  DcMotor::ArmatureStep armature(const ElementStep& step, const ElementMode& mode) const {
    const double u = dc_.voltage(step.start.t);
    const Limiter limiter = limiter_of(mode);
    const int held = limiter.mode == Limiter::holding ? limiter.side : 0;
    const double driver = limiter.mode == Limiter::saturated ? -limiter.side * std::abs(u) : u;
    return dc_.armature_step(driver, step.h, step.theta, current(step.start),
                             step.start.v[dc_.rotor], held);
  }

  double limit_margin(const ElementState& s, Limiter limiter) const {
    const double i = s.own[0], omega = s.v[dc_.rotor];
    const int side = limiter.side;
    switch (limiter.mode) {
      case Limiter::holding:
        return std::min(dc_.push_beyond(s.t, side, omega), dc_.supply_margin(s.t, side, omega));
      case Limiter::saturated: return side * i - dc_.current_limit;
      default: return dc_.current_limit - std::abs(i);
    }
  }

  // The limiter's mode with the current at side i_max: free where U(t)
  // does not drive it further (a touch without push stays free), holding
  // where the supply reaches the hold, else saturated (the current passes).
  Limiter decide_at_limit(double t, int side, double omega) const {
    if (dc_.push_beyond(t, side, omega) <= 0.0) return {};
    if (dc_.supply_margin(t, side, omega) < 0.0) return {Limiter::saturated, side};
    return {Limiter::holding, side};
  }

  static std::string describe(Limiter before, Limiter after) {
    if (after.mode == before.mode) return "";
    if (after.mode == Limiter::holding) return "current limit reached";
    if (after.mode == Limiter::saturated)
      return "current limit passed: the back-EMF exceeds the driver's supply";
    return "current limit released";
  }

  DcMotor dc_;
  bool limit_root_;  // with inductance and a current limit
  double rotor_torque_constant_, rotor_back_emf_constant_;
};

// ---- Its result checks (docs/physics/result_checks.md, "driver_voltage,
// motor_torque", "armature").

// Channel `channel`'s value at output row `row` (the point-major table).
double value(const integrate::SimulationResult& result, int channel, std::size_t row) {
  return result.values[row * result.channel_count() + static_cast<std::size_t>(channel)];
}

// A check's record (check_rows.hpp), its value -inf until a row is offered.
integrate::InvariantCheck motor_check(const char* name, const char* what, const char* unit) {
  integrate::InvariantCheck c = check_rows::make_check(name, what, unit);
  c.value = -std::numeric_limits<double>::infinity();
  return c;
}

// The rows' channels the checks read.
struct MotorRows {
  int current, voltage, torque, omega;
  explicit MotorRows(const integrate::SimulationResult& r)
      : current(r.channel_index("motor_current")),
        voltage(r.channel_index("motor_voltage")),
        torque(r.channel_index("drive_torque")),
        omega(r.channel_index("omega_drive")) {}
};

// U_d = R i + k_e omega at every row of a motor without inductance, the
// quasi-static armature (docs/physics/dc_motor.md): at the row's speed on
// the event-driven scheme, on Moreau-Jean at omega_theta of the step that
// ends at the row (its rows report the step's armature; row 0 its own
// speed; rows interpolated between steps are skipped, as by driver_voltage).
// Round-off: 1e-12 of the circuit's largest voltage term `volts`. (A step
// that held the current limit and ended where the free current lies below
// it once reported the hold's voltage with the free current: 0.05 V off of
// 16 V, every other check passing.)
integrate::InvariantCheck armature_check(const DcMotor& dc, double back_emf_constant, double theta,
                                         bool time_stepping, double volts,
                                         const integrate::SimulationResult& result) {
  integrate::InvariantCheck c = motor_check(
      "armature", "without inductance the DC motor's armature is quasi-static: "
                  "motor_voltage = R motor_current + k_e omega (docs/physics/dc_motor.md)", "V");
  c.applies = !dc.has_state() && !(time_stepping && result.interpolated);
  const MotorRows rows(result);
  check_rows::Worst worst{c};
  for (std::size_t i = 0; i < result.point_count() && c.applies; ++i) {
    double speed = value(result, rows.omega, i);
    if (time_stepping && i > 0)
      speed = (1.0 - theta) * value(result, rows.omega, i - 1) + theta * speed;
    const double voltage = value(result, rows.voltage, i);
    const double current = value(result, rows.current, i);
    worst.offer(std::abs(voltage - dc.resistance * current - back_emf_constant * speed),
                1e-12 * volts, result.time[i]);
  }
  return c;
}

// |U_d| <= |U| where the driver's voltage applies at the row: the
// event-driven scheme's row time; Moreau-Jean's last step's t + theta h
// (its rows are its step ends; rows interpolated between them are not the
// scheme's: skipped, as the force checks skip them). The event-driven row
// just before an event is at its located root, where the supply's margin
// has just changed sign by up to its rate times the root's time resolution
// (a voltage step of the end_stop_jam study: 5e-7 V at 2e10 V/s): skipped
// as the force checks skip it; the row after it is the new mode's.
integrate::InvariantCheck supply_check(const DcMotor& dc, double theta, bool time_stepping,
                                       double volts, const integrate::SimulationResult& result) {
  integrate::InvariantCheck supply = motor_check(
      "driver_voltage", "the DC motor's driver puts out no more than its supply: "
                        "|motor_voltage| <= |U(t)| (docs/physics/dc_motor.md)", "V");
  supply.applies = !(time_stepping && result.interpolated);
  const int voltage = result.channel_index("motor_voltage");
  check_rows::Worst worst{supply};
  const std::size_t n = result.point_count();
  for (std::size_t i = 0; i < n && supply.applies; ++i) {
    double t = result.time[i];
    if (!time_stepping && i + 1 < n && result.time[i + 1] == t) continue;  // (at an event's root)
    if (time_stepping && i > 0) t = result.time[i - 1] + theta * (t - result.time[i - 1]);
    worst.offer(std::abs(value(result, voltage, i)), std::abs(dc.voltage(t)) + 1e-12 * volts,
                result.time[i]);
  }
  return supply;
}

void DcMotorElement::check_result(const DriveSimulationOptions& options, bool time_stepping,
                                  integrate::SimulationResult& result) const {
  if (result.checks.empty() || !result.checks.front().passed) return;  // (not finite)
  const MotorRows rows(result);
  // The round-off scales: the circuit's largest voltage term and torque.
  double volts = 0.0, newton_metres = 0.0;
  for (std::size_t i = 0; i < result.point_count(); ++i) {
    const double u = std::abs(dc_.voltage(result.time[i]));
    volts = std::max({volts, u, std::abs(value(result, rows.voltage, i)),
                      dc_.resistance * std::abs(value(result, rows.current, i)),
                      rotor_back_emf_constant_ * std::abs(value(result, rows.omega, i))});
    newton_metres = std::max(newton_metres, std::abs(value(result, rows.torque, i)));
  }
  result.checks.push_back(supply_check(dc_, options.theta, time_stepping, volts, result));
  // drive_torque = k_t motor_current at every row (the rotor's torque).
  integrate::InvariantCheck channel = motor_check(
      "motor_torque", "drive_torque is the DC motor's torque k_t motor_current at every row",
      "N*m");
  check_rows::Worst worst{channel};
  for (std::size_t i = 0; i < result.point_count(); ++i)
    worst.offer(std::abs(value(result, rows.torque, i) -
                         rotor_torque_constant_ * value(result, rows.current, i)),
                1e-12 * newton_metres, result.time[i]);
  result.checks.push_back(channel);
  result.checks.push_back(
      armature_check(dc_, rotor_back_emf_constant_, options.theta, time_stepping, volts, result));
}

void declare(const DriveModel& model, const friction::Law& law, drive::Declaration& d) {
  (void)law;
  drive::declare_model_element(model, "dc_motor", d);
}

// ---- Its section: the scene's `motor` section with type = "dc" (the
// Python scene schema declares that section, the motor's friction torque
// in it, and hands these fields over as DriveParameters' attributes).

// The DC motor's own time constants, its rotor alone (before a gear): the
// mechanical J R / (k_t k_e) (the back-EMF's damping of the rotor) and the
// electrical L / R. The fastest motors built have about 1 ms and 1 us
// (coreless micro motors); a thousand times below, the values are a unit's
// mistake, and the run would grind through ever shorter steps to a solver
// failure that names no input (a torque constant of 1e6 N m/A: 9 s to
// CV_TOO_MUCH_WORK on the seat adjuster; 1e3, 3e-12 s: 5.6 s to the same).
// Issue 19's review.
constexpr double kShortestMechanicalTimeConstant = 1e-6;  // [s]
constexpr double kShortestElectricalTimeConstant = 1e-9;  // [s]

// Its constants as the section gives them (motor.*; the scene's `motor`
// section, type = "dc").
struct Constants {
  double resistance, inductance, torque_constant, back_emf_given, current_limit;
  explicit Constants(const Section& s)
      : resistance(s.number("resistance")),
        inductance(s.number("inductance")),
        torque_constant(s.number("torque_constant")),
        back_emf_given(s.number("back_emf_constant")),
        current_limit(s.number("current_limit")) {}
  // k_e: motor.back_emf_constant, or k_t where it is not given (< 0).
  double back_emf_constant() const {
    return back_emf_given < 0.0 ? torque_constant : back_emf_given;
  }
};

void check_time_constants(const Constants& m, const DriveParameters& p) {
  const double mechanical =
      p.rotor_inertia * m.resistance / (m.torque_constant * m.back_emf_constant());
  if (!(mechanical >= kShortestMechanicalTimeConstant))
    throw InvalidArgument(
        "motor.torque_constant = " + format_value(m.torque_constant) +
        (m.back_emf_given < 0.0
             ? std::string()
             : ", motor.back_emf_constant = " + format_value(m.back_emf_given)) +
        ", motor.resistance = " + format_value(m.resistance) + " and rotor.inertia = " +
        format_value(p.rotor_inertia) +
        " are invalid together: with them the DC motor's mechanical time constant "
        "rotor.inertia * motor.resistance / (motor.torque_constant * "
        "motor.back_emf_constant) comes to " +
        format_value(mechanical) + " s: must be at least " +
        format_value(kShortestMechanicalTimeConstant) +
        " s (the fastest motors built have about 1e-3 s: check the units)");
  const double inductance = m.inductance, resistance = m.resistance;
  if (inductance > 0.0 && !(inductance / resistance >= kShortestElectricalTimeConstant))
    throw InvalidArgument("motor.inductance = " + format_value(inductance) +
                          " and motor.resistance = " + format_value(resistance) +
                          " are invalid together: with them the DC motor's electrical time "
                          "constant "
                          "motor.inductance / motor.resistance comes to " +
                          format_value(inductance / resistance) + " s: must be at least " +
                          format_value(kShortestElectricalTimeConstant) +
                          " s (the fastest motors built have about 1e-6 s), or 0 (the "
                          "quasi-static limit, exact: no current dynamics)");
}

// The DC motor (motor.type = "dc"): the rotor's only drive, started from
// rest in its current, with plausible constants.
void check(const Section& s, const DriveParameters& p, const MessageStyle& style) {
  (void)style;  // (its section is the scene's motor section: the core's messages)
  if (p.speed_controlled)
    throw InvalidArgument("loads.drive_speed is invalid with motor.type = \"dc\": give "
                          "either the DC motor or loads.drive_speed (or loads.drive_torque), "
                          "not both");
  const Excitation::Definition torque = p.drive_torque.definition();
  if (!(torque.kind == "constant" && torque.parameters.at(0) == 0.0))
    throw InvalidArgument("loads.drive_torque = " + p.drive_torque.describe() +
                          " is invalid with motor.type = \"dc\": give either the DC motor "
                          "or loads.drive_torque, not both");
  const Constants m(s);
  require_positive("motor.resistance", m.resistance);
  require_nonnegative("motor.inductance", m.inductance);
  require_positive("motor.torque_constant", m.torque_constant);
  if (!(m.back_emf_given < 0.0))
    require_positive("motor.back_emf_constant", m.back_emf_given);
  require_nonnegative("motor.current_limit", m.current_limit);
  check_time_constants(m, p);
}

// The DC motor drives the rotor alone (the torque-controlled Motor applies
// 0); built with the motor (SectionType::Stage::motor): its coordinate and
// gear are set.
void build(const Section& s, const DriveParameters& p, elements::DriveElements& e) {
  const Constants c(s);
  DcMotor m;
  m.rotor = e.motor.rotor;
  m.voltage = section_input(p, s.type(), 0);
  m.resistance = c.resistance;
  m.inductance = c.inductance;
  m.torque_constant = c.torque_constant;
  m.back_emf_constant = c.back_emf_constant();
  m.current_limit = c.current_limit;
  // Behind a gear: the motor as its coordinate sees it (gear.hpp).
  m.torque_constant = e.motor.gear.driven_torque(m.torque_constant);
  m.back_emf_constant = e.motor.gear.driven_torque(m.back_emf_constant);
  e.motor.torque = Excitation();
  e.elements.push_back(elements::dc_motor_element(m, c.torque_constant, c.back_emf_constant()));
}

// Its part as the rotor's drive: in the batch's messages, its FMU output.
const RotorDrive kRotorDrive = {
    "a DC motor (motor.type = \"dc\")", "a DC motor (no motor section)", "motor_",
    "motor_current", "A", "the DC motor's armature current"};

}  // namespace

namespace drive {
const ElementKind& dc_motor_kind() {
  static const ElementKind kind{"dc_motor",
                                {{"motor_current", "A", Role::none},
                                 {"motor_voltage", "V", Role::none},
                                 {"copper_loss", "J", Role::loss},
                                 {"magnetic_energy", "J", Role::stored}},
                                &declare};
  return kind;
}
}  // namespace drive

// Its section (element_section.hpp): the fields of the scene's motor
// section, type = "dc", by their attributes (motor_resistance, ...; the
// Python scene checks their ranges and hands them over), their rules
// (check), the voltage its input, the rotor's drive.
SectionType dc_motor_section() {
  SectionType type;
  type.name = "dc_motor";
  type.doc = "(Absent: no DC motor; the loads drive_torque or drive_speed drive the rotor.)";
  type.fields = {
      number("resistance", "Ohm", "the armature's resistance R").defaults(1.0)
          .named("motor_resistance").cosim("Ohm", "the DC motor's armature resistance"),
      number("inductance", "H", "the armature's inductance L (0: quasi-static)").defaults(0.0)
          .named("motor_inductance")
          .cosim("H", "the DC motor's armature inductance (0: quasi-static)"),
      number("torque_constant", "N*m/A", "the torque constant k_t").defaults(0.0)
          .named("motor_torque_constant").cosim("N.m/A", "the DC motor's torque constant"),
      number("back_emf_constant", "V*s/rad", "the back-EMF constant k_e (< 0: k_t)")
          .defaults(-1.0)
          .named("motor_back_emf_constant")
          .cosim("V.s/rad", "the DC motor's back-EMF constant (< 0: the torque constant)"),
      number("current_limit", "A", "the driver's current limit (0: none)").defaults(0.0)
          .named("motor_current_limit").cosim("A", "the driver's current limit (0: none)"),
  };
  type.flag = "dc_motor";
  type.scene = "motor";
  type.stage = SectionType::Stage::motor;
  type.inputs = {{"motor_voltage", "voltage", "V", "V",
                  "the DC motor driver's voltage, held over a step"}};
  type.rotor_drive = &kRotorDrive;
  type.check = &check;
  type.build = &build;
  return type;
}

namespace elements {
std::shared_ptr<const Element> dc_motor_element(const DcMotor& dc, double rotor_torque_constant,
                                                double rotor_back_emf_constant) {
  return std::make_shared<DcMotorElement>(dc, rotor_torque_constant, rotor_back_emf_constant);
}
}  // namespace elements

}  // namespace leadscrew::model
