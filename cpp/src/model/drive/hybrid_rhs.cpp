// DriveHybrid (hybrid.hpp): construction (the elements with events, the mode
// solver), the right-hand side of the current mode and the output rows (by
// its mode solver, mode_solver.hpp), the loads' breakpoints and time scales.
#include "hybrid.hpp"

#include "channels.hpp"
#include "driver_element.hpp"
#include "mode_solver.hpp"

namespace leadscrew::model::drive {

DriveHybrid::DriveHybrid(const DriveModel& model, const friction::Law& law,
                         double bounce_threshold, double t_end,
                         const integrate::IntegratorOptions& integrator_options)
    : model_(model),
      p_(model.parameters()),
      dynamics_(model, &law),
      layout_(model, law),
      bristle_state_(layout_.find_state("bristle_share")),
      bristle_range_(law.bristle_range()),
      bounce_threshold_(bounce_threshold),
      backlash_(!model.bilateral_thread()),
      t_end_(t_end),
      integrator_options_(integrator_options) {
  const int n = model.coordinate_count();
  q_.setZero(n);
  v_.setZero(n);
  names_ = drive_channel_names(layout_);
  saved_state_.resize(static_cast<std::size_t>(layout_.size()));
  dynamics_.set_element_slots(layout_.element_slots());
  make_elements();
  solver_ = make_mode_solver(*this);
}

DriveHybrid::~DriveHybrid() = default;

// The elements with events (driver_element.hpp), from the registry
// (element_registry.cpp), in its order; each numbers its roots after the
// thread's g0..g4 and the elements' before it.
void DriveHybrid::make_elements() {
  const std::vector<ElementFactory>& factories = element_factories();
  for (std::size_t kind = 0; kind < factories.size(); ++kind)
    if (factories[kind]) add_element(factories[kind](*this, model_), static_cast<int>(kind));
  // The sections' elements behind the element interface (their kinds follow
  // the registry's: element_kinds()).
  for (const Declaration& d : layout_.declarations())
    if (d.kind >= static_cast<int>(factories.size()) && d.element >= 0)
      add_element(make_model_element(*this, model_, static_cast<std::size_t>(d.element)), d.kind);
}

void DriveHybrid::add_element(std::unique_ptr<Element> element, int kind) {
  if (!element) return;  // the model has none of that kind
  const Declaration* declared = layout_.declaration(kind);
  element->set_slots(root_count_, declared ? declared->first_state : -1,
                     declared ? declared->first_channel : -1);
  root_count_ += element->root_count();
  elements_.push_back(std::move(element));
}

void DriveHybrid::rhs(double t, const double* y, double* ydot) { solver_->rhs(t, y, ydot); }

void DriveHybrid::channels(double t, const double* y, double* out) {
  ContactForces forces;
  forces.stick = mode_.friction == FrictionMode::stick;
  const ChannelState state = solver_->output(t, y, forces);
  write_drive_channels(layout_, state, forces, y + layout_.energy_offset(), impact_loss_,
                       kinetic0_, stored0_, out);
}

std::vector<double> DriveHybrid::breakpoints() const {
  std::vector<double> times = p_.axial_force.breakpoints();
  const Excitation& drive = rotor_drive(p_);  // (a DC motor's voltage, the speed, the torque)
  times.insert(times.end(), drive.breakpoints().begin(), drive.breakpoints().end());
  for (const Excitation* base : {&p_.base_acceleration, &p_.base_angular_acceleration})
    times.insert(times.end(), base->breakpoints().begin(), base->breakpoints().end());
  return times;
}

double DriveHybrid::max_step_hint() const {
  const Excitation& drive = rotor_drive(p_);  // (a DC motor's voltage, the speed, the torque)
  return integrate::max_step_from_time_scales(
      {drive.time_scale(), p_.axial_force.time_scale(), p_.base_acceleration.time_scale(),
       p_.base_angular_acceleration.time_scale()});
}

}  // namespace leadscrew::model::drive
