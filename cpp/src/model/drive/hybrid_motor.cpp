// A DC motor's current (elements/dc_motor.hpp) as an element of the
// event-driven driver (driver_element.hpp): its declaration (its current
// and copper loss in y, its channels), its rates and channels, and the
// current limit's root and hold. The motor's torque k_t i enters the forces
// through DriveDynamics (set_motor_current, set_state), so every mode, root
// and impact sees it as a state's function.
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
  DcMotorElement(DriveHybrid& hybrid, const elements::DcMotor& dc)
      : Element(hybrid), dc_(dc), limit_root_(dc.has_state() && dc.limited()) {}

  // One root with inductance and a current limit: the margin to the limit,
  // or while held the driver's push beyond it.
  int root_count() const override { return limit_root_ ? 1 : 0; }
  void roots(double t, double* g) const override {
    if (limit_root_) g[0] = limit_margin(t);
  }
  void root_directions(int* directions) const override {
    if (limit_root_) directions[0] = -1;  // the limit reached, or the push ends
  }
  // The event holds or releases the current (snapped to the limit); the
  // mechanical mode changes only with another root.
  Event handle(double t, double* y, const int* root_info) override {
    (void)root_info;
    return {change_hold(t, y), false};
  }
  // After a mechanical event: an impact's jump of the rotor's speed may end
  // the driver's push at once (the root would start beyond its zero).
  void after_mode_change(double t, const double* y) override {
    if (held_ == 0) return;
    set(t, y);
    if (limit_margin(t) < 0.0) held_ = 0;
  }

  // Its current's rate, its copper loss rate and the electrical work's rate
  // (which replaces the motor torque's power in the drive's work).
  void rates(double t, const double* y, double* ydot, double* energy) const override {
    (void)y;
    const double current = dynamics().motor_current();
    const double omega = v()[dc_.rotor];
    if (dc_.has_state())
      ydot[current_state()] = held_ != 0 ? 0.0 : dc_.free_rate(t, current, omega);
    ydot[copper_state()] = dc_.copper_loss_rate(current);
    energy[kWorkDrive] = dc_.work_rate(t, current, omega, held_ != 0);
  }
  // Its channels: current, the driver's voltage, copper loss, magnetic energy.
  void output(double t, const double* y, const ContactForces& forces,
              ChannelState& state) const override {
    (void)forces;
    const double current = dynamics().motor_current();
    double* values = state.values.data() + first_channel();
    values[kCurrent] = current;
    values[kVoltage] = dc_.terminal_voltage(t, current, v()[dc_.rotor], held_ != 0);
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
    const double current = dynamics().motor_current();
    if (held_ == 0) return dc_.current_limit - std::abs(current);
    return held_ * dc_.free_rate(t, current, v()[dc_.rotor]);
  }

  std::string change_hold(double t, double* y) {
    set(t, y);
    if (held_ != 0) {
      held_ = 0;
      return "current limit released";
    }
    const int sign = dynamics().motor_current() >= 0.0 ? 1 : -1;
    y[current_state()] = sign * dc_.current_limit;  // at the limit, to round-off
    set(t, y);
    // The current reached the limit driven beyond it (a touch without push
    // stays free).
    if (sign * dc_.free_rate(t, dynamics().motor_current(), v()[dc_.rotor]) <= 0.0) return "";
    held_ = sign;
    return "current limit reached";
  }

  const elements::DcMotor& dc_;
  bool limit_root_;  // with inductance and a current limit
  int held_ = 0;     // the current held at +-current_limit (its sign; 0: free)
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
