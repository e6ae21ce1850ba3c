// A preloaded split nut (elements/preloaded_nut.hpp;
// docs/physics/preloaded_nut.md) in the driver: its declaration (with
// lift-off its channels, the spring's stiffness for the checks' force
// bound; without, the normal force the friction coefficient multiplies) and,
// with lift-off, an element of the event-driven driver (driver_element.hpp)
// without roots: its channels' values. Its forces enter through
// DriveDynamics (solve, the penalty flank of half A). With exact play closed
// by the preload (PreloadedNut::closes_exact_play) the driver's guard of
// half A's flank: its root g1 and the SimulationError where it lifts off.
#include <algorithm>
#include <cmath>

#include "driver_element.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::model::drive {

const ElementKind& preloaded_nut_kind();

namespace {

// Its channels (the declaration's, in this order).
enum Channel { kPreloadForce, kNormalForceA, kFlankNormal };

void declare(const DriveModel& model, const friction::Law& law, Declaration& d) {
  (void)law;
  const elements::PreloadedNut* nut = model.preloaded_nut();
  if (!nut) return;
  if (nut->lift_off) {
    // Its channel |N_A| + |N_B| is the normal force the friction multiplies
    // (half A's force is the penalty flank's, the spring's changes with the
    // play); its spring's rate bounds the elastic energy's gradient.
    d.channels = preloaded_nut_kind().catalog;
    d.stiffness = nut->stiffness;
  } else {
    // With mu_static above mu the cone's bound in stick is the element's at
    // mu_static' (half B's edge state at mu_static'): where the row does
    // not slip at mu' (|T| off mu' times the flank normal beyond round-off),
    // the larger of the two normals, so that mu_static' times it bounds the
    // stick force. (A slipping row's is mu''s: the law's check.)
    d.flank_normal = [nut = *nut](double normal, double friction) {
      const double slipping = nut.flank_normal(normal, friction);
      if (!nut.two_coefficients() ||
          std::abs(std::abs(friction) - nut.mu * slipping) <=
              1e-9 * (std::abs(friction) + nut.mu * slipping))
        return slipping;
      return std::max(slipping, nut.sticking().flank_normal(normal, friction));
    };
  }
}

class LiftOffNutElement final : public DriveHybrid::Element {
 public:
  LiftOffNutElement(DriveHybrid& hybrid, const elements::PreloadedNut& nut)
      : Element(hybrid), nut_(nut) {}

  int root_count() const override { return 0; }
  void roots(double t, double* g) const override {
    (void)t;
    (void)g;
  }
  void root_directions(int* directions) const override { (void)directions; }
  Event handle(double t, double* y, const int* root_info) override {
    (void)t;
    (void)y;
    (void)root_info;
    return {};
  }

  // Its spring, half A's normal force and both halves' (the normal force
  // mu' multiplies, half B at its slip's or the stick force's edge).
  void output(double t, const double* y, const ContactForces& forces,
              ChannelState& state) const override {
    (void)t;
    (void)y;
    double* values = state.values.data() + first_channel();
    const double preload = dynamics().preload_spring_force();
    const double normal_a = dynamics().penalty_normal_force();
    values[kPreloadForce] = preload;
    values[kNormalForceA] = normal_a;
    values[kFlankNormal] =
        mode().friction == FrictionMode::slip
            ? std::abs(normal_a) + std::abs(nut_.normal(mode().slip_sign, preload))
            : nut_.sticking().split_flank_normal(normal_a, preload, forces.friction);
  }

 private:
  const elements::PreloadedNut& nut_;
};

}  // namespace

const elements::PreloadedNut* DriveHybrid::closing_nut() const {
  const elements::PreloadedNut* nut = model_.preloaded_nut();
  return nut && nut->closes_exact_play && mode_.contact == ThreadContact::bilateral ? nut
                                                                                   : nullptr;
}

double DriveHybrid::half_a_bearing(double normal_force) const {
  const int s = mode_.friction == FrictionMode::slip ? mode_.slip_sign : 0;
  return model_.preloaded_nut()->half_a_bearing(s, normal_force);
}

void DriveHybrid::half_a_lifts_off(double t) const {
  throw SimulationError(
      t,
      "half A of the preloaded nut lifts off its flank into the exact play (its normal force on "
      "the flank reached zero: the load on half B's side exceeds what the preload of " +
          format_value(model_.preloaded_nut()->preload) +
          " N holds), which is not modelled with backlash.contact = \"exact\"",
      "use backlash.contact = \"bistop\" or \"cubic\" with nut.preload_stiffness > 0 to "
      "simulate the lift-off, or a larger nut.preload");
}

const ElementKind& preloaded_nut_kind() {
  static const ElementKind kind{"preloaded_nut",
                                {{"preload_force", "N", Role::none},
                                 {"normal_force_a", "N", Role::none},
                                 {"flank_normal", "N", Role::flank_normal}},
                                &declare};
  return kind;
}

std::unique_ptr<DriveHybrid::Element> make_preloaded_nut_element(DriveHybrid& hybrid,
                                                                 const DriveModel& model) {
  const elements::PreloadedNut* nut = model.preloaded_nut();
  if (!nut || !nut->lift_off) return nullptr;
  return std::make_unique<LiftOffNutElement>(hybrid, *nut);
}

}  // namespace leadscrew::model::drive
