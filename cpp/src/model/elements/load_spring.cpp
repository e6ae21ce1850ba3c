// Element: a spring on the load (scene section `load_spring`;
// docs/physics/load_spring.md): a balance, gas or return spring of a window
// lifter or a hatch, between the load and the ground, with its preload P
// (at the load's start, positive along +x), its stiffness k and a damper c:
//   the force on the load  F = -(P + k u_load) - c u_load'
// (u_load from the load's start). Its elastic energy (P + k u)^2 / (2 k),
// the energy of the spring at its deflection P / k + u, joins the account's
// `elastic` (the residual takes its change); its damper's loss c u'^2 the
// damping loss. Its channel load_spring_force [N] is F.
//
// This file is the whole element: its section's fields and rules, its force
// (a SectionForce, elements/section_force.hpp) and its channel; one line in
// the sections' registry (section_registry.cpp) adds it.
#include <memory>

#include "../drive/declaration.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/element_section.hpp"

namespace leadscrew::model {

namespace {

class LoadSpring final : public elements::SectionForceLaw {
 public:
  LoadSpring(int load, double stiffness, double preload, double damping)
      : load_(load), k_(stiffness), preload_(preload), c_(damping) {}

  // F at the load's position u and speed du [N].
  double force(double u, double du) const { return -(preload_ + k_ * u) - c_ * du; }

  void add_forces(const double* q, const double* v, double* forces, double& elastic,
                  double& damping_power) const override {
    const double spring = preload_ + k_ * q[load_];
    forces[load_] -= spring + c_ * v[load_];
    elastic += 0.5 * spring * spring / k_;
    damping_power += c_ * v[load_] * v[load_];
  }
  double damping_power(const double* v) const override { return c_ * v[load_] * v[load_]; }
  void add_stiffness(double* K, int n) const override { K[load_ + load_ * n] += k_; }
  void add_damping(double* C, int n) const override { C[load_ + load_ * n] += c_; }
  double stiffness() const override { return k_; }
  int load() const { return load_; }

 private:
  int load_;
  double k_, preload_, c_;
};

// The train's friction stages solve the rigid drive with the axial load and
// the end stops' force alone (TrainSolver): no spring on the load there.
void check(const Section& s, const DriveParameters& p, const MessageStyle& m) {
  (void)s;
  const bool stage = p.gear == GearType::lossy || p.gear == GearType::worm;
  if (stage || p.motor_friction_torque > 0.0)
    throw InvalidArgument(
        "load_spring is invalid with " +
        (stage ? "gear.type = " + m.text(gear_type_name(p.gear))
               : "motor.friction_torque = " + m.number(p.motor_friction_torque)) +
        ": the train's friction stages (a lossy or worm gear, the motor's friction torque) "
        "take no spring on the load; use gear.type = " + m.text("ideal") +
        " and motor.friction_torque = 0, or leave load_spring out");
}

void build(const Section& s, const DriveParameters& p, elements::DriveElements& e) {
  (void)p;
  elements::SectionForce force;
  force.law = std::make_shared<LoadSpring>(e.load.coordinate, s.number("stiffness"),
                                           s.number("preload"), s.number("damping"));
  e.forces.of<elements::SectionForce>().push_back(force);
}

const drive::ElementKind& load_spring_kind();

void declare(const DriveModel& model, const friction::Law& law, drive::Declaration& d) {
  (void)law;
  for (const elements::SectionForce& force : model.elements().forces.of<elements::SectionForce>())
    if (const auto* spring = dynamic_cast<const LoadSpring*>(force.law.get())) {
      d.channels = load_spring_kind().catalog;
      d.add_from_coordinates = [spring](const CoordinateVector& q, const CoordinateVector& v,
                                        double* values) {
        values[0] += spring->force(q[spring->load()], v[spring->load()]);
      };
    }
}

const drive::ElementKind& load_spring_kind() {
  static const drive::ElementKind kind{
      "load_spring", {{"load_spring_force", "N", drive::Role::none}}, &declare};
  return kind;
}

}  // namespace

SectionType load_spring_section() {
  SectionType type;
  type.name = "load_spring";
  type.doc = "(Absent: no spring on the load.)";
  type.fields = {
      number("stiffness", "N/m", "the spring's stiffness k: its force changes by k per metre "
                                 "of the load's travel")
          .required(0.0)
          .above(0.0)
          .named("load_spring_stiffness"),
      number("preload", "N", "the spring's preload P at the load's start (u_load = 0), "
                             "positive along +x: the force on the load is -(P + k u_load) - "
                             "c u_load', -P at the start (P > 0 balances an axial force of "
                             "+P, a hatch's weight along +x; any sign)")
          .defaults(0.0)
          .named("load_spring_preload"),
      number("damping", "N*s/m", "the damper c in parallel with the spring")
          .defaults(0.0)
          .at_least(0.0)
          .named("load_spring_damping"),
  };
  type.flag = "load_spring";
  type.check = &check;
  type.build = &build;
  type.kind = &load_spring_kind;
  return type;
}

}  // namespace leadscrew::model
