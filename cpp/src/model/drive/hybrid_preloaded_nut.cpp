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

// Whether the halves take a law whose slip coefficient is not one number
// (a smooth law, Stribeck's curve, the ODE methods' regularization): half
// B's normal force follows the law's coefficient kappa', which the net
// forces alone do not give, so the element reports |N_A| + |N_B| as a
// channel (as with lift-off).
bool law_channels(const friction::Law& law) {
  return !(law.resolution() == friction::Resolution::set_valued && law.viscous() == 0.0 &&
           law.slip_mu(0.0) == law.mu() && law.slip_mu(1.0) == law.mu());
}

void declare(const DriveModel& model, const friction::Law& law, Declaration& d) {
  const elements::PreloadedNut* nut = model.preloaded_nut();
  if (!nut) return;
  if (nut->lift_off || law_channels(law)) {
    // Its channel |N_A| + |N_B| is the normal force the friction multiplies
    // (half A's force is the penalty flank's, the spring's changes with the
    // play; half B's follows the law's coefficient); with lift-off its
    // spring's rate bounds the elastic energy's gradient.
    d.channels = preloaded_nut_kind().catalog;
    if (nut->lift_off) d.stiffness = nut->stiffness;
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

class NutChannelsElement final : public DriveHybrid::Element {
 public:
  NutChannelsElement(DriveHybrid& hybrid, const elements::PreloadedNut& nut)
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
  // the law's coefficient multiplies; in stick half B at the edge the stick
  // force heads for, at mu_static').
  void output(double t, const double* y, const ContactForces& forces,
              ChannelState& state) const override {
    (void)t;
    (void)y;
    // (No channels declared: exact Coulomb, no lift-off. Its declaration's
    // slot then is the next element's first channel, the train's
    // motor_friction_loss, which the nut's preload overwrote beside a
    // rotor's friction contact.)
    if (first_channel() < 0 || !(nut_.lift_off || law_channels(dynamics().law()))) return;
    double* values = state.values.data() + first_channel();
    if (!nut_.lift_off) {
      const double normal_a = forces.normal - forces.preload_normal;
      values[kPreloadForce] = nut_.preload;
      values[kNormalForceA] = normal_a;
      values[kFlankNormal] = mode().friction == FrictionMode::stick
                                 ? nut_.sticking().flank_normal(forces.normal, forces.friction)
                                 : std::abs(normal_a) + std::abs(forces.preload_normal);
      return;
    }
    const double preload = dynamics().preload_spring_force();
    const double normal_a = dynamics().penalty_normal_force();
    values[kPreloadForce] = preload;
    values[kNormalForceA] = normal_a;
    values[kFlankNormal] =
        mode().friction == FrictionMode::stick
            ? nut_.sticking().split_flank_normal(normal_a, preload, forces.friction)
        : mode().friction == FrictionMode::slip && !at_kappa()
            ? std::abs(normal_a) + std::abs(nut_.normal(mode().slip_sign, preload))
            : std::abs(normal_a) + std::abs(forces.preload_normal);
  }

 private:
  // Whether half B takes the law's coefficient in the current mode
  // (DriveDynamics::preload_at_kappa).
  bool at_kappa() const {
    ModeSpec spec;
    spec.friction = mode().friction;
    return dynamics().preload_at_kappa(spec);
  }

  const elements::PreloadedNut& nut_;
};

}  // namespace

const elements::PreloadedNut* DriveHybrid::closing_nut() const {
  const elements::PreloadedNut* nut = model_.preloaded_nut();
  return nut && nut->closes_exact_play && mode_.contact == ThreadContact::bilateral ? nut
                                                                                   : nullptr;
}

double DriveHybrid::half_a_bearing(double normal_force, double preload_normal) const {
  const elements::PreloadedNut& nut = *model_.preloaded_nut();
  // Half B at the law's coefficient (a smooth law, Stribeck's slip): the
  // mode's own N_B, its preload_normal.
  if (dynamics_.preload_at_kappa(spec(1))) return -nut.side * (normal_force - preload_normal);
  const int s = mode_.friction == FrictionMode::slip ? mode_.slip_sign : 0;
  return nut.half_a_bearing(s, normal_force);
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

// (Its channels are declared with lift-off or a law of law_channels: the
// element writes them where it has a slot.)
std::unique_ptr<DriveHybrid::Element> make_preloaded_nut_element(DriveHybrid& hybrid,
                                                                 const DriveModel& model) {
  const elements::PreloadedNut* nut = model.preloaded_nut();
  if (!nut) return nullptr;
  return std::make_unique<NutChannelsElement>(hybrid, *nut);
}

}  // namespace leadscrew::model::drive
