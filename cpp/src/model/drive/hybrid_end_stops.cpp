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
// Exact stops (on a load that no constraint ties to other coordinates): one
// root per stop, its gap while free (an impact where it falls to 0: Newton's
// law u'+ = -e u'-, or the contact closes where the rebound is below the
// bounce threshold and the forces press the load on), and while closed the
// reaction that holds the load at the face (it opens where that falls to 0).
#include <cmath>

#include "driver_element.hpp"

namespace leadscrew::model::drive {

const ElementKind& end_stops_kind();

namespace {

void declare(const DriveModel& model, bool bristle, Declaration& d) {
  (void)bristle;
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
      g[k++] = closed ? exact_[i].side * dynamics().forces()[load_] : exact_[i].gap(q()[load_]);
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
    // at a face and the forces still press it there.
    closed_.assign(exact_.size(), 0);
    for (std::size_t i = 0; i < exact_.size(); ++i)
      closed_[i] = exact_[i].gap(q()[load_]) <= 0.0 && v()[load_] == 0.0 &&
                   exact_[i].side * dynamics().forces()[load_] >= 0.0;
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
          q()[load_] = stop.position;
          layout().compress(q(), v(), y);
        }
        continue;
      }
      const double mass = model().mass()[load_];
      double after = -stop.restitution * approach;
      q()[load_] = stop.position;  // the root's round-off onto the face
      // A rebound below the bounce threshold closes the contact where the
      // forces press the load on (else it leaves at that speed).
      const bool close = std::abs(after) <= bounce_threshold() &&
                         stop.side * dynamics().forces()[load_] >= 0.0;
      if (close) after = 0.0;
      v()[load_] = after;
      impact_loss() += 0.5 * mass * (approach * approach - after * after);
      layout().compress(q(), v(), y);
      closed_[i] = close;
      kind = joined(kind, stop.name + (close ? " impact, closed" : " impact"));
    }
    return {kind, true};
  }

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
        state.values[first_channel()] = -dynamics().forces()[load_];
        return;
      }
  }

 private:
  const std::vector<elements::EndStop>& stops_;
  const std::vector<elements::ExactEndStop>& exact_;
  int load_;
  std::vector<char> pushing_;  // per penalty stop: it pushes (its root's direction)
  std::vector<char> closed_;   // per exact stop: closed (the load held at its face)
};

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
