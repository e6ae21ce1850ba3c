// An element outside the core, through the element interface alone
// (cpp/include/leadscrew/model/element.hpp; issue 32, item 4): a viscous
// brake on the rotor with one state, its temperature rise, and one event,
// its fade. This file is the whole element, its scene section and the one
// line that registers it (main: register_element_section); the plant and
// both schemes (event-driven, Moreau-Jean) run it without naming it.
//
// The brake: torque -c omega on the rotor; the heat it takes warms it,
// C theta' = c omega^2 (no cooling), so its heat C theta is its loss (a
// channel of role loss: the energy account takes it like any other). Where
// theta reaches theta_fade it fades (an event): c becomes f c.
//
// Closed form on a frictionless rigid drive without loads (one degree of
// freedom, inertia J): omega(t) = omega0 exp(-c t / J) until the fade,
// C theta = J (omega0^2 - omega^2) / 2, so the fade is at
// omega_f^2 = omega0^2 - 2 C theta_fade / J, t_f = (J / c) ln(omega0 / omega_f),
// and omega = omega_f exp(-f c (t - t_f) / J) after it.
//
// Prints `PASS <label> (<count>)` per check, or `FAIL <label>: ...`, and ends
// with OK; exits 1 on a failure.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "declaration.hpp"
#include "leadscrew/integrate/simulation_result.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_simulation.hpp"
#include "leadscrew/model/element.hpp"
#include "leadscrew/model/element_section.hpp"
#include "leadscrew/model/elements/drive_elements.hpp"

namespace lm = leadscrew::model;
namespace li = leadscrew::integrate;

namespace {

// ---- The element (its own file in a real addition).

class RotorBrake final : public lm::Element {
 public:
  RotorBrake(int rotor, double damping, double heat_capacity, double fade_temperature,
             double fade_factor)
      : rotor_(rotor), c_(damping), capacity_(heat_capacity), fade_at_(fade_temperature),
        fade_(fade_factor) {}

  const char* name() const override { return "rotor_brake"; }
  void declare(lm::drive::Declaration& d) const override;

  double damping(const lm::ElementMode& mode) const { return mode.mode == 1 ? fade_ * c_ : c_; }

  void add_forces(const lm::ElementState& s, const lm::ElementMode& mode,
                  double* forces) const override {
    forces[rotor_] -= damping(mode) * s.v[rotor_];
  }
  bool forces_from_loads_alone() const override { return false; }
  void rates(const lm::ElementState& s, const lm::ElementMode& mode, double* own_rates,
             double* energy) const override {
    (void)energy;
    own_rates[0] = damping(mode) * s.v[rotor_] * s.v[rotor_] / capacity_;
  }
  void output(const lm::ElementState& s, const lm::ElementMode& mode,
              double* values) const override {
    (void)mode;
    values[0] = s.own[0];
    values[1] = capacity_ * s.own[0];
  }
  double energy_terms(const lm::ElementState& s) const override { return capacity_ * s.own[0]; }

  // The fade: theta reaching theta_fade from below, once (none without one).
  int root_count() const override { return std::isfinite(fade_at_) ? 1 : 0; }
  void roots(const lm::ElementState& s, const lm::ElementMode& mode, double* g) const override {
    if (root_count() > 0) g[0] = mode.mode == 1 ? 1.0 : fade_at_ - s.own[0];
  }
  void root_directions(int* directions) const override {
    if (root_count() > 0) directions[0] = -1;
  }
  lm::ElementEvent handle(const lm::ElementState& s, lm::ElementMode& mode,
                          double* own) const override {
    (void)s;
    (void)own;
    mode.mode = 1;
    return {"brake faded", true};
  }
  void start(const lm::ElementState& s, lm::ElementMode& mode) const override {
    mode.mode = s.own[0] >= fade_at_ ? 1 : 0;
  }

  // Moreau-Jean: the impulse -h c omega_theta, omega_theta = (1 - theta)
  // omega0 + theta omega+, beyond the start's -h c omega0: h c theta omega0
  // - h c theta omega+. Its heat h c omega_theta^2, the work of that impulse
  // at omega_theta; the fade from the step after theta passes theta_fade.
  void step_impulse(const lm::ElementStep& step, const lm::ElementMode& mode, double* constant,
                    double* slope) const override {
    const double c = damping(mode);
    constant[rotor_] += step.h * c * step.theta * step.start.v[rotor_];
    slope[rotor_] -= step.h * c * step.theta;
  }
  void step_end(const lm::ElementStep& step, const double* q_next, const double* v_next,
                lm::ElementMode& mode, double* own_next, double* energy) const override {
    (void)q_next;
    (void)energy;
    const double w =
        (1.0 - step.theta) * step.start.v[rotor_] + step.theta * v_next[rotor_];
    own_next[0] = step.start.own[0] + step.h * damping(mode) * w * w / capacity_;
    if (own_next[0] >= fade_at_) mode.mode = 1;
  }

 private:
  int rotor_;
  double c_, capacity_, fade_at_, fade_;
};

const lm::drive::ElementKind& rotor_brake_kind();

void RotorBrake::declare(lm::drive::Declaration& d) const {
  d.states.push_back("brake_temperature");
  d.channels = rotor_brake_kind().catalog;
}

void declare_brake(const lm::DriveModel& model, const leadscrew::friction::Law& law,
                   lm::drive::Declaration& d) {
  (void)law;
  lm::drive::declare_model_element(model, "rotor_brake", d);
}

const lm::drive::ElementKind& rotor_brake_kind() {
  static const lm::drive::ElementKind kind{
      "rotor_brake",
      {{"brake_temperature", "K", lm::drive::Role::none},
       {"brake_heat", "J", lm::drive::Role::loss}},
      &declare_brake};
  return kind;
}

void build_brake(const lm::Section& s, const lm::DriveParameters& p,
                 lm::elements::DriveElements& e) {
  (void)p;
  e.elements.push_back(std::make_shared<RotorBrake>(
      e.motor.rotor, s.number("damping"), s.number("heat_capacity"),
      s.number("fade_temperature"), s.number("fade_factor")));
}

lm::SectionType rotor_brake_section() {
  lm::SectionType type;
  type.name = "rotor_brake";
  type.doc = "(Absent: no brake.)";
  type.fields = {
      lm::number("damping", "N*m*s/rad", "its viscous coefficient c").required().above(0.0),
      lm::number("heat_capacity", "J/K", "its heat capacity C").required().above(0.0),
      lm::number("fade_temperature", "K", "the temperature rise at which it fades")
          .defaults(INFINITY)
          .above(0.0),
      lm::number("fade_factor", "", "what of c is left after the fade")
          .defaults(0.5)
          .range(0.0, 1.0, true, false),
  };
  type.flag = "rotor_brake";
  type.build = &build_brake;
  type.kind = &rotor_brake_kind;
  return type;
}

// ---- The checks.

int failures = 0;

void report(const char* label, int count, double worst, double bound) {
  if (worst <= bound) {
    std::printf("PASS %s (%d)\n", label, count);
  } else {
    std::printf("FAIL %s: worst %.3e > %.3e\n", label, worst, bound);
    ++failures;
  }
}

constexpr double kOmega0 = 100.0, kDamping = 2e-4, kCapacity = 1e-3;

lm::DriveParameters brake_drive(double fade_temperature) {
  lm::DriveParameters p;  // the rigid concept, the screw driven, no play
  p.mu = 0.0;
  p.rotor_speed = kOmega0;
  lm::ElementSection brake;
  brake.present = true;
  brake.numbers = {{"damping", kDamping}, {"heat_capacity", kCapacity}};
  if (std::isfinite(fade_temperature))
    brake.numbers.push_back({"fade_temperature", fade_temperature});
  p.sections["rotor_brake"] = brake;
  return p;
}

double at(const li::SimulationResult& r, const char* channel, std::size_t row) {
  return r.values[row * r.channel_count() + static_cast<std::size_t>(r.channel_index(channel))];
}

// The closed form's omega(t) for the drive's inertia J and fade at theta_f.
struct ClosedForm {
  double inertia, fade_temperature;
  double fade_time() const {
    const double wf2 = kOmega0 * kOmega0 - 2.0 * kCapacity * fade_temperature / inertia;
    if (!(wf2 > 0.0)) return INFINITY;
    return inertia / kDamping * std::log(kOmega0 / std::sqrt(wf2));
  }
  double omega(double t) const {
    const double tf = fade_time();
    if (t <= tf) return kOmega0 * std::exp(-kDamping * t / inertia);
    return kOmega0 * std::exp(-kDamping * tf / inertia) *
           std::exp(-0.5 * kDamping * (t - tf) / inertia);
  }
};

li::SimulationResult run(const lm::DriveModel& model, const char* integrator, double t_end,
                         double dt) {
  lm::DriveSimulationOptions options;
  options.integrator = integrator;
  options.integrator_options.rtol = 1e-11;
  options.integrator_options.atol = 1e-13;
  options.dt = dt;
  options.output.t_end = t_end;  // (rows at the steps and events)
  return lm::simulate(model, options);
}

// Every check passed, the account closes and the channels are the brake's.
void check_result(const char* label, const li::SimulationResult& r, double inertia) {
  double worst = 0.0;
  for (const li::InvariantCheck& c : r.checks)
    if (c.applies && !c.passed) {
      std::printf("  %s: check %s failed: %g > %g\n", label, c.name, c.value, c.bound);
      worst = 1.0;
    }
  report((std::string(label) + ": every result check passes").c_str(),
         static_cast<int>(r.checks.size()), worst, 0.0);
  // The brake's heat is the kinetic energy the rotor lost.
  double residual = 0.0;
  const double e0 = 0.5 * inertia * kOmega0 * kOmega0;
  for (std::size_t i = 0; i < r.point_count(); ++i)
    residual = std::max(residual, std::abs(at(r, "energy_residual", i)) / e0);
  report((std::string(label) + ": energy account closes with the brake's heat").c_str(),
         static_cast<int>(r.point_count()), residual, 1e-9);
}

}  // namespace

int main() {
  lm::register_element_section(rotor_brake_section());  // its one registry line

  const double t_end = 0.5;
  // The drive's inertia on the rotor's coordinate: its kinetic energy at
  // the start (the brake does not change it).
  const lm::DriveModel free_model(brake_drive(INFINITY));
  const li::SimulationResult first = run(free_model, "event_driven", 1e-3, 1e-4);
  const double inertia = 2.0 * at(first, "kinetic", 0) / (kOmega0 * kOmega0);
  // A fade at half the heat the run would take without it.
  const ClosedForm no_fade{inertia, INFINITY};
  const double heat_end = 0.5 * inertia * (kOmega0 * kOmega0 - std::pow(no_fade.omega(t_end), 2));
  const double theta_fade = 0.5 * heat_end / kCapacity;
  const ClosedForm form{inertia, theta_fade};

  const lm::DriveModel model(brake_drive(theta_fade));
  // Event-driven: the closed form at every row, the fade at its time.
  const li::SimulationResult exact = run(model, "event_driven", t_end, 1e-4);
  double worst = 0.0;
  for (std::size_t i = 0; i < exact.point_count(); ++i)
    worst = std::max(worst, std::abs(at(exact, "omega_drive", i) - form.omega(exact.time[i])) /
                                kOmega0);
  report("event-driven: omega follows the closed form", static_cast<int>(exact.point_count()),
         worst, 1e-8);
  double fade_error = INFINITY;
  int fades = 0;
  for (const li::Event& e : exact.events)
    if (e.kind.find("brake faded") != std::string::npos) {
      ++fades;
      fade_error = std::abs(e.time - form.fade_time()) / form.fade_time();
    }
  report("event-driven: one fade, at its closed-form time", fades, fades == 1 ? fade_error : 1.0,
         1e-8);
  double heat = 0.0;
  const std::size_t last = exact.point_count() - 1;
  heat = std::abs(at(exact, "brake_heat", last) -
                  0.5 * inertia * (kOmega0 * kOmega0 - std::pow(form.omega(t_end), 2))) /
         (0.5 * inertia * kOmega0 * kOmega0);
  report("event-driven: the brake's heat is the kinetic energy lost", 1, heat, 1e-8);
  check_result("event-driven", exact, inertia);

  // Moreau-Jean (theta = 1/2): second order before the fade (its error at
  // t_f / 2 against dt), first order across it (the fade at a step's end),
  // the account closed at every dt (the trapezoidal damper's work is exact).
  const double t_half = 0.5 * form.fade_time();
  std::vector<double> before, after;
  const double steps[] = {4e-4, 2e-4, 1e-4};
  for (double dt : steps) {
    const li::SimulationResult r = run(model, "moreau", t_end, dt);
    check_result(("moreau dt " + std::to_string(dt)).c_str(), r, inertia);
    const li::SimulationResult h = run(model, "moreau", t_half, dt);
    const std::size_t n = h.point_count() - 1, m = r.point_count() - 1;
    before.push_back(std::abs(at(h, "omega_drive", n) - form.omega(h.time[n])));
    after.push_back(std::abs(at(r, "omega_drive", m) - form.omega(r.time[m])));
  }
  const double order_before = std::log2(before[0] / before[1]);
  const double order_before2 = std::log2(before[1] / before[2]);
  report("moreau: second order before the fade", 2,
         std::max(std::abs(order_before - 2.0), std::abs(order_before2 - 2.0)), 0.1);
  const double order_after = std::log2(after[0] / after[2]) / 2.0;
  report("moreau: at least first order across the fade", 1, 0.9 - order_after, 0.0);

  std::printf(failures == 0 ? "OK\n" : "FAILED\n");
  return failures == 0 ? 0 : 1;
}
