// DriveHybrid (hybrid.hpp): the end stops of the load's travel
// (elements/end_stop.hpp; docs/physics/end_stops.md).
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

#include "hybrid.hpp"

namespace leadscrew::model::drive {

namespace {

std::string joined(const std::string& a, const std::string& b) {
  return a.empty() ? b : a + ", " + b;
}

}  // namespace

void DriveHybrid::end_stop_roots(double* g) const {
  const int load = model_.load();
  int k = end_stop_root();
  for (const elements::EndStop& stop : model_.elements().end_stops())
    g[k++] = stop.contact_margin(q_[load], v_[load]);
  const auto& exact = model_.elements().exact_stops;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const bool closed = i < stop_closed_.size() && stop_closed_[i];
    // The reaction side F_load that holds the load at the face (the forces
    // on the load press it on while > 0).
    g[k++] = closed ? exact[i].side * dynamics_.forces()[load] : exact[i].gap(q_[load]);
  }
}

void DriveHybrid::end_stop_directions(int* directions) const {
  // A penalty stop that does not push starts to (rising); one that pushes
  // releases (falling). The other crossing is the located root's round-off.
  // An exact stop's gap and reaction both end their state falling.
  const std::size_t count = model_.elements().end_stops().size();
  int k = end_stop_root();
  for (std::size_t i = 0; i < count; ++i)
    directions[k++] = i < stop_pushing_.size() && stop_pushing_[i] ? -1 : 1;
  for (std::size_t i = 0; i < model_.elements().exact_stops.size(); ++i) directions[k++] = -1;
}

void DriveHybrid::start_end_stops() {
  const auto& stops = model_.elements().end_stops();
  stop_pushing_.assign(stops.size(), 0);
  const int load = model_.load();
  for (std::size_t i = 0; i < stops.size(); ++i)
    stop_pushing_[i] = stops[i].contact_margin(q_[load], v_[load]) > 0.0;
  // The scene starts the load between the stops; a resumed run (the stepper's
  // next piece) starts closed where the last left the load held at a face
  // and the forces still press it there.
  const auto& exact = model_.elements().exact_stops;
  stop_closed_.assign(exact.size(), 0);
  for (std::size_t i = 0; i < exact.size(); ++i)
    stop_closed_[i] = exact[i].gap(q_[load]) <= 0.0 && v_[load] == 0.0 &&
                      exact[i].side * dynamics_.forces()[load] >= 0.0;
}

std::string DriveHybrid::change_end_stops(double t, double* y,
                                          const std::vector<int>& root_info) {
  std::string kind;
  const auto& stops = model_.elements().end_stops();
  stop_pushing_.resize(stops.size(), 0);
  const std::size_t first = static_cast<std::size_t>(end_stop_root());
  for (std::size_t i = 0; i < stops.size(); ++i) {
    const int info = root_info[first + i];
    if (info == 0) continue;
    stop_pushing_[i] = info > 0;
    kind = joined(kind, stops[i].name + (info > 0 ? " contact" : " release"));
  }
  const auto& exact = model_.elements().exact_stops;
  stop_closed_.resize(exact.size(), 0);
  const int load = model_.load();
  for (std::size_t i = 0; i < exact.size(); ++i) {
    if (root_info[first + stops.size() + i] >= 0) continue;  // (falling only)
    const elements::ExactEndStop& stop = exact[i];
    set(t, y);
    if (stop_closed_[i]) {
      stop_closed_[i] = 0;
      kind = joined(kind, stop.name + " opens");
      continue;
    }
    const double approach = v_[load];
    if (stop.side * approach < 0.0) continue;  // leaving: no impact (round-off of the gap)
    const double mass = model_.mass()[load];
    double after = -stop.restitution * approach;
    q_[load] = stop.position;  // the root's round-off onto the face
    // A rebound below the bounce threshold closes the contact where the
    // forces press the load on (else it leaves at that speed).
    const bool close = std::abs(after) <= bounce_threshold_ &&
                       stop.side * dynamics_.forces()[load] >= 0.0;
    if (close) after = 0.0;
    v_[load] = after;
    impact_loss_ += 0.5 * mass * (approach * approach - after * after);
    layout_.compress(q_, v_, y);
    stop_closed_[i] = close;
    kind = joined(kind, stop.name + (close ? " impact, closed" : " impact"));
  }
  return kind;
}

void DriveHybrid::hold_closed_stops(double* ydot) const {
  const int load = model_.load();
  for (std::size_t i = 0; i < stop_closed_.size(); ++i) {
    if (!stop_closed_[i]) continue;
    const int np = static_cast<int>(layout_.positions().size());
    for (int k = 0; k < np; ++k)
      if (layout_.positions()[k] == load) ydot[k] = 0.0;
    for (std::size_t k = 0; k < layout_.velocities().size(); ++k)
      if (layout_.velocities()[k] == load) ydot[np + static_cast<int>(k)] = 0.0;
  }
}

double DriveHybrid::exact_stop_force() const {
  // A closed stop balances the forces on the held load.
  for (std::size_t i = 0; i < stop_closed_.size(); ++i)
    if (stop_closed_[i]) return -dynamics_.forces()[model_.load()];
  return 0.0;
}

}  // namespace leadscrew::model::drive
