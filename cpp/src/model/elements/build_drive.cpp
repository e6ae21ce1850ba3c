// The thesis's drive concepts (chapter 4) as elements: the one place where
// the concept, the driven part and the backlash become bodies, springs, the
// thread pair, the motor and the load. The parameters' checks (check_*,
// each raising InvalidArgument that names the key, its value and what is
// valid) come apart from the construction (build_*, on checked input), in
// the order the first refused key of any input is the one named: a check
// that needs a built part (the thread's law, a spring's stiffness at the
// nut) runs where that part is built.
#include <algorithm>
#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/law.hpp"
#include "leadscrew/model/drive_geometry.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/element_section.hpp"
#include "leadscrew/model/elements/drive_elements.hpp"

namespace leadscrew::model::elements {

namespace {

// The thread's friction (mu, k_v; the law's own parameters: make_law).
void check_thread_friction(const DriveParameters& p) {
  require_nonnegative("friction.mu", p.mu);
  require_positive("friction.k_v", p.k_v);
}

// The rotor, the load, the play's size and restitution, the initial state.
void check_rotor_load_and_start(const DriveParameters& p) {
  require_positive("rotor.inertia", p.rotor_inertia);
  require_nonnegative("load.mass", p.load_mass);
  require_nonnegative("backlash.axial", p.clearance);
  require_in_range("backlash.restitution", p.restitution, 0.0, 1.0);
  require_finite("initial.rotor_angle", p.rotor_angle);
  require_finite("initial.rotor_speed", p.rotor_speed);
  require_finite("initial.play_position", p.play_position);
}

// The play as it runs: p's backlash, clearance and play position where a
// contact or a preload closes it. Returns whether a preloaded nut closes
// exact play on a flexible concept (PreloadedNut::closes_exact_play).
bool normalize_play(DriveParameters& p) {
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
  if (p.backlash == BacklashContact::none) {
    p.clearance = 0.0;
  }
  return closes_exact_play;
}

// The penalty flanks' law, the play's size and the initial play position
// (after normalize_play).
void check_play(const DriveParameters& p) {
  if (p.backlash == BacklashContact::bistop || p.backlash == BacklashContact::cubic) {
    require_positive("backlash.stiffness", p.contact_stiffness);
    require_nonnegative("backlash.damping", p.contact_damping);
    require_positive("backlash.penetration", p.contact_penetration);
    require_in_range("backlash.exponent", p.contact_exponent, 1.0, 10.0);
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
}

// The start at the static equilibrium: at rest, under a torque (a
// speed-controlled motor would make the thread's friction force statically
// indeterminate), with the nut where the loads put it.
void check_equilibrium_start(const DriveParameters& p) {
  if (p.initial_state != InitialState::equilibrium) return;
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

// The gear stage's ratio: 1 without a stage.
void check_gear_ratio(const DriveParameters& p) {
  if (p.gear == GearType::none) {
    if (p.gear_ratio != 1.0)
      throw InvalidArgument("gear_ratio = " + format_value(p.gear_ratio) +
                            " is invalid without a gear stage (gear.type = \"none\"): "
                            "must be 1");
    return;
  }
  require_finite("gear.ratio", p.gear_ratio);
  if (!(std::abs(p.gear_ratio) >= kSmallestGearRatio &&
        std::abs(p.gear_ratio) <= 1.0 / kSmallestGearRatio))
    throw InvalidArgument("gear.ratio = " + format_value(p.gear_ratio) +
                          " is invalid: must be in [" + format_value(kSmallestGearRatio) +
                          ", " + format_value(1.0 / kSmallestGearRatio) + "] or in [-" +
                          format_value(1.0 / kSmallestGearRatio) + ", -" +
                          format_value(kSmallestGearRatio) +
                          "] (rotor turns per turn of the driven part; < 0 a reversing stage)");
}

// The gear stage between the rotor and the driven part (gear.hpp): the
// rotor's coordinate is the stage's output, the rotor and its motor
// reflected onto it.
Gear build_gear(const DriveParameters& p) {
  Gear gear;
  if (p.gear != GearType::none) gear.ratio = p.gear_ratio;
  return gear;
}

// The concept: which parts are contact bodies of their own.
struct DriveLayout {
  explicit DriveLayout(const DriveParameters& p)
      : nut_flexible(p.concept != Concept::rigid),
        screw_flexible(p.concept == Concept::flexible),
        screw_rotates(p.drive == DrivenPart::screw),
        rotating_flexible(screw_rotates ? screw_flexible : nut_flexible),
        translating_flexible(screw_rotates ? nut_flexible : screw_flexible),
        rotating(screw_rotates ? "screw" : "nut"),
        translating(screw_rotates ? "nut" : "screw"),
        rotating_mass(screw_rotates ? p.screw_mass : p.nut_mass),
        rotating_inertia(screw_rotates ? p.screw_inertia : p.nut_inertia),
        translating_mass(screw_rotates ? p.nut_mass : p.screw_mass),
        translating_inertia(screw_rotates ? p.nut_inertia : p.screw_inertia) {}

  bool nut_flexible, screw_flexible, screw_rotates, rotating_flexible, translating_flexible;
  std::string rotating, translating;
  double rotating_mass, rotating_inertia, translating_mass, translating_inertia;
};

// The parts' masses and inertias: >= 0, > 0 for a contact body of its own;
// a load that moves (with the translating part's mass where that is rigid).
void check_bodies(const DriveParameters& p, const DriveLayout& d) {
  require_nonnegative(d.rotating + " mass", d.rotating_mass);
  require_nonnegative(d.rotating + " inertia", d.rotating_inertia);
  require_nonnegative(d.translating + " mass", d.translating_mass);
  require_nonnegative(d.translating + " inertia", d.translating_inertia);
  if (d.rotating_flexible) {
    require_positive(d.rotating + " mass", d.rotating_mass);
    require_positive(d.rotating + " inertia", d.rotating_inertia);
  }
  if (d.translating_flexible) {
    require_positive(d.translating + " mass", d.translating_mass);
    require_positive(d.translating + " inertia", d.translating_inertia);
  }
  const double load_total = p.load_mass + (d.translating_flexible ? 0.0 : d.translating_mass);
  if (!(load_total > 0.0))
    throw InvalidArgument("load.mass = " + format_value(p.load_mass) +
                          " is invalid: must be > 0 when the " + d.translating +
                          " is flexible or massless");
}

// The screw's stiffness data (checked at the initial nut position by
// build_spring_damping), the whole nut on the screw, for every concept (a
// run ends where it leaves), and the springs' damping ratio.
void check_screw_and_nut(const DriveParameters& p, const DriveLayout& d) {
  if (d.screw_flexible) {
    if (p.screw_axial_stiffness <= 0.0)
      require_positive("screw axial rigidity E A", p.screw_axial_rigidity);
    if (p.screw_torsional_stiffness <= 0.0)
      require_positive("screw torsional rigidity G I_p", p.screw_torsional_rigidity);
  }
  require_positive("screw.length", p.screw_length);
  require_positive("nut.position", p.nut_position);
  if (!(p.nut_position < p.screw_length))
    throw InvalidArgument("nut.position = " + format_value(p.nut_position) +
                          " is invalid: must be < screw.length = " +
                          format_value(p.screw_length));
  require_positive("nut.length", p.nut_length);
  require_nut_on_screw(p.drive, p.nut_position, p.nut_length, p.screw_length, false);
  require_nonnegative("overrides.damping_ratio", p.damping_ratio);
}

// The coordinates of the bodies build_bodies adds (-1: none).
struct BodyCoordinates {
  int rotor = -1, load = -1;
  int rotating_u = -1, rotating_phi = -1, translating_u = -1, translating_phi = -1;
  ContactCoordinates contact;
};

// Bodies: the rotor (with a rigid rotating part on its coordinate), the
// flexible parts' own contact bodies (u_<part>, phi_<part>), the load
// (with a rigid translating part on its coordinate).
BodyCoordinates build_bodies(const DriveParameters& p, const DriveLayout& d, const Gear& gear,
                             DriveElements& e) {
  auto add_coordinate = [&](const std::string& name) {
    e.coordinates.push_back(name);
    return e.coordinate_count() - 1;
  };
  BodyCoordinates at;
  const int rotor = at.rotor = add_coordinate("phi_rotor");
  e.bodies.push_back({"rotor", rotor, gear.reflected_inertia(p.rotor_inertia)});
  if (!d.rotating_flexible) e.bodies.push_back({d.rotating, rotor, d.rotating_inertia});
  at.rotating_phi = rotor;
  auto add_contact_body = [&](const std::string& part, double mass, double inertia, int& u,
                              int& phi) {
    u = add_coordinate("u_" + part);
    e.bodies.push_back({part, u, mass});
    phi = add_coordinate("phi_" + part);
    e.bodies.push_back({part, phi, inertia});
  };
  if (d.rotating_flexible)
    add_contact_body(d.rotating, d.rotating_mass, d.rotating_inertia, at.rotating_u,
                     at.rotating_phi);
  if (d.translating_flexible)
    add_contact_body(d.translating, d.translating_mass, d.translating_inertia, at.translating_u,
                     at.translating_phi);
  const int load = at.load = add_coordinate("u_load");
  e.bodies.push_back({"load", load, p.load_mass});
  if (!d.translating_flexible) {
    e.bodies.push_back({d.translating, load, d.translating_mass});
    at.translating_u = load;
  }
  e.rotating_group = {rotor};
  if (d.rotating_flexible) e.rotating_group.push_back(at.rotating_phi);
  e.translating_group = {load};
  if (d.translating_flexible) e.translating_group.push_back(at.translating_u);

  at.contact = d.screw_rotates ? ContactCoordinates{at.rotating_u, at.rotating_phi,
                                                    at.translating_u, at.translating_phi}
                               : ContactCoordinates{at.translating_u, at.translating_phi,
                                                    at.rotating_u, at.rotating_phi};
  return at;
}

// Springs and supports of the flexible parts (thesis eq. 4.16, 4.26).
void build_springs(const DriveParameters& p, const DriveLayout& d, const BodyCoordinates& at,
                   DriveElements& e) {
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
    s.on_screw = d.screw_flexible;
    e.forces.of<SpringDamper>().push_back(s);
  };
  if (d.rotating_flexible) {
    add_spring(d.rotating + " torsion", at.rotating_phi, at.rotor, d.screw_rotates, false);
    add_spring(d.rotating + " axial", at.rotating_u, -1, d.screw_rotates, true);
  }
  if (d.translating_flexible) {
    add_spring(d.translating + " axial", at.translating_u, at.load, !d.screw_rotates, true);
    add_spring(d.translating + " torsion", at.translating_phi, -1, !d.screw_rotates, false);
  }
}

// The springs' stiffness at the initial nut position (> 0) and their
// damping (its defaults from the damping ratio; finite), spring by spring:
// checks of the built springs and bodies.
void build_spring_damping(const DriveParameters& p, DriveElements& e) {
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
}

// The train's friction stages (train_friction.hpp): the motor's Coulomb
// friction and a lossy or worm stage, checked here alone (one rule, one
// place; the scene only converts). They run on the rigid drive without play
// alone, where every contact slips with one speed.
bool has_friction_stage(const DriveParameters& p) {
  return p.gear == GearType::lossy || p.gear == GearType::worm;
}

constexpr double kRightAngle = 1.5707963267948966;

// 1 / cos(flank_angle / 2): a worm's flank factor on its mu.
double worm_flank_factor(const DriveParameters& p) {
  return 1.0 / std::cos(0.5 * p.gear_flank_angle);
}

// gear.mu_static, or gear.mu where it is not given (< 0).
double worm_mu_static(const DriveParameters& p) {
  return p.gear_mu_static < 0.0 ? p.gear_mu : p.gear_mu_static;
}

void check_lossy_stage(const DriveParameters& p) {
  require_finite("gear.efficiency", p.gear_efficiency);
  if (!(p.gear_efficiency > 0.0 && p.gear_efficiency <= 1.0))
    throw InvalidArgument("gear.efficiency = " + format_value(p.gear_efficiency) +
                          " is invalid: must be in (0, 1]");
  require_finite("gear.efficiency_backdrive", p.gear_efficiency_backdrive);
  if (!(p.gear_efficiency_backdrive <= 1.0))
    throw InvalidArgument("gear.efficiency_backdrive = " +
                          format_value(p.gear_efficiency_backdrive) +
                          " is invalid: must be at most 1 (<= 0: self-locking)");
}

void check_worm_stage(const DriveParameters& p) {
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
  const double mu_static = worm_mu_static(p);
  require_finite("gear.mu_static", mu_static);
  if (!(mu_static >= p.gear_mu))
    throw InvalidArgument("gear.mu_static = " + format_value(mu_static) +
                          " is invalid: must be at least gear.mu = " + format_value(p.gear_mu));
  const double factor = worm_flank_factor(p);
  // Driven by the worm at all: gamma + rho'_static < pi/2.
  if (!(p.gear_lead_angle + std::atan(mu_static * factor) < kRightAngle))
    throw InvalidArgument(
        "gear.lead_angle = " + format_value(p.gear_lead_angle) + " rad is invalid with " +
        (p.gear_mu_static < 0.0 ? "gear.mu = " : "gear.mu_static = ") +
        format_value(mu_static) +
        ": the worm cannot be driven (lead angle + atan(mu_static / cos(flank_angle / 2)) "
        "must stay below pi/2 rad; gear.mu_static defaults to gear.mu)");
}

// The stages' parameters, then what nothing runs with them (needs the
// built thread's law).
void check_train_friction(const DriveParameters& p, const DriveElements& e) {
  require_finite("motor.friction_torque", p.motor_friction_torque);
  require_nonnegative("motor.friction_torque", p.motor_friction_torque);
  const bool stage = has_friction_stage(p);
  if (p.motor_friction_torque == 0.0 && !stage) return;
  if (p.gear == GearType::lossy) check_lossy_stage(p);
  if (p.gear == GearType::worm) check_worm_stage(p);
  const std::string what = stage ? "gear.type = \"" + gear_type_name(p.gear) + "\""
                                 : "motor.friction_torque = " +
                                       format_value(p.motor_friction_torque) + " N m";
  // What nothing runs. (The rigid concept without play, plain Coulomb
  // friction on the thread and a torque or DC motor run on both schemes;
  // the rest on Moreau-Jean only, every thread law but eq. (3.15); a
  // prescribed rotor speed on both, on the event-driven scheme with every
  // law: train_event_driven_obstacle, check_simulation_options;
  // docs/physics/gear.md.)
  if (e.thread->law().resolution() == friction::Resolution::acceleration && !p.speed_controlled)
    throw InvalidArgument(
        what + " is invalid with friction.law = \"" + p.friction +
        "\": Moreau-Jean's velocity-level step has no slip acceleration for eq. (3.15)'s "
        "friction (it would follow dt), and the event-driven scheme's rotor contact does not "
        "take it yet; use friction.law = "
        "\"arctan_velocity\", \"lugre\", \"stribeck\" or \"coulomb\", or a prescribed rotor "
        "speed (loads.drive_speed), which the event-driven scheme runs with every law");
  const double alpha = p.thread.lead_angle();
  if (!(std::cos(alpha) - e.thread->effective_mu() * std::sin(alpha) > 0.0))
    throw InvalidArgument(what + " is invalid with friction.mu = " + format_value(p.mu) +
                          ": a torque cannot drive the thread (mu' >= cot(lead angle)), so its "
                          "holding torques at rest form no interval");
  // (A preloaded nut: the stages take it on Moreau-Jean, with lift-off too:
  // moreau_lift_off.cpp.)
  // Penalty end stops are one more axial force on the train (TrainSolver,
  // and Moreau-Jean's); exact ones where the load is a body of its own
  // (elements/end_stops.cpp), on Moreau-Jean.
  if (p.initial_state == InitialState::equilibrium)
    throw InvalidArgument(what + " is invalid with initial.state = \"equilibrium\": the "
                          "initial equilibrium is not solved with the train's friction stages "
                          "(use \"relaxed\")");
}

// The stages of checked parameters (check_train_friction).
void build_train_friction(const DriveParameters& p, DriveElements& e) {
  const bool stage = has_friction_stage(p);
  if (p.motor_friction_torque == 0.0 && !stage) return;
  TrainFriction f;
  f.ratio = e.motor.gear.ratio;
  f.rotor_inertia = e.motor.gear.reflected_inertia(p.rotor_inertia);
  f.motor_friction = p.motor_friction_torque;
  if (p.gear == GearType::lossy) {
    f.stage = true;
    f.efficiency = f.efficiency_static = p.gear_efficiency;
    f.efficiency_backdrive = f.efficiency_backdrive_static = p.gear_efficiency_backdrive;
  } else if (p.gear == GearType::worm) {
    f.stage = f.worm = true;
    const double mu_static = worm_mu_static(p);
    const double factor = worm_flank_factor(p);
    f.efficiency = TrainFriction::worm_efficiency(p.gear_lead_angle, p.gear_mu * factor);
    f.efficiency_backdrive =
        TrainFriction::worm_efficiency_backdrive(p.gear_lead_angle, p.gear_mu * factor);
    f.efficiency_static = TrainFriction::worm_efficiency(p.gear_lead_angle, mu_static * factor);
    f.efficiency_backdrive_static =
        TrainFriction::worm_efficiency_backdrive(p.gear_lead_angle, mu_static * factor);
  }
  f.event_driven_obstacle = train_event_driven_obstacle(p, e.thread->law());
  // Where the event-driven scheme took the stages in issue 32 (a prescribed
  // rotor speed, a static coefficient on the thread), Moreau-Jean stays the
  // default: the results of before are unchanged.
  // (And off the rigid concept without play: the rotor's friction contact.)
  f.moreau_default = p.speed_controlled || !e.thread->law().plain_coulomb() ||
                     p.concept != Concept::rigid || p.backlash != BacklashContact::none;
  e.train_friction = f;
}

// The preloaded split nut of p (nut.preload > 0) on the thread without play
// (the rigid concept's, the flexible concepts' with or without exact play
// closed) or on penalty play (lift-off); elsewhere refused with what is
// supported.

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
void check_carried_preload(const DriveParameters& p, const DriveElements& e, bool lift_off) {
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

// The halves' friction coefficients mu' and mu_static' on the thread (the
// thread's law times its flank factor).
double preload_mu(const DriveElements& e) { return e.thread->effective_mu(); }
double preload_mu_static(const DriveElements& e) {
  return e.thread->law().mu_static() * e.thread->flank_factor();
}

// Whether the halves can move apart: lift-off (preloaded_nut.hpp), half A,
// the nut body, on its penalty flank.
bool preload_lifts_off(const DriveParameters& p) {
  return p.concept != Concept::rigid && p.backlash != BacklashContact::none;
}

// The preload's parameters and what it runs with (needs the built thread);
// the lift-off spring: check_preload_spring. Returns whether p has a
// preloaded nut.
bool check_preloaded_nut(const DriveParameters& p, const DriveElements& e) {
  require_nonnegative("nut.preload", p.nut_preload);
  require_nonnegative("nut.preload_stiffness", p.nut_preload_stiffness);
  if (p.nut_preload == 0.0) return false;
  const std::string preload = "nut.preload = " + format_value(p.nut_preload) + " is invalid ";
  // Each half's flank takes the law (docs/physics/preloaded_nut.md,
  // "Friction laws"): exact Coulomb with one coefficient or mu_static above
  // mu (the halves stick at mu_static', slip at mu': preloaded_nut.hpp),
  // Stribeck's curve, a velocity law, LuGre's bristles (one deflection for
  // both halves: they slip together), eq. (3.15) (its coefficient a fixed
  // point of the mode, drive_dynamics.cpp): no rule of the law's here.
  const friction::Law& law = e.thread->law();
  // The static equilibrium holds the halves' net forces (their spring is
  // internal; the cone the halves', drive_equilibrium.cpp); with lift-off the
  // assembled nut (half A pressed in by the preload) is the start.
  if (p.initial_state == InitialState::equilibrium && preload_lifts_off(p))
    throw InvalidArgument(preload + "with initial.state = \"equilibrium\" and backlash.contact "
                          "= \"" + backlash_contact_name(p.backlash) + "\": a preloaded nut that "
                          "lifts off starts assembled, half A pressed into its flank by the "
                          "preload (the equilibrium's nut sits where the loads put it); use "
                          "initial.state = \"relaxed\"");
  check_carried_preload(p, e, p.concept != Concept::rigid && p.backlash != BacklashContact::none &&
                                  p.backlash != BacklashContact::exact);
  const double mu = preload_mu(e), mu_static = preload_mu_static(e);
  const double alpha = p.thread.lead_angle();
  const double cos_lead = std::cos(alpha), sin_lead = std::sin(alpha);
  if (!(cos_lead - mu * sin_lead > 0.0))
    throw InvalidArgument(preload + "with mu' tan(lead angle) = " +
                          format_value(mu * std::tan(alpha)) +
                          " >= 1: the preload half would lock against its own spring "
                          "(lower friction.mu or the lead)");
  // The same at the stick limit (the edges at mu_static', preloaded_nut.hpp).
  if (!(cos_lead - mu_static * sin_lead > 0.0))
    throw InvalidArgument("friction.mu_static = " + format_value(law.mu_static()) +
                          " is invalid with nut.preload = " + format_value(p.nut_preload) +
                          ": mu_static' tan(lead angle) = " +
                          format_value(mu_static * std::tan(alpha)) +
                          " >= 1, the preload half would lock against its own spring at rest "
                          "(must be < 1: lower friction.mu_static or the lead)");
  return true;
}

// Where the halves can move apart, the spring carries the load beyond what
// the preload holds. (Checked after build_preloaded_nut, which evaluates the
// axial load at t = 0: a load that fails there is named first.)
void check_preload_spring(const DriveParameters& p) {
  if (preload_lifts_off(p) && !(p.nut_preload_stiffness > 0.0))
    throw InvalidArgument("nut.preload_stiffness = " + format_value(p.nut_preload_stiffness) +
                          " is invalid with nut.preload = " + format_value(p.nut_preload) +
                          " and backlash.contact = \"" + backlash_contact_name(p.backlash) +
                          "\" on concept = \"" + concept_name(p.concept) +
                          "\": must be > 0 where the halves can move apart (the spring "
                          "carries the load beyond what the preload holds)");
}

// The preloaded nut of checked parameters (check_preloaded_nut).
PreloadedNut build_preloaded_nut(const DriveParameters& p, const DriveElements& e) {
  PreloadedNut nut;
  nut.preload = p.nut_preload;
  nut.stiffness = p.nut_preload_stiffness;
  nut.mu = preload_mu(e);
  nut.mu_static = preload_mu_static(e);
  const double alpha = p.thread.lead_angle();
  nut.cos_lead = std::cos(alpha);
  nut.sin_lead = std::sin(alpha);
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
  if (preload_lifts_off(p)) {
    // Lift-off (preloaded_nut.hpp): half A, the nut body, on its penalty
    // flank penetrated as far as the preload presses it.
    nut.lift_off = true;
    nut.closing = 0.5 * p.clearance + e.thread->penetration_for(p.nut_preload);
  }
  return nut;
}

}  // namespace

DriveElements build_drive_elements(DriveParameters& p) {
  // The parameters' checks, in the order of their messages (the law checks
  // its own parameters as make_law builds it).
  check_thread_friction(p);
  std::shared_ptr<const friction::Law> law = ThreadPair::make_law(p);
  check_rotor_load_and_start(p);
  const bool closes_exact_play = normalize_play(p);
  check_play(p);
  check_equilibrium_start(p);
  check_gear_ratio(p);
  const DriveLayout layout(p);
  check_bodies(p, layout);
  check_screw_and_nut(p, layout);

  // The model: bodies, springs, the thread pair, the motor, the load, the
  // elements; the checks that need a built part where it is built.
  const Gear gear = build_gear(p);
  DriveElements e;
  const BodyCoordinates at = build_bodies(p, layout, gear, e);
  build_springs(p, layout, at, e);
  build_spring_damping(p, e);
  e.thread.emplace(p, law, at.contact, e.coordinate_count());
  e.motor = Motor{at.rotor, p.speed_controlled, p.drive_torque, p.drive_speed, gear};
  // The sections whose element drives the rotor (a DC motor), with the motor.
  build_element_sections(p, e, SectionType::Stage::motor);
  e.load = AxialLoad{at.load, p.axial_force};
  build_base_excitation(p, e);
  if (check_preloaded_nut(p, e)) {
    PreloadedNut nut = build_preloaded_nut(p, e);
    check_preload_spring(p);
    nut.closes_exact_play = closes_exact_play;
    e.preloaded_nut = nut;
  }
  if (e.preloaded_nut && e.preloaded_nut->lift_off) {
    // The assembled nut: half A on its flank at the preload (e_0 = -b
    // closing, b = -side; initial.play_position is ignored, as on the rigid
    // concept).
    p.play_position = e.preloaded_nut->side * e.preloaded_nut->closing;
    e.thread.emplace(p, law, at.contact, e.coordinate_count());
  }
  build_element_sections(p, e);  // the elements' own sections (end stops, ...)
  check_train_friction(p, e);
  build_train_friction(p, e);
  return e;
}

// Why the event-driven scheme cannot run the train's friction stages of p
// ("" where it can): its TrainSolver takes the rigid drive without play
// with Coulomb friction on the thread, the rotor's friction contact the
// rest it runs (docs/physics/gear.md, "The event-driven rotor contact").
std::string train_event_driven_obstacle(const DriveParameters& p, const friction::Law& law) {
  // Behind a prescribed rotor speed the stages change the motor's torque
  // alone, not the motion: the constrained solve runs every drive
  // (ConstrainedSolver books their losses).
  if (p.speed_controlled) return "";
  // The rotor's friction contact (hybrid_rotor_contact.cpp) runs them on
  // the constrained solve with the thread's own law where TrainSolver does
  // not (off the rigid concept without play; arctan_velocity on it,
  // DriveHybrid::train_solver_applies): no play, penalty and exact play,
  // Coulomb (mu_static too), Stribeck and
  // arctan_velocity (docs/physics/gear.md, "Exact play through the rotor's
  // contact").
  // Exact play: the flank's impacts through the rotor's contact
  // (hybrid_rotor_impact.cpp); on the rigid concept a closed flank with the
  // rotor stuck fixes every velocity, the thread's friction then the one
  // that leaves the rotor's contact the least |Q| (DriveDynamics::
  // rotor_fixes_slip, Moreau-Jean's "stuck together").
  // The rotor's contact takes the thread's set-valued laws (Coulomb with
  // mu_static, Stribeck: the thread's own stick and slip decisions beside
  // the rotor's) and arctan_velocity (eq. (3.15) check_train_friction
  // refuses). Not LuGre (Moreau-Jean does not run its
  // bristles beside the rotor's contact: no reference), nor Stribeck on
  // the rigid concept without play, where the thread's stick row and the
  // rotor's fix the one velocity together (TrainSolver's closed forms take
  // Coulomb's one kinetic coefficient).
  const bool rigid_train = p.concept == Concept::rigid && p.backlash == BacklashContact::none;
  if (law.resolution() == friction::Resolution::bristle ||
      (rigid_train && law.resolution() == friction::Resolution::set_valued &&
       p.friction != "coulomb"))
    return "friction.law = \"" + p.friction + "\"";
  // A preloaded nut and exact end stops: the rotor's friction contact on
  // the flexible concepts (hybrid_rotor_stops.cpp), beside the thread's
  // mu_static and Stribeck, a preloaded nut beside exact play's impacts too
  // (validated together against Moreau-Jean:
  // tests/test_event_driven_stops_play_static.py, and the drive-train
  // fuzz's cases they refused). Not on the rigid
  // concept, whose two coordinates a held load and a stuck rotor fix
  // already: the thread's stick row is dependent on them, the split of the
  // holding torque between the thread's friction and the rotor's
  // statically indeterminate, which the rotor's contact does not resolve
  // (its solve is singular) and TrainSolver's closed forms do not take; a
  // preloaded nut's stick edge there is not resolved with the rotor's
  // contact either (no consistent edge at the start).
  const bool exact_stops = has_exact_end_stops(p);
  // Exact end stops beside exact play's impacts: not validated together (a
  // clamp at the stop, seat_adjuster_worm_flexible, fails its friction-cone
  // check at rtol 1e-6 and 1e-8: docs/physics/gear.md).
  if (exact_stops && p.backlash == BacklashContact::exact)
    return "end_stops.contact = \"exact\" and backlash.contact = \"exact\" (each runs beside "
           "the rotor's friction contact alone, not validated together)";
  if (p.concept == Concept::rigid) {
    if (p.nut_preload > 0.0)
      return "nut.preload = " + format_value(p.nut_preload) +
             " N on concept = \"rigid\" (the preloaded nut's stick edge with the rotor's "
             "friction contact is not resolved there)";
    if (exact_stops)
      return "end_stops.contact = \"exact\" on concept = \"rigid\" (with the load held and "
             "the rotor stuck the thread's friction and the rotor's share the holding torque "
             "in a statically indeterminate split)";
  }
  // A nut lifting off with Stribeck's viscous term: no reference (Moreau-
  // Jean's lift-off takes none), and the rotor's contact stalled at one
  // instant on such a drive (train fuzz, seed 20261127, case 9,179).
  const bool lifts_off = p.nut_preload > 0.0 && (p.backlash == BacklashContact::bistop ||
                                                 p.backlash == BacklashContact::cubic);
  if (lifts_off && p.friction == "stribeck" && law.viscous() > 0.0)
    return "nut.preload = " + format_value(p.nut_preload) +
           " N lifting off (backlash.contact = \"" + backlash_contact_name(p.backlash) +
           "\") with friction.law = \"stribeck\" and "
           "friction.viscous = " + format_value(law.viscous()) +
           " (no reference: Moreau-Jean's lift-off takes no viscous term)";
  return given_base_excitation(p);
}

}  // namespace leadscrew::model::elements
