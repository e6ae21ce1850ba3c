// DriveHybrid (hybrid.hpp): the penalty end stops of the load's travel
// (elements/end_stop.hpp). Their force enters the forces through
// DriveDynamics (a force element); here are their roots, one per stop: its
// contact margin, which rises through 0 where the stop starts to push (the
// load reaches its face: a jump of c d') and falls through 0 where it
// releases (a kink), so that the integrator stops at either.
#include "hybrid.hpp"

namespace leadscrew::model::drive {

void DriveHybrid::end_stop_roots(double* g) const {
  const int load = model_.load();
  int k = end_stop_root();
  for (const elements::EndStop& stop : model_.elements().end_stops())
    g[k++] = stop.contact_margin(q_[load], v_[load]);
}

void DriveHybrid::end_stop_directions(int* directions) const {
  // A stop that does not push starts to (rising); one that pushes releases
  // (falling). The other crossing is the located root's round-off.
  const std::size_t count = model_.elements().end_stops().size();
  int k = end_stop_root();
  for (std::size_t i = 0; i < count; ++i)
    directions[k++] = i < stop_pushing_.size() && stop_pushing_[i] ? -1 : 1;
}

void DriveHybrid::start_end_stops() {
  const auto& stops = model_.elements().end_stops();
  stop_pushing_.assign(stops.size(), 0);
  const int load = model_.load();
  for (std::size_t i = 0; i < stops.size(); ++i)
    stop_pushing_[i] = stops[i].contact_margin(q_[load], v_[load]) > 0.0;
}

std::string DriveHybrid::change_end_stops(const std::vector<int>& root_info) {
  std::string kind;
  const auto& stops = model_.elements().end_stops();
  stop_pushing_.resize(stops.size(), 0);
  for (std::size_t i = 0; i < stops.size(); ++i) {
    const int info = root_info[static_cast<std::size_t>(end_stop_root()) + i];
    if (info == 0) continue;
    stop_pushing_[i] = info > 0;
    kind += (kind.empty() ? "" : ", ") + stops[i].name + (info > 0 ? " contact" : " release");
  }
  return kind;
}

}  // namespace leadscrew::model::drive
