// The thesis's drive concepts (chapter 4) as elements: the one place where
// the concept, the driven part and the backlash become bodies, springs, the
// thread pair, the motor and the load.
#include <algorithm>
#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/model/drive_geometry.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/element_section.hpp"
#include "leadscrew/model/elements/drive_elements.hpp"

namespace leadscrew::model::elements {

namespace {

// The preloaded split nut of p (nut.preload > 0) on the thread without play
// (the rigid concept's, the flexible concepts' with or without exact play
// closed) or on penalty play (lift-off); elsewhere refused with what is
// supported.
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

void require_plausible_dc_motor(const DriveParameters& p, const DcMotor& m) {
  const double mechanical =
      p.rotor_inertia * m.resistance / (m.torque_constant * m.back_emf_constant);
  if (!(mechanical >= kShortestMechanicalTimeConstant))
    throw InvalidArgument(
        "motor.torque_constant = " + format_value(p.motor_torque_constant) +
        (p.motor_back_emf_constant < 0.0
             ? std::string()
             : ", motor.back_emf_constant = " + format_value(p.motor_back_emf_constant)) +
        ", motor.resistance = " + format_value(m.resistance) + " and rotor.inertia = " +
        format_value(p.rotor_inertia) +
        " are invalid together: with them the DC motor's mechanical time constant "
        "rotor.inertia * motor.resistance / (motor.torque_constant * "
        "motor.back_emf_constant) comes to " +
        format_value(mechanical) + " s: must be at least " +
        format_value(kShortestMechanicalTimeConstant) +
        " s (the fastest motors built have about 1e-3 s: check the units)");
  if (m.inductance > 0.0 && !(m.inductance / m.resistance >= kShortestElectricalTimeConstant))
    throw InvalidArgument("motor.inductance = " + format_value(m.inductance) +
                          " and motor.resistance = " + format_value(m.resistance) +
                          " are invalid together: with them the DC motor's electrical time "
                          "constant "
                          "motor.inductance / motor.resistance comes to " +
                          format_value(m.inductance / m.resistance) + " s: must be at least " +
                          format_value(kShortestElectricalTimeConstant) +
                          " s (the fastest motors built have about 1e-6 s), or 0 (the "
                          "quasi-static limit, exact: no current dynamics)");
}

// The train's friction stages (train_friction.hpp): the motor's Coulomb
// friction and a lossy or worm stage, checked here alone (one rule, one
// place; the scene only converts). They run on the rigid drive without play
// alone, where every contact slips with one speed.
void build_train_friction(const DriveParameters& p, DriveElements& e) {
  require_finite("motor.friction_torque", p.motor_friction_torque);
  require_nonnegative("motor.friction_torque", p.motor_friction_torque);
  const bool stage = p.gear == GearType::lossy || p.gear == GearType::worm;
  if (p.motor_friction_torque == 0.0 && !stage) return;
  TrainFriction f;
  f.ratio = e.motor.gear.ratio;
  f.rotor_inertia = e.motor.gear.reflected_inertia(p.rotor_inertia);
  f.motor_friction = p.motor_friction_torque;
  if (p.gear == GearType::lossy) {
    f.stage = true;
    require_finite("gear.efficiency", p.gear_efficiency);
    if (!(p.gear_efficiency > 0.0 && p.gear_efficiency <= 1.0))
      throw InvalidArgument("gear.efficiency = " + format_value(p.gear_efficiency) +
                            " is invalid: must be in (0, 1]");
    require_finite("gear.efficiency_backdrive", p.gear_efficiency_backdrive);
    if (!(p.gear_efficiency_backdrive <= 1.0))
      throw InvalidArgument("gear.efficiency_backdrive = " +
                            format_value(p.gear_efficiency_backdrive) +
                            " is invalid: must be at most 1 (<= 0: self-locking)");
    f.efficiency = f.efficiency_static = p.gear_efficiency;
    f.efficiency_backdrive = f.efficiency_backdrive_static = p.gear_efficiency_backdrive;
  } else if (p.gear == GearType::worm) {
    f.stage = f.worm = true;
    constexpr double kRightAngle = 1.5707963267948966;
    require_finite("gear.lead_angle", p.gear_lead_angle);
    if (!(p.gear_lead_angle > 0.0 && p.gear_lead_angle < kRightAngle))
      throw InvalidArgument("gear.lead_angle = " + format_value(p.gear_lead_angle) +
                            " is invalid: must be in (0, pi/2) rad");
    require_finite("gear.flank_angle", p.gear_flank_angle);
    if (!(p.gear_flank_angle >= 0.0 && p.gear_flank_angle < 2.0 * kRightAngle))
      throw InvalidArgument("gear.flank_angle = " + format_value(p.gear_flank_angle) +
                            " is invalid: must be in [0, pi) rad (the included angle)");
    require_finite("gear.mu", p.gear_mu);
    require_nonnegative("gear.mu", p.gear_mu);
    const double mu_static = p.gear_mu_static < 0.0 ? p.gear_mu : p.gear_mu_static;
    require_finite("gear.mu_static", mu_static);
    if (!(mu_static >= p.gear_mu))
      throw InvalidArgument("gear.mu_static = " + format_value(mu_static) +
                            " is invalid: must be at least gear.mu = " + format_value(p.gear_mu));
    const double factor = 1.0 / std::cos(0.5 * p.gear_flank_angle);
    // Driven by the worm at all: gamma + rho'_static < pi/2.
    if (!(p.gear_lead_angle + std::atan(mu_static * factor) < kRightAngle))
      throw InvalidArgument(
          "gear.lead_angle = " + format_value(p.gear_lead_angle) + " rad is invalid with " +
          (p.gear_mu_static < 0.0 ? "gear.mu = " : "gear.mu_static = ") +
          format_value(mu_static) +
          ": the worm cannot be driven (lead angle + atan(mu_static / cos(flank_angle / 2)) "
          "must stay below pi/2 rad; gear.mu_static defaults to gear.mu)");
    f.efficiency = TrainFriction::worm_efficiency(p.gear_lead_angle, p.gear_mu * factor);
    f.efficiency_backdrive =
        TrainFriction::worm_efficiency_backdrive(p.gear_lead_angle, p.gear_mu * factor);
    f.efficiency_static = TrainFriction::worm_efficiency(p.gear_lead_angle, mu_static * factor);
    f.efficiency_backdrive_static =
        TrainFriction::worm_efficiency_backdrive(p.gear_lead_angle, mu_static * factor);
  }
  const std::string what = stage ? "gear.type = \"" + gear_type_name(p.gear) + "\""
                                 : "motor.friction_torque = " +
                                       format_value(p.motor_friction_torque) + " N m";
  // What nothing runs. (The rigid concept without play and plain Coulomb
  // friction on the thread runs on both schemes; play, the flexible
  // concepts and a static coefficient on the thread on Moreau-Jean only:
  // train_event_driven_obstacle, check_simulation_options.)
  const std::string needs = " is invalid: needs a torque (loads.drive_torque) or a DC motor "
                            "and exact Coulomb friction on the thread (the event-driven scheme "
                            "on the rigid concept without play, Moreau-Jean on every concept "
                            "and play)";
  if (p.speed_controlled)
    throw InvalidArgument(what + needs + "; loads.drive_speed prescribes the speed (a motor's "
                          "friction is absorbed by it)");
  // (Penalty flanks, bistop and cubic, run on Moreau-Jean: a play, the
  // event-driven scheme's obstacle.)
  if (e.thread->law().resolution() != friction::Resolution::set_valued)
    throw InvalidArgument(what + needs + "; friction.law = \"" + p.friction + "\"");
  const double alpha = p.thread.lead_angle();
  if (!(std::cos(alpha) - e.thread->effective_mu() * std::sin(alpha) > 0.0))
    throw InvalidArgument(what + " is invalid with friction.mu = " + format_value(p.mu) +
                          ": a torque cannot drive the thread (mu' >= cot(lead angle)), so its "
                          "holding torques at rest form no interval");
  // (A preloaded nut: build_preloaded_nut refuses the stages first.)
  // Penalty end stops are one more axial force on the train (TrainSolver,
  // and Moreau-Jean's); exact ones where the load is a body of its own
  // (elements/end_stops.cpp), on Moreau-Jean.
  if (p.initial_state == InitialState::equilibrium)
    throw InvalidArgument(what + needs + "; initial.state = \"equilibrium\" (use \"relaxed\")");
  f.event_driven_obstacle = train_event_driven_obstacle(p, e.thread->law());
  e.train_friction = f;
}

// The largest axial strain of the nut body that a preload may cause: 10 %,
// beyond the elastic range of every nut material (steel and bronze yield
// near 0.1 to 0.2 % strain, POM and PA near 2 to 4 %) and of the model's
// linear springs (eq. 4.17). The preload is carried by the nut halves'
// cross-section: P / k_nut is their compression, k_nut = E A / l the
// nut's axial stiffness. (docs/physics/preloaded_nut.md, "Valid preloads".)
constexpr double kLargestPreloadStrain = 0.1;

// A preload the nut could not carry, refused up front (a preload of 1e12 N
// on penalty flanks ground to CV_TOO_MUCH_WORK at t = 0.02 s without naming
// it): the nut body's strain P / (k_nut l_nut) at most kLargestPreloadStrain
// on every concept, and with lift-off half A's flank penetration at the
// preload, d_0 = f^-1(P), below the thread's depth (half the pitch for
// trapezoidal and metric threads: a deeper penetration passes the flanks
// through each other).
void require_carried_preload(const DriveParameters& p, const DriveElements& e, bool lift_off) {
  const double strain_limit = kLargestPreloadStrain * p.nut_axial_stiffness * p.nut_length;
  if (p.nut_axial_stiffness > 0.0 && !(p.nut_preload <= strain_limit))
    throw InvalidArgument(
        "nut.preload = " + format_value(p.nut_preload) + " N is invalid: must be <= " +
        format_value(strain_limit) + " N, what the nut carries (10 % axial strain of its "
        "body: 0.1 * nut axial stiffness " + format_value(p.nut_axial_stiffness) +
        " N/m * nut.length " + format_value(p.nut_length) +
        " m; beyond it no nut material is elastic)");
  if (!lift_off) return;
  const double depth = 0.5 * p.thread.pitch();
  const double penetration = e.thread->penetration_for(p.nut_preload);
  if (!(penetration < depth))
    throw InvalidArgument(
        "nut.preload = " + format_value(p.nut_preload) + " N is invalid with backlash.contact = \"" +
        backlash_contact_name(p.backlash) + "\": it presses half A's flank in by " +
        format_value(penetration) + " m (the flank contact's law at the preload), must be below "
        "the thread's depth, half of thread.pitch = " + format_value(depth) +
        " m (lower the preload or raise backlash.stiffness)");
}

void build_preloaded_nut(const DriveParameters& p, DriveElements& e) {
  require_nonnegative("nut.preload", p.nut_preload);
  require_nonnegative("nut.preload_stiffness", p.nut_preload_stiffness);
  if (p.nut_preload == 0.0) return;
  // The train's friction stages take no preloaded nut (checked first: no
  // other rule of the nut's is worth meeting before this one).
  const bool stage = p.gear == GearType::lossy || p.gear == GearType::worm;
  if (stage || p.motor_friction_torque > 0.0)
    throw InvalidArgument(
        "nut.preload = " + format_value(p.nut_preload) + " N is invalid with " +
        (stage ? "gear.type = \"" + gear_type_name(p.gear) + "\""
               : "motor.friction_torque = " + format_value(p.motor_friction_torque) + " N m") +
        ": a preloaded nut takes none of the train's friction stages (a lossy or worm stage, "
        "the motor's friction torque); use nut.preload = 0, or gear.type = \"ideal\" and "
        "motor.friction_torque = 0");
  const std::string preload = "nut.preload = " + format_value(p.nut_preload) + " is invalid ";
  const std::string supported =
      ": a preloaded nut is supported on the rigid concept, and on the flexible concepts "
      "without play, with exact play (closed by the preload) or with penalty flanks "
      "(backlash.contact = \"bistop\" or \"cubic\"), "
      "with exact Coulomb friction (friction.law = \"coulomb\", mu_static >= mu) and "
      "initial.state = \"relaxed\"";
  // Exact Coulomb, with one coefficient or with mu_static above mu (the
  // halves stick at mu_static', slip at mu': preloaded_nut.hpp).
  const friction::Law& law = e.thread->law();
  const bool coulomb = law.resolution() == friction::Resolution::set_valued &&
                       law.viscous() == 0.0 && law.slip_mu(0.0) == law.mu() &&
                       law.slip_mu(1.0) == law.mu() && law.mu_static() >= law.mu();
  if (!coulomb)
    throw InvalidArgument(preload + "with friction.law = \"" + p.friction + "\"" + supported);
  if (p.initial_state == InitialState::equilibrium)
    throw InvalidArgument(preload + "with initial.state = \"equilibrium\"" + supported +
                          " (on the rigid concept the relaxed start at rest is the same state)");
  require_carried_preload(p, e, p.concept != Concept::rigid && p.backlash != BacklashContact::none &&
                                    p.backlash != BacklashContact::exact);
  PreloadedNut nut;
  nut.preload = p.nut_preload;
  nut.stiffness = p.nut_preload_stiffness;
  nut.mu = e.thread->effective_mu();
  nut.mu_static = law.mu_static() * e.thread->flank_factor();
  const double alpha = p.thread.lead_angle();
  nut.cos_lead = std::cos(alpha);
  nut.sin_lead = std::sin(alpha);
  if (!(nut.cos_lead - nut.mu * nut.sin_lead > 0.0))
    throw InvalidArgument(preload + "with mu' tan(lead angle) = " +
                          format_value(nut.mu * std::tan(alpha)) +
                          " >= 1: the preload half would lock against its own spring "
                          "(lower friction.mu or the lead)");
  // The same at the stick limit (the edges at mu_static', preloaded_nut.hpp).
  if (!(nut.cos_lead - nut.mu_static * nut.sin_lead > 0.0))
    throw InvalidArgument("friction.mu_static = " + format_value(law.mu_static()) +
                          " is invalid with nut.preload = " + format_value(p.nut_preload) +
                          ": mu_static' tan(lead angle) = " +
                          format_value(nut.mu_static * std::tan(alpha)) +
                          " >= 1, the preload half would lock against its own spring at rest "
                          "(must be < 1: lower friction.mu_static or the lead)");
  // Half A carries the axial load at t = 0 (its flank: the sign of the normal
  // force the load alone puts on the screw); half B bears on the other flank.
  // No load at t = 0: half A on the flank of lambda_N > 0.
  // (The thread's normal on the translating part: on the load where that
  // part is rigid, on its contact body where it is flexible.)
  double translating_normal = 0.0;
  for (const int i : e.translating_group) translating_normal += e.thread->normal()[i];
  const double force = p.axial_force(0.0) * translating_normal;
  const int loaded_side = force > 0.0 ? -1 : 1;
  nut.side = -loaded_side;
  if (p.concept != Concept::rigid && p.backlash != BacklashContact::none) {
    // Lift-off (preloaded_nut.hpp): half A, the nut body, on its penalty
    // flank penetrated as far as the preload presses it.
    if (!(p.nut_preload_stiffness > 0.0))
      throw InvalidArgument("nut.preload_stiffness = " + format_value(p.nut_preload_stiffness) +
                            " is invalid with nut.preload = " + format_value(p.nut_preload) +
                            " and backlash.contact = \"" + backlash_contact_name(p.backlash) +
                            "\" on concept = \"" + concept_name(p.concept) +
                            "\": must be > 0 where the halves can move apart (the spring "
                            "carries the load beyond what the preload holds)");
    nut.lift_off = true;
    nut.closing = 0.5 * p.clearance + e.thread->penetration_for(p.nut_preload);
  }
  e.preloaded_nut = nut;
}

}  // namespace

DriveElements build_drive_elements(DriveParameters& p) {
  require_nonnegative("friction.mu", p.mu);
  require_positive("friction.k_v", p.k_v);
  std::shared_ptr<const friction::Law> law = ThreadPair::make_law(p);
  require_positive("rotor.inertia", p.rotor_inertia);
  require_nonnegative("load.mass", p.load_mass);
  require_nonnegative("backlash.axial", p.clearance);
  require_in_range("backlash.restitution", p.restitution, 0.0, 1.0);
  require_finite("initial.rotor_angle", p.rotor_angle);
  require_finite("initial.rotor_speed", p.rotor_speed);
  require_finite("initial.play_position", p.play_position);
  // Exact flank contacts with zero play touch both flanks at once: that is
  // the thread without play.
  if (p.backlash == BacklashContact::exact && p.clearance == 0.0)
    p.backlash = BacklashContact::none;
  // A preloaded split nut on the rigid concept closes the play: its halves
  // bear on both flanks (preloaded_nut.hpp), the thread without play. So
  // does it exact play on the flexible concepts, while half A bears on its
  // flank (the driver raises where it would lift off: closes_exact_play).
  const bool closes_exact_play = p.nut_preload > 0.0 && p.concept != Concept::rigid &&
                                 p.backlash == BacklashContact::exact;
  if (p.nut_preload > 0.0 && (p.concept == Concept::rigid || closes_exact_play) &&
      p.backlash != BacklashContact::none) {
    p.backlash = BacklashContact::none;
    p.play_position = 0.0;
  }
  if (p.backlash == BacklashContact::bistop || p.backlash == BacklashContact::cubic) {
    require_positive("backlash.stiffness", p.contact_stiffness);
    require_nonnegative("backlash.damping", p.contact_damping);
    require_positive("backlash.penetration", p.contact_penetration);
    require_in_range("backlash.exponent", p.contact_exponent, 1.0, 10.0);
  }
  if (p.backlash == BacklashContact::none) {
    p.clearance = 0.0;
  }
  // A play below a picometre is below the resolution of the positions it is
  // the difference of (round-off of coordinates of up to a metre, 1e-16 m).
  if (p.clearance > 0.0 && p.clearance < kSmallestClearance)
    throw InvalidArgument("backlash.axial = " + format_value(p.clearance) +
                          " is invalid: must be 0 (no play) or >= " +
                          format_value(kSmallestClearance) +
                          " m (a smaller play is below the resolution of the positions)");
  if (std::abs(p.play_position) > 0.5 * p.clearance)
    throw InvalidArgument("initial.play_position = " + format_value(p.play_position) +
                          " is invalid: must be within +-backlash.axial / 2 = +-" +
                          format_value(0.5 * p.clearance));
  if (p.initial_state == InitialState::equilibrium) {
    // The equilibrium is at rest, under a torque (a speed-controlled motor
    // would make the thread's friction force statically indeterminate), with
    // the nut where the loads put it.
    const std::string with = " is invalid with initial.state = \"equilibrium\": ";
    if (p.speed_controlled)
      throw InvalidArgument("initial.state = \"equilibrium\" is invalid with loads.drive_speed: "
                            "the static equilibrium needs a torque-controlled motor "
                            "(loads.drive_torque)");
    if (p.rotor_speed != 0.0)
      throw InvalidArgument("initial.rotor_speed = " + format_value(p.rotor_speed) + with +
                            "must be 0 (the drive starts at rest)");
    if (p.play_position != 0.0)
      throw InvalidArgument("initial.play_position = " + format_value(p.play_position) + with +
                            "must be 0 (the equilibrium puts the nut on the flank the loads "
                            "press it against)");
  }

  // The gear stage between the rotor and the driven part (gear.hpp): the
  // rotor's coordinate is the stage's output, the rotor and its motor
  // reflected onto it.
  Gear gear;
  if (p.gear == GearType::none) {
    if (p.gear_ratio != 1.0)
      throw InvalidArgument("gear_ratio = " + format_value(p.gear_ratio) +
                            " is invalid without a gear stage (gear.type = \"none\"): "
                            "must be 1");
  } else {
    require_finite("gear.ratio", p.gear_ratio);
    if (!(std::abs(p.gear_ratio) >= kSmallestGearRatio &&
          std::abs(p.gear_ratio) <= 1.0 / kSmallestGearRatio))
      throw InvalidArgument("gear.ratio = " + format_value(p.gear_ratio) +
                            " is invalid: must be in [" + format_value(kSmallestGearRatio) +
                            ", " + format_value(1.0 / kSmallestGearRatio) + "] or in [-" +
                            format_value(1.0 / kSmallestGearRatio) + ", -" +
                            format_value(kSmallestGearRatio) +
                            "] (rotor turns per turn of the driven part; < 0 a reversing stage)");
    gear.ratio = p.gear_ratio;
  }

  // The concept: which parts are contact bodies of their own.
  const bool nut_flexible = p.concept != Concept::rigid;
  const bool screw_flexible = p.concept == Concept::flexible;
  const bool screw_rotates = p.drive == DrivenPart::screw;
  const bool rotating_flexible = screw_rotates ? screw_flexible : nut_flexible;
  const bool translating_flexible = screw_rotates ? nut_flexible : screw_flexible;
  const std::string rotating = screw_rotates ? "screw" : "nut";
  const std::string translating = screw_rotates ? "nut" : "screw";
  const double rotating_mass = screw_rotates ? p.screw_mass : p.nut_mass;
  const double rotating_inertia = screw_rotates ? p.screw_inertia : p.nut_inertia;
  const double translating_mass = screw_rotates ? p.nut_mass : p.screw_mass;
  const double translating_inertia = screw_rotates ? p.nut_inertia : p.screw_inertia;
  require_nonnegative(rotating + " mass", rotating_mass);
  require_nonnegative(rotating + " inertia", rotating_inertia);
  require_nonnegative(translating + " mass", translating_mass);
  require_nonnegative(translating + " inertia", translating_inertia);

  DriveElements e;
  auto add_coordinate = [&](const std::string& name) {
    e.coordinates.push_back(name);
    return e.coordinate_count() - 1;
  };
  // Bodies: the rotor (with a rigid rotating part on its coordinate), the
  // flexible parts' own contact bodies (u_<part>, phi_<part>), the load
  // (with a rigid translating part on its coordinate).
  const int rotor = add_coordinate("phi_rotor");
  e.bodies.push_back({"rotor", rotor, gear.reflected_inertia(p.rotor_inertia)});
  if (!rotating_flexible) e.bodies.push_back({rotating, rotor, rotating_inertia});
  int rotating_u = -1, rotating_phi = rotor, translating_u = -1, translating_phi = -1;
  auto add_contact_body = [&](const std::string& part, double mass, double inertia, int& u,
                              int& phi) {
    u = add_coordinate("u_" + part);
    e.bodies.push_back({part, u, require_positive(part + " mass", mass)});
    phi = add_coordinate("phi_" + part);
    e.bodies.push_back({part, phi, require_positive(part + " inertia", inertia)});
  };
  if (rotating_flexible)
    add_contact_body(rotating, rotating_mass, rotating_inertia, rotating_u, rotating_phi);
  if (translating_flexible)
    add_contact_body(translating, translating_mass, translating_inertia, translating_u,
                     translating_phi);
  const int load = add_coordinate("u_load");
  const double load_total = p.load_mass + (translating_flexible ? 0.0 : translating_mass);
  if (!(load_total > 0.0))
    throw InvalidArgument("load.mass = " + format_value(p.load_mass) +
                          " is invalid: must be > 0 when the " + translating +
                          " is flexible or massless");
  e.bodies.push_back({"load", load, p.load_mass});
  if (!translating_flexible) {
    e.bodies.push_back({translating, load, translating_mass});
    translating_u = load;
  }
  e.rotating_group = {rotor};
  if (rotating_flexible) e.rotating_group.push_back(rotating_phi);
  e.translating_group = {load};
  if (translating_flexible) e.translating_group.push_back(translating_u);

  const ContactCoordinates c = screw_rotates
                                   ? ContactCoordinates{rotating_u, rotating_phi, translating_u,
                                                        translating_phi}
                                   : ContactCoordinates{translating_u, translating_phi,
                                                        rotating_u, rotating_phi};

  // Springs and supports of the flexible parts (thesis eq. 4.16, 4.26).
  auto add_spring = [&](const std::string& name, int first, int second, bool screw, bool axial) {
    SpringDamper s;
    s.name = name;
    s.first = first;
    s.second = second;
    if (screw) {
      s.stiffness = axial ? p.screw_axial_stiffness : p.screw_torsional_stiffness;
      s.law = s.stiffness > 0.0 ? SpringDamper::Law::constant
                                : (axial ? SpringDamper::Law::screw_axial
                                         : SpringDamper::Law::screw_torsional);
      s.rigidity = axial ? p.screw_axial_rigidity : p.screw_torsional_rigidity;
      s.screw_length = p.screw_length;
      s.far_segment = axial && p.drive == DrivenPart::screw && p.support == ScrewSupport::both_ends;
      s.damping = axial ? p.screw_axial_damping : p.screw_torsional_damping;
    } else {
      s.law = SpringDamper::Law::constant;
      s.stiffness = axial ? p.nut_axial_stiffness : p.nut_torsional_stiffness;
      s.damping = axial ? p.nut_axial_damping : p.nut_torsional_damping;
    }
    // Every spring of the flexible screw's model needs the nut on the screw.
    s.on_screw = screw_flexible;
    e.forces.of<SpringDamper>().push_back(s);
  };
  if (rotating_flexible) {
    add_spring(rotating + " torsion", rotating_phi, rotor, screw_rotates, false);
    add_spring(rotating + " axial", rotating_u, -1, screw_rotates, true);
  }
  if (translating_flexible) {
    add_spring(translating + " axial", translating_u, load, !screw_rotates, true);
    add_spring(translating + " torsion", translating_phi, -1, !screw_rotates, false);
  }

  // Screw stiffness data, checked at the initial nut position.
  if (screw_flexible) {
    if (p.screw_axial_stiffness <= 0.0)
      require_positive("screw axial rigidity E A", p.screw_axial_rigidity);
    if (p.screw_torsional_stiffness <= 0.0)
      require_positive("screw torsional rigidity G I_p", p.screw_torsional_rigidity);
  }
  // The whole nut on the screw, for every concept (a run ends where it leaves).
  require_positive("screw.length", p.screw_length);
  require_positive("nut.position", p.nut_position);
  if (!(p.nut_position < p.screw_length))
    throw InvalidArgument("nut.position = " + format_value(p.nut_position) +
                          " is invalid: must be < screw.length = " +
                          format_value(p.screw_length));
  require_positive("nut.length", p.nut_length);
  require_nut_on_screw(p.drive, p.nut_position, p.nut_length, p.screw_length, false);
  require_nonnegative("overrides.damping_ratio", p.damping_ratio);
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(e.coordinate_count());
  for (const RigidBody& body : e.bodies) body.add_mass(mass);
  for (SpringDamper& s : e.forces.of<SpringDamper>()) {  // (their damping defaults)
    double derivative = 0.0;
    const double k = s.stiffness_at(p.nut_position, &derivative);
    require_positive(s.name + " stiffness", k);
    if (s.damping < 0.0) {
      // The mode that matters on a spring is the heavier body's (the load
      // bouncing on the nut, the screw on its support): the reduced mass
      // would leave it nearly undamped.
      const double carried =
          s.second >= 0 ? std::max(mass[s.first], mass[s.second]) : mass[s.first];
      s.damping = 2.0 * p.damping_ratio * std::sqrt(k * carried);
    }
    require_finite(s.name + " damping", s.damping);
  }

  e.thread.emplace(p, law, c, e.coordinate_count());
  e.motor = Motor{rotor, p.speed_controlled, p.drive_torque, p.drive_speed, gear};
  if (p.dc_motor) {
    // The DC motor drives the rotor alone (the torque-controlled Motor applies 0).
    if (p.speed_controlled)
      throw InvalidArgument("loads.drive_speed is invalid with motor.type = \"dc\": give "
                            "either the DC motor or loads.drive_speed (or loads.drive_torque), "
                            "not both");
    if (p.initial_state == InitialState::equilibrium)
      throw InvalidArgument("initial.state = \"equilibrium\" is invalid with motor.type = "
                            "\"dc\": the run starts with the current at 0 (use \"relaxed\")");
    const Excitation::Definition torque = p.drive_torque.definition();
    if (!(torque.kind == "constant" && torque.parameters.at(0) == 0.0))
      throw InvalidArgument("loads.drive_torque = " + p.drive_torque.describe() +
                            " is invalid with motor.type = \"dc\": give either the DC motor "
                            "or loads.drive_torque, not both");
    DcMotor m;
    m.rotor = rotor;
    m.voltage = p.motor_voltage;
    m.resistance = require_positive("motor.resistance", p.motor_resistance);
    m.inductance = require_nonnegative("motor.inductance", p.motor_inductance);
    m.torque_constant = require_positive("motor.torque_constant", p.motor_torque_constant);
    m.back_emf_constant = p.motor_back_emf_constant < 0.0
                              ? m.torque_constant
                              : require_positive("motor.back_emf_constant",
                                                 p.motor_back_emf_constant);
    m.current_limit = require_nonnegative("motor.current_limit", p.motor_current_limit);
    require_plausible_dc_motor(p, m);
    // Behind a gear: the motor as its coordinate sees it (gear.hpp).
    m.torque_constant = gear.driven_torque(m.torque_constant);
    m.back_emf_constant = gear.driven_torque(m.back_emf_constant);
    e.motor.torque = Excitation();
    e.dc_motor = m;
  }
  e.load = AxialLoad{load, p.axial_force};
  build_base_excitation(p, e);
  build_preloaded_nut(p, e);
  if (e.preloaded_nut) e.preloaded_nut->closes_exact_play = closes_exact_play;
  if (e.preloaded_nut && e.preloaded_nut->lift_off) {
    // The assembled nut: half A on its flank at the preload (e_0 = -b
    // closing, b = -side; initial.play_position is ignored, as on the rigid
    // concept).
    p.play_position = e.preloaded_nut->side * e.preloaded_nut->closing;
    e.thread.emplace(p, law, c, e.coordinate_count());
  }
  build_element_sections(p, e);  // the elements' own sections (end stops, ...)
  build_train_friction(p, e);
  return e;
}

// Why the event-driven scheme cannot run the train's friction stages of p
// ("" where it can): its TrainSolver takes the rigid drive without play,
// whose contacts all slip with one speed, with plain Coulomb friction on
// the thread.
std::string train_event_driven_obstacle(const DriveParameters& p, const friction::Law& law) {
  if (p.concept != Concept::rigid) return "concept = \"" + concept_name(p.concept) + "\"";
  if (p.clearance > 0.0 || p.backlash != BacklashContact::none)
    return "backlash.axial = " + format_value(p.clearance) + " (play)";
  if (!law.plain_coulomb())
    return p.friction == "coulomb" ? "friction.mu_static = " + format_value(law.mu_static()) +
                                         " above friction.mu = " + format_value(law.mu())
                                   : "friction.law = \"" + p.friction + "\"";
  // (The closed exact stop holds the drive through the thread's row,
  // DriveDynamics::solve; TrainSolver's closed forms do not take it.)
  if (const ElementSection* stops = find_section(p, "end_stops"))
    for (const auto& [key, value] : stops->choices)
      if (key == "contact" && value == "exact") return "end_stops.contact = \"exact\"";
  return given_base_excitation(p);
}

}  // namespace leadscrew::model::elements
