// DriveHybrid (hybrid.hpp): an exact flank closing (Newton's impact law with
// Coulomb friction on the impulses, restitution that creates no energy),
// the play moved onto a flank, and the checks of a free flight.
#include "hybrid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::model::drive {

// The open thread's flank roots, g[2] = e - c/2 and g[3] = e + c/2, see a
// contact as the play crossing a flank from inside the clearance: a flight
// that starts with the play beyond a flank has its root on the crossed side
// from the start, and if the play moves on, no sign change ever shows. A
// touch below resolution (change_mode) restored the state as it was, a
// round-off beyond the flank, approaching it at a round-off rate; where the
// flight then turned back to the flank, the nut passed through it unseen
// (flexible_nut, 5 N mm, axial force -100 + 30 sin(2 pi 20 t) N from the
// upper flank: its flight of the first nanosecond, 1 ulp beyond it at
// 1.04 ns, turned back at 1.16 ns; the load was 7.87 m off after 0.4 s,
// with no event and no error). The play goes back onto the flank: the
// positions along M^-1 grad e (as flank_impact places an impact), and a
// rate into the flank (below resolution: see change_mode) is taken out as
// by a plastic frictionless touch.
void DriveHybrid::put_back_inside(double t, double* y) {
  set(t, y);
  const double half = 0.5 * p_.clearance;
  const int beyond = dynamics_.play() > half ? 1 : (dynamics_.play() < -half ? -1 : 0);
  if (beyond == 0) return;
  const PlayDirection direction = play_direction();
  const double kinetic_before = dynamics_.kinetic_energy();
  const double motor_work = beyond * dynamics_.play_rate() > 0.0 ? stop_play(t, direction) : 0.0;
  // The play sums several coordinates: where rounding leaves it beyond the
  // flank, aim inside by as much, then twice as much, and so on.
  double target = beyond * half, shift = 0.0;
  for (int attempt = 0; attempt < 16; ++attempt) {
    move_play_to(t, direction, target);
    const double excess = beyond * dynamics_.play() - half;
    if (!(excess > 0.0)) break;
    shift = std::max(2.0 * shift, excess);
    target = beyond * (half - shift);
  }
  impact_loss_ += kinetic_before + motor_work - dynamics_.kinetic_energy();
  layout_.compress(q_, v_, y);
  book_motor_impulse(y, motor_work);
  set(t, y);
}

// The rotor's reflected inertia takes none of the impulse (its speed is
// held): the stage passes the whole of it, at the held speed w the work
// W = P_b w, and the motor puts k W in (docs/physics/gear.md, "A prescribed
// rotor speed"; the motor's Coulomb friction, a finite torque, no impulse).
void DriveHybrid::book_motor_impulse(double* y, double motor_work) const {
  double stage_loss = 0.0;
  if (const elements::TrainFriction* train = model_.train_friction(); train && motor_work != 0.0) {
    stage_loss = train->stage_loss(motor_work);
    if (const int gear = layout_.find_state("gear_loss"); gear >= 0) y[gear] += stage_loss;
  }
  y[layout_.energy_offset() + kWorkDrive] += motor_work + stage_loss;
}

DriveHybrid::PlayDirection DriveHybrid::play_direction() const {
  const Eigen::VectorXd& w = model_.play_gradient();
  CoordinateVector along = model_.mass().cwiseInverse();
  // (A stuck rotor's contact holds it too: the touch moves the rest.)
  if (p_.speed_controlled || (rotor_train_ && rotor_mode_.slip == 0)) along[model_.rotor()] = 0.0;
  along = along.cwiseProduct(w);
  return {along, w.dot(along)};
}

// Moves the positions along `direction` until the play is `target` (to
// round-off), the state set.
void DriveHybrid::move_play_to(double t, const PlayDirection& direction, double target) {
  q_ += direction.along * ((target - dynamics_.play()) / direction.metric);
  dynamics_.set_state(t, q_, v_);
}

// Takes the play rate out of the velocities along `direction` (a plastic
// frictionless touch), the state set.
// Returns the work of a speed-controlled motor's impulse at its held
// speed: the rotor does not yield, so the thread's impulse on it, grad e_r
// times the play impulse, is the motor's (a flank met by a moving screw
// takes kinetic energy from the motor: booked, the account lost 1.5e-6 J).
double DriveHybrid::stop_play(double t, const PlayDirection& direction) {
  const double impulse = dynamics_.play_rate() / direction.metric;
  v_ -= direction.along * impulse;
  dynamics_.set_state(t, q_, v_);
  if (!p_.speed_controlled) return 0.0;
  const int r = model_.rotor();
  return model_.play_gradient()[r] * impulse * v_[r];
}

// How far beyond a flank a free flight starts (a closed flank's drift where
// it opens), the baseline of check_flight.
void DriveHybrid::note_flight_start(double t, const double* y) {
  flight_start_excess_ = 0.0;
  if (!model_.thread_pair().exact_play() || mode_.contact != ThreadContact::open) return;
  set(t, y);
  flight_start_excess_ = std::max(0.0, std::abs(dynamics_.play()) - 0.5 * p_.clearance);
}

// A free flight (the state set) whose play went beyond a flank by more than
// kFlankTolerance of the clearance passed through it unseen: an error, never
// an answer.
void DriveHybrid::check_flight(double t) const {
  const double beyond = std::abs(dynamics_.play()) - 0.5 * p_.clearance - flight_start_excess_;
  const double tolerance =
      std::max(kFlankTolerance * p_.clearance, 10.0 * integrator_options_.atol);
  if (!(beyond <= tolerance))
    throw SimulationError(
        t,
        "the nut passed through the " + std::string(dynamics_.play() > 0.0 ? "upper" : "lower") +
            " flank of the backlash unseen: in free flight the play is " +
            format_value(beyond + flight_start_excess_) + " m beyond it (tolerance " +
            format_value(tolerance) + " m)",
        "a flank contact was missed; tighten rtol and atol, and please report the scene");
}

// The play's acceleration e'' in free flight (the thread open) at the state
// set: how far a flight would rise (flank_impact) or a slow approach go
// beyond a flank (change_mode's touch below resolution).
double DriveHybrid::free_flight_play_acceleration() {
  const Mode saved = mode_;
  mode_.contact = ThreadContact::open;
  mode_.friction = FrictionMode::none;
  const ModeSolution flight = solve_current();
  mode_ = saved;
  return model_.play_gradient().dot(flight.acceleration);
}

// An exact flank closes: Newton's impact law with Coulomb friction on the
// impulses. Returns true if the impact ends with zero slip.
bool DriveHybrid::flank_impact(double t, double* y, int flank) {
  const PlayDirection direction = play_direction();
  // Place the play exactly on the flank (the root is located to round-off).
  move_play_to(t, direction, flank > 0 ? -0.5 * p_.clearance : 0.5 * p_.clearance);
  const double kinetic_before = dynamics_.kinetic_energy();
  auto close_flank = [&]() {
    // Plastic, grazing or too weak to fly: the flank stays closed with zero
    // normal velocity (the closed flank opens again at once if it cannot push).
    // The normal velocity taken out is the impact's loss too (unbooked, a
    // weak bounce's energy went missing from the account: 5e-4 of the work
    // of a rattling nut with restitution 0.5).
    const double kinetic_open = dynamics_.kinetic_energy();
    // (After an impact through the rotor's contact its mode may hold it.)
    const double closing_work = stop_play(t, rotor_train_ ? play_direction() : direction);
    book_motor_impulse(y, closing_work);
    impact_loss_ += kinetic_open + closing_work - dynamics_.kinetic_energy();
    mode_.contact = ThreadContact::closed;
    mode_.flank = flank;
  };
  if (flank * dynamics_.play_rate() >= 0.0) {
    // Grazing: the play touches the flank without approaching it; no impulse.
    close_flank();
    return dynamics_.slip_velocity() == 0.0;
  }
  DriveDynamics::Impulses impulses;
  // The impact at restitution e: v_ from before it, and the energy it
  // dissipates (kinetic energy lost plus the speed-controlled motor's
  // impulsive work at its held speed).
  const CoordinateVector v_before = v_;
  double motor_work = 0.0;
  auto collide = [&](double e) {
    if (!flank_impulses(flank, e, v_before, impulses)) jam("no consistent frictional impact");
    motor_work = p_.speed_controlled ? impulses.rotor * v_[model_.rotor()] : 0.0;
    dynamics_.set_state(t, q_, v_);
    return kinetic_before + motor_work - dynamics_.kinetic_energy();
  };
  double dissipated = collide(p_.restitution);
  const double round_off = 64.0 * std::numeric_limits<double>::epsilon() *
                           (kinetic_before + std::abs(motor_work));
  if (dissipated < -round_off) {
    // Newton's restitution with Coulomb friction can create energy (Kane
    // and Levinson's paradox: a rigid nut's first impact at e = 0.48 gained
    // 0.0155 J): the impact takes the largest restitution up to e that
    // creates none, as an energetic coefficient of restitution would
    // (Stronge). A plastic frictional impact dissipates (its impulses
    // solve the LCP of maximal dissipation), so bisection on [0, e] finds it.
    double low = 0.0, high = p_.restitution;
    for (int iteration = 0; iteration < 60; ++iteration) {
      const double middle = 0.5 * (low + high);
      (collide(middle) >= -round_off ? low : high) = middle;
    }
    dissipated = collide(low);
  }
  // The motor's work enters the drive's work as well as the impact's loss
  // (booked in the loss alone, 4 % of the work went missing from the account).
  book_motor_impulse(y, motor_work);
  // (The stage's share of it through the rotor's contact: gear_loss.)
  const double stage_share = stage_impact_loss(impulses, dissipated);
  if (stage_share != 0.0) y[layout_.find_state("gear_loss")] += stage_share;
  impact_loss_ += dissipated - stage_share;
  const double normal_after = dynamics_.play_rate();
  // Height of the flight the bounce would start: v^2 / (2 |e''|) with the
  // play's acceleration in free flight; see kPlasticHeight.
  const double play_acceleration = free_flight_play_acceleration();
  const bool pushed_back = flank * play_acceleration < 0.0;
  const double height = pushed_back ? normal_after * normal_after / (2.0 * std::abs(play_acceleration))
                                    : std::numeric_limits<double>::infinity();
  if (std::abs(normal_after) <= bounce_threshold_ || height <= kPlasticHeight * p_.clearance) {
    close_flank();
    // Zero slip only where the impulse LCP chose stick (its post-impact
    // slip velocity carries round-off, which decide_friction projects away).
    return impulses.sticks || dynamics_.slip_velocity() == 0.0;
  }
  mode_.contact = ThreadContact::open;
  mode_.friction = FrictionMode::none;
  return false;
}

}  // namespace leadscrew::model::drive
