// DriveMoreau (moreau.hpp): the preloaded split nut on Moreau-Jean's step
// (elements/preloaded_nut.hpp; docs/physics/preloaded_nut.md, "Moreau-Jean"),
// on the thread without play: the rigid concept, the flexible concepts
// without play or with exact play closed by the preload. (Lift-off, half B
// on its own flank beside the penalty flank, runs on the event-driven
// scheme only: check_simulation_options.)
//
// The step's thread row W_N v+ = 0 carries the net normal impulse P_N, the
// tangential column W_T the net friction impulse P_T (half A's and half
// B's: the spring between the halves is internal, and on the thread
// without play both halves move with the thread). Over the step half B's
// flank impulse is the force law's times h: in slip s its normal impulse is
// h N_B^s = h side P / (cos a - s side mu' sin a), linear in P, so the
// step's impulse cone is the element's force cone at the preload h P,
//   -s P_T <= mu' (|P_N - h N_B^s| + h |N_B^s|),
// and with the step's maps gamma+ = c + d P_T, P_N = beta + alpha P_T the
// element's decision by the LCP's three cases (PreloadedNut::decide) is the
// step's: stick where P_T = -c / d lies between the edges, slip s at the
// edge where gamma+ has the sign s. With mu_static above mu the stick test
// at mu_static' first (the two-step test of the plain thread); a prescribed
// slip (a speed-controlled rotor, or the train's stuck rotor holding every
// velocity) takes PreloadedNut::prescribed_slip. The loss -P_T gamma+ is
// booked as the plain thread's (book_step): the halves' friction works on
// the common slip.
#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "moreau.hpp"

namespace leadscrew::model::drive {

DriveMoreau::Impulses DriveMoreau::solve_preloaded_thread(
    const elements::PreloadedNut& nut, double t, double h, double c, double d, double alpha,
    double beta, bool prescribed, bool slip_zero, double motor0, double motor1,
    double normal_target, double rotor_target, const ViscousStep& viscous, bool& stick) {
  // The element at the step's impulses: half B's impulse over the step is
  // its force's times h (N_B^s and T_B^s are linear in P).
  elements::PreloadedNut step_nut = nut;
  step_nut.preload = h * nut.preload;
  friction::FlankLcpResult r;
  if (prescribed) {
    r = step_nut.prescribed_slip(c, slip_zero, alpha, beta, motor0, motor1);
  } else {
    if (nut.two_coefficients()) r = step_nut.sticking().decide(c, d, alpha, beta);
    // (Stuck at mu_static' or, where it slips there, the slip at mu': at the
    // narrower cone gamma+ at the edge has the same sign.)
    if (!(r.consistent && r.slip_acceleration == 0.0)) r = step_nut.decide(c, d, alpha, beta);
  }
  ++lcp_solves_;
  if (!r.consistent)
    throw JammingError(t, "dynamic jamming: the preloaded nut's friction cone has no unique "
                          "edge in the Moreau-Jean step (the Painleve regime, mu' |alpha| = " +
                              format_value(nut.mu * std::abs(alpha)) + "); " +
                              dynamics_.jamming_report(),
                       "reduce the friction or change the inertia ratio");
  // The viscous impulse on top of the cone's (Stribeck's viscous term; zero
  // where stuck), as the plain thread's.
  double friction = r.friction_force;
  if (viscous.step > 0.0) friction = (friction - viscous.step * viscous.c) * viscous.scale;
  Impulses impulses = solve(true, normal_target, rotor_target, friction);
  impulses.friction = friction;
  stick = r.slip_acceleration == 0.0;
  // Half B's normal impulse in slip (the channels' |N_A| + |N_B|; in stick
  // the channels take half B at the edge the friction heads for).
  if (!stick) impulses.preload_normal = step_nut.normal(r.slip_acceleration > 0.0 ? 1 : -1);
  return impulses;
}

// Exact play closed by the preload (PreloadedNut::closes_exact_play): half
// A's normal force on its own flank over the step, the event-driven
// scheme's guard (hybrid_preloaded_nut.cpp), checked at the step's end
// (half B at N_B^s in slip s, at its spring's side P / cos(a) in stick):
// where it is negative half A has lifted off into the play within the
// step, which the model without play does not resolve.
void DriveMoreau::check_half_a_bearing(const StepState& s) const {
  const elements::PreloadedNut* nut = model_.preloaded_nut();
  if (!nut || !nut->closes_exact_play) return;
  const double slip = model_.tangent_direction().dot(v_);
  const int sign = s.stick || slip == 0.0 ? 0 : slip > 0.0 ? 1 : -1;
  // (A smooth law: half B at the step's own N_B, moreau_smooth_friction.cpp.)
  const double bearing =
      model_.law().resolution() != friction::Resolution::set_valued
          ? -nut->side * (s.impulses.normal - s.impulses.preload_normal) / s.h
          : nut->half_a_bearing(sign, s.impulses.normal / s.h);
  if (bearing >= 0.0) return;
  throw SimulationError(
      s.t + s.h,
      "half A of the preloaded nut lifts off its flank into the exact play within the "
      "Moreau-Jean step ending here (its normal force on the flank " +
          format_value(bearing) + " N < 0: the load on half B's side exceeds what the preload "
          "of " + format_value(nut->preload) +
          " N holds), which is not modelled with backlash.contact = \"exact\"",
      "use a larger nut.preload; the lift-off runs with backlash.contact = \"bistop\" or "
      "\"cubic\" and nut.preload_stiffness > 0 on integrator = \"event_driven\" (without "
      "the train's friction stages)");
}

}  // namespace leadscrew::model::drive
