// The end stops of the load's travel (elements/end_stop.hpp;
// docs/physics/end_stops.md) as an element of the event-driven driver
// (driver_element.hpp): one root per stop, the penalty stops' first; its
// channel stop_force (declaration.hpp).
//
// Penalty stops: their force enters the forces through DriveDynamics (a
// force element); here are their roots, one per stop: its contact margin,
// which rises through 0 where the stop starts to push (the load reaches its
// face: a jump of c d') and falls through 0 where it releases (a kink), so
// that the integrator stops at either.
//
// Exact stops: one root per stop, its gap while free (an impact where it
// falls to 0: Newton's law u'+ = -e u'-, on a load that the thread ties to
// other coordinates through the frictional thread, tied_impact; or the
// contact closes where the rebound is below the bounce threshold and the
// stop pushes), and while closed the reaction that holds the load at the
// face (the held load a row of the mode's solve, ModeSpec::held_load; it
// opens where that falls to 0). docs/physics/end_stops.md, "The rigid drive
// at an exact stop".
#include <cmath>
#include <limits>
#include <string>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

#include "driver_element.hpp"

namespace leadscrew::model::drive {

const ElementKind& end_stops_kind();

namespace {

void declare(const DriveModel& model, const friction::Law& law, Declaration& d) {
  (void)law;
  // The stops' force on the load along +u (its energy is the force
  // elements' elastic energy and damping loss, an exact stop's impacts').
  if (model.elements().end_stops().empty() && model.elements().exact_stops.empty()) return;
  d.channels = end_stops_kind().catalog;
  // The penalty stops' force follows from the load's position and speed
  // (for every driver); an exact stop's is the element's (output).
  if (model.elements().end_stops().empty()) return;
  d.add_from_coordinates = [stops = &model.elements().end_stops(), load = model.load()](
                               const CoordinateVector& q, const CoordinateVector& v,
                               double* values) {
    for (const elements::EndStop& stop : *stops) values[0] += stop.force_on_load(q[load], v[load]);
  };
}

std::string joined(const std::string& a, const std::string& b) {
  return a.empty() ? b : a + ", " + b;
}

class EndStopsElement final : public DriveHybrid::Element {
 public:
  EndStopsElement(DriveHybrid& hybrid, const DriveModel& model)
      : Element(hybrid),
        stops_(model.elements().end_stops()),
        exact_(model.elements().exact_stops),
        load_(model.load()) {}

  int root_count() const override { return static_cast<int>(stops_.size() + exact_.size()); }

  // A penalty stop's contact margin (> 0 exactly where it pushes); an exact
  // stop's gap while free, its reaction while closed.
  void roots(double t, double* g) const override {
    (void)t;
    int k = 0;
    for (const elements::EndStop& stop : stops_)
      g[k++] = stop.contact_margin(q()[load_], v()[load_]);
    for (std::size_t i = 0; i < exact_.size(); ++i) {
      const bool closed = i < closed_.size() && closed_[i];
      // The reaction side F_load that holds the load at the face (the forces
      // on the load press it on while > 0).
      g[k++] = closed ? reaction(exact_[i]) : exact_[i].gap(q()[load_]);
    }
  }

  void root_directions(int* directions) const override {
    // A penalty stop that does not push starts to (rising); one that pushes
    // releases (falling). The other crossing is the located root's round-off.
    // An exact stop's gap and reaction both end their state falling.
    int k = 0;
    for (std::size_t i = 0; i < stops_.size(); ++i)
      directions[k++] = i < pushing_.size() && pushing_[i] ? -1 : 1;
    for (std::size_t i = 0; i < exact_.size(); ++i) directions[k++] = -1;
  }

  // Which stops push at the state last set (a start, a resume: exact stops
  // free).
  void start(double t, const double* y) override {
    (void)t;
    (void)y;
    pushing_.assign(stops_.size(), 0);
    for (std::size_t i = 0; i < stops_.size(); ++i)
      pushing_[i] = stops_[i].contact_margin(q()[load_], v()[load_]) > 0.0;
    // The scene starts the load between the stops; a resumed run (the
    // stepper's next piece) starts closed where the last left the load held
    // at a face (at rest within the bounce threshold: a load the thread ties
    // to other coordinates carries their round-off, 4e-20 m/s) and the
    // stop still pushes there. (Left open with the gap at or below 0, its
    // root, which ends the free flight only falling through 0, could not
    // fire: the load passed the stop in the next pieces.)
    closed_.assign(exact_.size(), 0);
    hold_load(-1);
    for (std::size_t i = 0; i < exact_.size(); ++i)
      closed_[i] = exact_[i].gap(q()[load_]) <= 0.0 &&
                   std::abs(v()[load_]) <= bounce_threshold() && presses(exact_[i]);
  }

  // The penalty stops that now push or no longer do, an exact stop's
  // impact, closing or opening (y changed). A stop's force jumps (c d' at
  // the onset; an exact stop's impact or closing), so the friction mode is
  // decided anew, as at a penalty flank.
  Event handle(double t, double* y, const int* root_info) override {
    std::string kind;
    pushing_.resize(stops_.size(), 0);
    for (std::size_t i = 0; i < stops_.size(); ++i) {
      const int info = root_info[i];
      if (info == 0) continue;
      pushing_[i] = info > 0;
      kind = joined(kind, stops_[i].name + (info > 0 ? " contact" : " release"));
    }
    closed_.resize(exact_.size(), 0);
    for (std::size_t i = 0; i < exact_.size(); ++i) {
      if (root_info[stops_.size() + i] >= 0) continue;  // (falling only)
      const elements::ExactEndStop& stop = exact_[i];
      set(t, y);
      if (closed_[i]) {
        closed_[i] = 0;
        hold_load(-1);
        kind = joined(kind, stop.name + " opens");
        continue;
      }
      const double approach = v()[load_];
      if (stop.side * approach < 0.0) {
        // Leaving: no impact, the gap's fall is the integrator's round-off
        // (a rebound whose flight is below its tolerance). The load goes
        // back onto the face: left beyond it, the gap would start the next
        // piece below 0 and its root, which ends the free flight only
        // falling through 0, could never fire again (the load passed the
        // stop after a decaying run of bounces: 0.215 mm through it).
        if (stop.gap(q()[load_]) < 0.0) {
          onto_face(stop);
          layout().compress(q(), v(), y);
        }
        continue;
      }
      bool close = false;
      if (tied()) {
        close = tied_impact(t, y, stop);
      } else {
        const double mass = model().mass()[load_];
        double after = -stop.restitution * approach;
        q()[load_] = stop.position;  // the root's round-off onto the face
        // A rebound below the bounce threshold closes the contact where the
        // forces press the load on (else it leaves at that speed).
        close = std::abs(after) <= bounce_threshold() && presses(stop);
        if (close) after = 0.0;
        v()[load_] = after;
        impact_loss() += 0.5 * mass * (approach * approach - after * after);
        layout().compress(q(), v(), y);
      }
      closed_[i] = close;
      hold_load(close ? load_ : -1);
      kind = joined(kind, stop.name + (close ? " impact, closed" : " impact"));
    }
    return {kind, true};
  }

  void release_hold() override { closed_.assign(exact_.size(), 0); }

  // A closed exact stop holds the load: its position's and velocity's rates 0.
  void rates(double t, const double* y, double* ydot, double* energy) const override {
    (void)t;
    (void)y;
    (void)energy;
    const StateLayout& layout = this->layout();
    for (std::size_t i = 0; i < closed_.size(); ++i) {
      if (!closed_[i]) continue;
      const int np = static_cast<int>(layout.positions().size());
      for (int k = 0; k < np; ++k)
        if (layout.positions()[k] == load_) ydot[k] = 0.0;
      for (std::size_t k = 0; k < layout.velocities().size(); ++k)
        if (layout.velocities()[k] == load_) ydot[np + static_cast<int>(k)] = 0.0;
    }
  }

  // The exact stops' force on the load along +u [N]: a closed stop
  // balances the forces on the held load (the penalty stops' is added from
  // q and v, the declaration's add_from_coordinates).
  void output(double t, const double* y, const ContactForces& forces,
              ChannelState& state) const override {
    (void)t;
    (void)y;
    (void)forces;
    if (first_channel() < 0) return;
    for (std::size_t i = 0; i < closed_.size(); ++i)
      if (closed_[i]) {
        state.values[first_channel()] = solve_current().stop_force;
        return;
      }
  }

 private:
  // The closed stop's reaction at the state set, > 0 while it pushes the
  // load off its face: the stop's force from the mode's solve with the
  // load held (its row; on the rigid drive the thread's friction 0 then:
  // DriveDynamics::solve, docs/physics/end_stops.md).
  double reaction(const elements::ExactEndStop& stop) const {
    return -stop.side * solve_current().stop_force;
  }
  // Would the stop, closed at the state set, push (the forces press the
  // load on)? Leaves the load held where it would.
  bool presses(const elements::ExactEndStop& stop) {
    hold_load(load_);
    const bool pushes = reaction(stop) >= 0.0;
    if (!pushes) hold_load(-1);
    return pushes;
  }
  // A constraint row of the mode moves the load with other coordinates
  // (the thread without play, a closed flank of exact play, with the load
  // on the translating part): an impulse on it passes through the thread.
  bool tied() const {
    const ThreadContact c = mode().contact;
    return (c == ThreadContact::bilateral || c == ThreadContact::closed) &&
           model().normal_direction()[load_] != 0.0;
  }
  bool tied_impact(double t, double* y, const elements::ExactEndStop& stop);
  CoordinateVector frictionless_response(const CoordinateVector& unit) const;
  // The load onto the face (the root's round-off), the coordinates tied to
  // it along (the thread's constraints kept: on the rigid drive the load's
  // position follows the rotor's, which StateLayout keeps).
  void onto_face(const elements::ExactEndStop& stop) {
    if (tied()) {
      CoordinateVector unit = CoordinateVector::Zero(model().coordinate_count());
      unit[load_] = 1.0;
      const CoordinateVector shift = frictionless_response(unit);
      if (shift[load_] != 0.0) q() += ((stop.position - q()[load_]) / shift[load_]) * shift;
    }
    q()[load_] = stop.position;
  }
  struct Phase {
    CoordinateVector dv;  // the velocities' change per unit impulse of the stop
    bool stuck = false;
  };
  Phase phase(const CoordinateVector& unit, const CoordinateVector& zero, double slip,
              double slip_noise) const;
  Phase slipping(int slip_sign, const CoordinateVector& unit, const CoordinateVector& zero) const;
  // The phase with the rotor's friction contact: its mode per impulse
  // (hybrid_rotor_stops.cpp) chosen with the thread's phase.
  Phase rotor_phase(const CoordinateVector& unit, const CoordinateVector& zero, double slip,
                    double slip_noise);

  const std::vector<elements::EndStop>& stops_;
  const std::vector<elements::ExactEndStop>& exact_;
  int load_;
  std::vector<char> pushing_;  // per penalty stop: it pushes (its root's direction)
  std::vector<char> closed_;   // per exact stop: closed (the load held at its face)
};

// The velocities' response to the generalized impulse `unit` with the
// mode's constraints and no friction (they keep the constraints).
CoordinateVector EndStopsElement::frictionless_response(const CoordinateVector& unit) const {
  ModeSpec base = spec(1);
  base.held_load = -1;
  base.friction = FrictionMode::none;
  base.given_tangential = 0.0;
  const CoordinateVector zero = CoordinateVector::Zero(unit.size());
  return solve_with(base, unit).acceleration - solve_with(base, zero).acceleration;
}

// The velocities' response to a unit impulse of the stop in slip with the
// slip's sign: the normal impulse's sign consistent with the friction it
// carries (eq. 3.15 on impulses). Both signs or none: the Painleve regime,
// the phase's effective mass not positive (rigid_drive.md section 7:
// Delta_eps <= 0), dynamic jamming.
EndStopsElement::Phase EndStopsElement::slipping(int slip_sign, const CoordinateVector& unit,
                                                 const CoordinateVector& zero) const {
  Phase found;
  int consistent = 0;
  for (const int sigma : {1, -1}) {
    ModeSpec s = spec(sigma);
    s.held_load = -1;
    s.friction = FrictionMode::slip;
    s.slip_sign = slip_sign;
    const ModeSolution a = solve_with(s, unit), b = solve_with(s, zero);
    if (!a.regular || !b.regular) continue;
    if (s.contact == ThreadContact::closed || sigma * (a.normal_force - b.normal_force) >= 0.0) {
      found.dv = a.acceleration - b.acceleration;
      ++consistent;
    }
    if (s.contact == ThreadContact::closed) break;
  }
  if (consistent != 1)
    jam("the end stop's impact through the thread in slip (slip sign " +
        std::to_string(slip_sign) + ") has " + std::to_string(consistent) +
        " consistent signs of the flank's normal impulse");
  return found;
}

// The phase at the current velocities: the thread slips along its slip
// (friction against it), or at zero slip sticks where mu_static''s cone
// holds the stick's friction impulse, else slips the way the impulse
// drives it (docs/physics/end_stops.md, "Impacts on the rigid drive").
EndStopsElement::Phase EndStopsElement::phase(const CoordinateVector& unit,
                                              const CoordinateVector& zero, double slip,
                                              double slip_noise) const {
  ModeSpec base = spec(1);
  base.held_load = -1;
  if (base.friction == FrictionMode::none) {
    base.given_tangential = 0.0;
    Phase p;
    p.dv = solve_with(base, unit).acceleration - solve_with(base, zero).acceleration;
    return p;
  }
  if (std::abs(slip) > slip_noise) return slipping(slip > 0.0 ? 1 : -1, unit, zero);
  ModeSpec st = base;
  st.friction = FrictionMode::stick;
  const ModeSolution a = solve_with(st, unit), b = solve_with(st, zero);
  const double normal = a.normal_force - b.normal_force;
  const double friction = a.friction_force - b.friction_force;
  if (a.regular && b.regular && std::abs(friction) <= stick_mu() * std::abs(normal)) {
    Phase p;
    p.dv = a.acceleration - b.acceleration;
    p.stuck = true;
    return p;
  }
  // Slip where the stick's friction impulse points against the slip it
  // would start (the impulse drives the slip the other way).
  return slipping(friction > 0.0 ? -1 : 1, unit, zero);
}

// The phase at the current velocities with the rotor's friction contact:
// the rotor's modes in decide_rotor's order (at rest stick, the slips, the
// slips at breakaway; moving its slip's), each with the thread's phase, the
// first whose rotor speed change fits the impulse kept
// (DriveHybrid::rotor_impulse_consistent).
EndStopsElement::Phase EndStopsElement::rotor_phase(const CoordinateVector& unit,
                                                    const CoordinateVector& zero, double slip,
                                                    double slip_noise) {
  const int r = model().rotor();
  const double w = v()[r];
  const bool at_rest =
      std::abs(w) <= 64.0 * std::numeric_limits<double>::epsilon() * v().cwiseAbs().sum();
  std::string failure;
  for (const moreau_contacts::RotorMode& candidate : moreau_contacts::kRotorModes) {
    if (!rotor_train()->stage && candidate.flow < 0) continue;
    if (candidate.slip == 0 && !at_rest) continue;
    if (!at_rest && (candidate.breakaway || candidate.slip != (w > 0.0 ? 1 : -1))) continue;
    rotor_mode() = candidate;
    try {
      const Phase p = phase(unit, zero, slip, slip_noise);
      if (rotor_impulse_consistent(candidate, p.dv[r], at_rest)) return p;
    } catch (const SimulationError& e) {  // (that mode's thread phase jams)
      if (failure.empty()) failure = e.what();
    }
  }
  jam("the end stop's impact through the thread admits no consistent stick/slip state of the "
      "rotor's friction contact (the motor's friction, the gear stage)" +
      (failure.empty() ? std::string() : " (" + failure + ")"));
}

// An impact on a load that a constraint ties to other coordinates (the
// rigid drive; the nut-driven flexible nut's screw): the stop's impulse P
// on the load passes through the frictional thread, piecewise linear in P
// (Darboux-Keller on the impulse): in each phase the velocities change by
// dv P, a phase ends where the slip reaches zero (then stick or the
// reversed slip: compression with the slip along v-, expansion reversed)
// or where the load's normal velocity reaches Newton's target -e u'-. A
// phase in which the impulse does not slow the load (an effective mass
// not positive) is dynamic jamming; a stick that holds the load at rest
// after the compression (the self-locking thread, tan a <= mu_static' on
// the rigid drive: the stop cannot back-drive it) ends the impact without
// a rebound. The loss is the kinetic energy's drop (the stop does no work).
bool EndStopsElement::tied_impact(double t, double* y, const elements::ExactEndStop& stop) {
  const int n = model().coordinate_count();
  const Eigen::VectorXd& tangent = model().tangent_direction();
  const Eigen::VectorXd& mass = model().mass();
  CoordinateVector zero = CoordinateVector::Zero(n), unit = zero;
  unit[load_] = -stop.side;  // the stop pushes the load off its face
  CoordinateVector& vel = v();
  const double approach = stop.side * vel[load_];
  const double kinetic = 0.5 * vel.cwiseProduct(mass).dot(vel);
  double target = -stop.restitution * approach;
  if (std::abs(target) <= bounce_threshold()) target = 0.0;
  const double noise = 64.0 * std::numeric_limits<double>::epsilon() *
                       tangent.cwiseProduct(vel).cwiseAbs().sum();
  if (model().motor().speed_controlled && 2 >= n)
    throw SimulationError(t, "the rotor's prescribed speed drives the load, rigid in the thread, "
                             "into the exact " + stop.name + ": the speed and the rigid stop "
                             "both fix the drive's one degree of freedom, an infinite impulse",
                          "use a drive torque or a DC motor, end_stops.contact = \"penalty\" "
                          "(its stiffness bounds the force), or a flexible concept");
  double vn = approach;
  // (the normal velocity's round-off: compression ends within it)
  const double resolution = 1024.0 * std::numeric_limits<double>::epsilon() * approach;
  const bool friction = spec(1).friction != FrictionMode::none;
  bool held = false;
  const moreau_contacts::RotorMode rotor_before =
      rotor_train() ? rotor_mode() : moreau_contacts::RotorMode{};
  const int rotor = model().rotor();
  for (int segment = 0; segment < 16 && vn > target; ++segment) {
    const double slip = tangent.dot(vel);
    const Phase p = rotor_train() ? rotor_phase(unit, zero, slip, noise)
                                  : phase(unit, zero, slip, noise);
    const double dvn = stop.side * p.dv[load_];
    if (p.stuck && !(dvn < 0.0) && vn <= resolution) {
      held = true;  // the stuck thread holds the load at the face
      break;
    }
    if (!(dvn < 0.0))
      jam("the end stop's impulse through the thread does not slow the load (the phase's "
          "effective mass " + format_value(-1.0 / dvn) + " kg is not positive)");
    double dp = (target - vn) / dvn;
    const double ds = tangent.dot(p.dv);
    if (friction && !p.stuck && std::abs(slip) > noise && slip * ds < 0.0)
      dp = std::min(dp, -slip / ds);  // the slip ends: the next phase
    if (rotor_train() && rotor_mode().slip != 0 && vel[rotor] * p.dv[rotor] < 0.0)
      dp = std::min(dp, -vel[rotor] / p.dv[rotor]);  // the rotor stops: the next phase
    vel += dp * p.dv;
    vn = stop.side * vel[load_];
  }
  if (target == 0.0 || held) {
    // At rest at the face (the rebound below the bounce threshold, or
    // held): the load's round-off taken out along the frictionless
    // response, which keeps the constraints.
    const CoordinateVector dv0 = frictionless_response(unit);
    if (dv0[load_] != 0.0) vel -= (vel[load_] / dv0[load_]) * dv0;
    vel[load_] = 0.0;
    // The held load fixes every velocity (the rigid drive): all at rest.
    if (2 + model().motor().constraint_count() >= n) vel.setZero();
  }
  // (The rotor's mode after the impact: the driver's settle_rotor, from
  // the mode before it.)
  if (rotor_train()) rotor_mode() = rotor_before;
  const double after = 0.5 * vel.cwiseProduct(mass).dot(vel);
  if (after > kinetic * (1.0 + 1e-12))
    throw SimulationError(t, "the end stop's impact through the frictional thread would create "
                             "energy (" + format_value(after - kinetic) + " J)");
  impact_loss() += kinetic - after;
  onto_face(stop);
  layout().compress(q(), vel, y);
  set(t, y);
  vn = stop.side * v()[load_];
  return (target == 0.0 || held) && presses(stop);
}

}  // namespace

const ElementKind& end_stops_kind() {
  static const ElementKind kind{"end_stops", {{"stop_force", "N", Role::none}}, &declare};
  return kind;
}

std::unique_ptr<DriveHybrid::Element> make_end_stops_element(DriveHybrid& hybrid,
                                                             const DriveModel& model) {
  if (model.elements().end_stops().empty() && model.elements().exact_stops.empty())
    return nullptr;
  return std::make_unique<EndStopsElement>(hybrid, model);
}

}  // namespace leadscrew::model::drive
