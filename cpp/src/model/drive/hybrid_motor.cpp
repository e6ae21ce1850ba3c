// A DC motor's current (elements/dc_motor.hpp) as an element of the
// event-driven driver (driver_element.hpp): its declaration (its current
// and copper loss in y, its channels), its rates and channels, and the
// current limit's root and hold. The motor's torque k_t i enters the forces
// through DriveDynamics (set_motor_current, set_state), so every mode, root
// and impact sees it as a state's function.
#include <algorithm>
#include <cmath>

#include "driver_element.hpp"

namespace leadscrew::model::drive {

const ElementKind& dc_motor_kind();

namespace {

// Its channels (the declaration's, in this order).
enum Channel { kCurrent, kVoltage, kCopperLoss, kMagnetic };

void declare(const DriveModel& model, bool bristle, Declaration& d) {
  (void)bristle;
  const elements::DcMotor* dc = model.dc_motor();
  if (!dc) return;
  // With inductance its current is a state; the copper loss is an integral.
  if (dc->has_state()) d.states.push_back("motor_current");
  d.states.push_back("copper_loss");
  d.channels = dc_motor_kind().catalog;
  // (The magnetic energy L i^2 / 2 is kinetic-like: |L i| <= sqrt(2 E L).)
  d.momentum_mass = dc->inductance;
}

class DcMotorElement final : public DriveHybrid::Element {
 public:
  using Limiter = elements::DcMotor::Limiter;

  DcMotorElement(DriveHybrid& hybrid, const elements::DcMotor& dc)
      : Element(hybrid), dc_(dc), limit_root_(dc.has_state() && dc.limited()) {}

  // One root with inductance and a current limit: free, the margin to the
  // limit [A]; holding, the driver's push beyond it or its supply's margin
  // beyond the hold, whichever ends first [V]; saturated, the current's
  // excess over the limit [A].
  int root_count() const override { return limit_root_ ? 1 : 0; }
  void roots(double t, double* g) const override {
    if (limit_root_) g[0] = limit_margin(t);
  }
  void root_directions(int* directions) const override {
    if (limit_root_) directions[0] = -1;  // each margin ends falling through zero
  }
  // The event changes the limiter's mode (the current snapped onto the
  // limit where it reaches it); the mechanical mode changes only with
  // another root.
  Event handle(double t, double* y, const int* root_info) override {
    (void)root_info;
    return {change_limiter(t, y), false};
  }
  // After a mechanical event: an impact's jump of the rotor's speed may end
  // the driver's push, or its supply's reach, at once (the root would start
  // beyond its zero).
  void after_mode_change(double t, const double* y) override {
    if (limiter_.mode != Limiter::holding) return;
    set(t, y);
    if (limit_margin(t) < 0.0) limiter_ = decide_at_limit(t, limiter_.side);
  }

  // At a start (the run's, or a resumed piece's new element after an input
  // changed): the limiter's mode from the state, as its events leave it:
  // beyond the limit saturated (until the current is back at it), at the
  // limit decided as at the event, else free. (Started free, a current
  // beyond the limit lost its limiter: its root starts below zero.)
  void start(double t, const double* y) override {
    limiter_ = {};
    if (!limit_root_) return;
    set(t, y);
    const double current = dynamics().motor_current();
    const int side = current >= 0.0 ? 1 : -1;
    const double excess = std::abs(current) - dc_.current_limit;
    if (excess > 0.0) limiter_ = {Limiter::saturated, side};
    else if (excess == 0.0) limiter_ = decide_at_limit(t, side);
  }

  // Its current's rate, its copper loss rate and the electrical work's rate
  // (which replaces the motor torque's power in the drive's work).
  void rates(double t, const double* y, double* ydot, double* energy) const override {
    (void)y;
    const double current = dynamics().motor_current();
    const double omega = v()[dc_.rotor];
    if (dc_.has_state()) ydot[current_state()] = dc_.rate(t, current, omega, limiter_);
    ydot[copper_state()] = dc_.copper_loss_rate(current);
    energy[kWorkDrive] = dc_.work_rate(t, current, omega, limiter_);
  }
  // Its channels: current, the driver's voltage, copper loss, magnetic energy.
  void output(double t, const double* y, const ContactForces& forces,
              ChannelState& state) const override {
    (void)forces;
    const double current = dynamics().motor_current();
    double* values = state.values.data() + first_channel();
    values[kCurrent] = current;
    values[kVoltage] = dc_.terminal_voltage(t, current, v()[dc_.rotor], limiter_);
    values[kCopperLoss] = y[copper_state()];
    values[kMagnetic] = dc_.magnetic_energy(current);
  }
  // Its torque k_t i depends on the state: its roots are the state's.
  bool forces_from_loads_alone() const override { return false; }

 private:
  // Its states in y: the current (with inductance), then the copper loss.
  int current_state() const { return first_state(); }
  int copper_state() const { return first_state() + (dc_.has_state() ? 1 : 0); }

  double limit_margin(double t) const {
    const double current = dynamics().motor_current(), omega = v()[dc_.rotor];
    const int side = limiter_.side;
    switch (limiter_.mode) {
      case Limiter::holding:
        return std::min(dc_.push_beyond(t, side, omega), dc_.supply_margin(t, side, omega));
      case Limiter::saturated: return side * current - dc_.current_limit;
      default: return dc_.current_limit - std::abs(current);
    }
  }

  // The limiter's mode with the current at side i_max: free where U(t)
  // does not drive it further (a touch without push stays free), holding
  // where the supply reaches the hold, else saturated (the current passes).
  Limiter decide_at_limit(double t, int side) const {
    const double omega = v()[dc_.rotor];
    if (dc_.push_beyond(t, side, omega) <= 0.0) return {};
    if (dc_.supply_margin(t, side, omega) < 0.0) return {Limiter::saturated, side};
    return {Limiter::holding, side};
  }

  std::string change_limiter(double t, double* y) {
    set(t, y);
    const Limiter before = limiter_;
    int side = limiter_.side;
    if (limiter_.mode == Limiter::holding) {
      // Which margin ended: the push (released) or the supply's (saturated).
      const double omega = v()[dc_.rotor];
      limiter_ = dc_.push_beyond(t, side, omega) <= dc_.supply_margin(t, side, omega)
                     ? Limiter{}
                     : Limiter{Limiter::saturated, side};
    } else {
      // The current reached the limit (free), or came back to it (saturated).
      if (limiter_.mode == Limiter::free) side = dynamics().motor_current() >= 0.0 ? 1 : -1;
      y[current_state()] = side * dc_.current_limit;  // at the limit, to round-off
      set(t, y);
      limiter_ = decide_at_limit(t, side);
    }
    return describe(before, limiter_);
  }

  static std::string describe(Limiter before, Limiter after) {
    if (after.mode == before.mode) return "";
    if (after.mode == Limiter::holding) return "current limit reached";
    if (after.mode == Limiter::saturated)
      return "current limit passed: the back-EMF exceeds the driver's supply";
    return "current limit released";
  }

  const elements::DcMotor& dc_;
  bool limit_root_;   // with inductance and a current limit
  Limiter limiter_;   // the driver's current limiter (free at the start)
};

}  // namespace

const ElementKind& dc_motor_kind() {
  static const ElementKind kind{"dc_motor",
                                {{"motor_current", "A", Role::none},
                                 {"motor_voltage", "V", Role::none},
                                 {"copper_loss", "J", Role::loss},
                                 {"magnetic_energy", "J", Role::stored}},
                                &declare};
  return kind;
}

std::unique_ptr<DriveHybrid::Element> make_dc_motor_element(DriveHybrid& hybrid,
                                                            const DriveModel& model) {
  if (!model.dc_motor()) return nullptr;
  return std::make_unique<DcMotorElement>(hybrid, *model.dc_motor());
}

}  // namespace leadscrew::model::drive
