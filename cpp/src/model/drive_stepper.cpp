// DriveStepper (model/drive_stepper.hpp): simulate()'s event-driven run
// (integrate::EventDrivenRun over drive::DriveHybrid) advanced in pieces.
#include "leadscrew/model/drive_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "drive/hybrid.hpp"
#include "drive/integrators.hpp"
#include "drive/run_setup.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/model/elements/train_friction.hpp"

namespace leadscrew::model {

// A drive under one set of loads: its model, the law that runs, its hybrid
// system. Replaced when an input changes; the run goes on from its state.
struct DriveStepper::System {
  std::unique_ptr<DriveModel> model;
  std::unique_ptr<friction::Law> regularization;
  const friction::Law* law = nullptr;
  std::unique_ptr<drive::DriveHybrid> hybrid;
};

namespace {

// A load that is the constant `value` already (nothing to restart for).
bool constant_at(const Excitation& load, double t, double value) {
  return std::isinf(load.time_scale()) && load.breakpoints().empty() && load(t) == value;
}

// Whether `load` holds `value` from t on (a constant, or a table past its
// last time): a prescribed speed already there needs no ramp.
bool held_from(const Excitation& load, double t, double value) {
  if (constant_at(load, t, value)) return true;
  const std::vector<double> times = load.breakpoints();
  return load.definition().kind == "table" && !times.empty() && times.back() <= t &&
         load(t) == value;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "\"" : ", \"") + name + "\"";
  return out;
}

}  // namespace

DriveStepper::DriveStepper(DriveParameters parameters, DriveSimulationOptions options)
    : parameters_(std::move(parameters)), current_(parameters_), options_(std::move(options)) {
  if (const SectionType* type = rotor_drive_section(parameters_)) {
    for (const SectionInput& input : type->inputs) element_inputs_.emplace_back(input.name);
    element_inputs_.emplace_back("axial_force");
  }
  // The output request is the stepper's own; simulate()'s checks of the
  // options need a run length, which a stepper does not have.
  options_.output = integrate::OutputRequest{};
  options_.output.t_end = 1.0;
  {
    const DriveModel model(parameters_);  // validates the parameters
    integrator_ = drive::chosen_integrator(model, options_);
    // FMU export and the C API (this stepper's users) run the event-driven
    // scheme or an ODE method, not Moreau-Jean's time stepping.
    const std::vector<std::string>& allowed = drive::model_integrators(model);
    std::vector<std::string> others;
    for (const std::string& name : allowed)
      if (name != "moreau") others.push_back(name);
    // Moreau-Jean the default, another scheme beside (the train's stages
    // behind a prescribed rotor speed): the stepper takes that one.
    if (options_.integrator.empty() && integrator_ == "moreau" && !others.empty())
      integrator_ = options_.integrator = others.front();
    if (integrator_ == "moreau" &&
        std::find(allowed.begin(), allowed.end(), integrator_) != allowed.end()) {
      if (others.empty()) {  // Moreau-Jean alone: the train's stages elsewhere
        const elements::TrainFriction* train = model.train_friction();
        throw InvalidArgument(
            "this scene runs only on Moreau-Jean time stepping (integrator = \"moreau\")" +
            (train ? std::string(train->stage ? ": its gear stage (gear.type = \"" +
                                                    gear_type_name(parameters_.gear) + "\")"
                                              : ": its motor friction (motor.friction_torque)") +
                         " with " + train->event_driven_obstacle + " runs on nothing else"
                   : std::string()) +
            "; FMU export and the C API do not offer Moreau-Jean: they take a scene the "
            "event-driven scheme runs (the train's stages where the rotor's friction "
            "contact takes them, e.g. the shipped scene \"seat_adjuster_worm\"; "
            "docs/physics/gear.md lists where)");
      }
      throw InvalidArgument("integrator = \"moreau\" is invalid for FMU export and the C API, "
                            "which do not offer Moreau-Jean time stepping: leave integrator out "
                            "(here \"" + others.front() + "\") or choose one of " +
                            quoted_list(others));
    }
    check_simulation_options(model, options_);
  }
  reset();
}

DriveStepper::~DriveStepper() = default;

std::unique_ptr<DriveStepper::System> DriveStepper::make_system() const {
  auto system = std::make_unique<System>();
  system->model = std::make_unique<DriveModel>(current_);
  system->law = &drive::running_law(*system->model, integrator_, system->regularization);
  // The horizon (t_end) grows with each advance (DriveHybrid::extend_horizon).
  system->hybrid = std::make_unique<drive::DriveHybrid>(
      *system->model, *system->law, options_.bounce_threshold, 0.0, options_.integrator_options);
  return system;
}

void DriveStepper::reset() {
  current_ = parameters_;
  start_run();
}

void DriveStepper::start_run() {
  run_.reset();
  system_ = make_system();
  const drive::StateLayout layout = drive::state_layout(*system_->model, *system_->law);
  const Eigen::VectorXd y0 = drive::initial_vector(*system_->model, layout);
  const integrate::EventDrivenOptions driver =
      drive::event_driven_options(*system_->model, *system_->law, integrator_, options_);
  speed_pending_ = false;
  ramp_end_ = std::numeric_limits<double>::infinity();
  advanced_ = false;
  record_ = integrate::SimulationResult{};
  record_.channel_names = system_->hybrid->channel_names();
  record_.integrator = integrator_;
  record_.friction = current_.friction;
  row_.assign(record_.channel_count(), 0.0);
  failure_.clear();
  failure_time_ = 0.0;
  run_ = std::make_unique<integrate::EventDrivenRun>(*system_->hybrid, 0.0, y0, driver);
}

double DriveStepper::time() const noexcept { return run_->time(); }

const std::vector<std::string>& DriveStepper::input_names() const {
  static const std::vector<std::string> torque = {"drive_torque", "axial_force"};
  static const std::vector<std::string> speed = {"drive_speed", "axial_force"};
  if (!element_inputs_.empty()) return element_inputs_;
  return parameters_.speed_controlled ? speed : torque;
}

double DriveStepper::input(const std::string& name) const {
  const std::vector<std::string>& names = input_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw InvalidArgument("input = \"" + name + "\" is invalid: must be one of " +
                          quoted_list(names));
  const double t = time();
  if (name == "axial_force") return current_.axial_force(t);
  if (const Excitation* own = find_section_input(current_, name))
    return (*own)(t);
  if (name == "drive_speed") return speed_pending_ ? speed_target_ : current_.drive_speed(t);
  return current_.drive_torque(t);
}

Excitation& DriveStepper::load_of(const std::string& name) {
  if (name == "axial_force") return current_.axial_force;
  if (Excitation* own = find_section_input(current_, name)) return *own;
  return current_.drive_torque;
}

void DriveStepper::set_input(const std::string& name, double value) {
  input(name);  // the name
  require_finite(name, value);
  if (!failure_.empty())
    throw SimulationError(failure_time_, "the stepper stopped at its failure: " + failure_,
                          "reset() starts it again");
  if (name == "drive_speed") {
    if (!advanced_) {  // before the first advance: the speed the drive starts at
      current_.drive_speed = Excitation(ConstantExcitation{value});
      start_run();
      return;
    }
    speed_pending_ = true;  // (its ramp starts at the next advance)
    speed_target_ = value;
    return;
  }
  Excitation& load = load_of(name);
  if (constant_at(load, time(), value)) return;
  load = Excitation(ConstantExcitation{value});
  restart_with_current_loads();
}

void DriveStepper::restart_with_current_loads() {
  const double t = time();
  try {
    std::unique_ptr<System> next = make_system();
    next->hybrid->resume(*system_->hybrid, t, run_->state().data());
    run_->restart(*next->hybrid);
    system_ = std::move(next);
  } catch (const std::exception& e) {
    failure_ = e.what();
    failure_time_ = t;
    throw;
  }
}

void DriveStepper::advance(double t) {
  if (!std::isfinite(t))
    throw InvalidArgument("t = " + format_value(t) + " is invalid: must be a finite time [s]");
  if (!failure_.empty())
    throw SimulationError(failure_time_, "the stepper stopped at its failure: " + failure_,
                          "reset() starts it again");
  const double now = time();
  if (t < now)
    throw InvalidArgument("t = " + format_value(t) + " is invalid: must be >= the stepper's time " +
                          format_value(now) + " s (reset() goes back to 0)");
  if (t == now) return;
  if (speed_pending_ || ramp_end_ <= now) {
    // The prescribed speed ramps from its value now to the target at t
    // (continuous: a finite acceleration, the motor's torque finite).
    bool changed = false;
    if (ramp_end_ <= now) {  // the last ramp has ended: its speed holds from here
      current_.drive_speed = Excitation(ConstantExcitation{ramp_target_});
      ramp_end_ = std::numeric_limits<double>::infinity();
      changed = true;
    }
    if (speed_pending_ && !held_from(current_.drive_speed, now, speed_target_)) {
      // Reached at t; the table runs on at the ramp's slope one piece
      // beyond, so that the channels at t are the ramp's (its acceleration:
      // the left limit), not those of the hold the next advance starts.
      const double from = current_.drive_speed(now);
      current_.drive_speed = Excitation(TableExcitation{
          {now, t, 2.0 * t - now}, {from, speed_target_, 2.0 * speed_target_ - from}});
      ramp_end_ = t;
      ramp_target_ = speed_target_;
      changed = true;
    }
    speed_pending_ = false;
    if (changed) restart_with_current_loads();
  }
  advanced_ = true;
  integrate::OutputRequest output;
  output.t_end = t;
  output.t_eval = {t};
  record_.time.clear();
  record_.values.clear();
  try {
    system_->hybrid->extend_horizon(now, run_->state().data(), t);
    run_->advance(output, record_);
  } catch (const SimulationError& e) {
    failure_ = e.reason();  // (its time is failure_time_: what() would repeat it)
    failure_time_ = e.time();
    throw;
  } catch (const std::exception& e) {
    failure_ = e.what();
    failure_time_ = time();
    throw;
  }
}

const std::vector<std::string>& DriveStepper::channel_names() const {
  return record_.channel_names;
}

std::vector<double> DriveStepper::channels() {
  system_->hybrid->channels(time(), run_->state().data(), row_.data());
  return row_;
}

double DriveStepper::channel(const std::string& name) {
  const int k = record_.channel_index(name);
  if (k < 0)
    throw InvalidArgument("channel = \"" + name + "\" is invalid: must be one of " +
                          quoted_list(record_.channel_names));
  system_->hybrid->channels(time(), run_->state().data(), row_.data());
  return row_[static_cast<std::size_t>(k)];
}

const std::vector<integrate::Event>& DriveStepper::events() const { return record_.events; }

integrate::SimulationStats DriveStepper::stats() const {
  integrate::SimulationResult counts;
  run_->fill_stats(counts);
  return counts.stats;
}

}  // namespace leadscrew::model
