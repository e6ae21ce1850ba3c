#include "leadscrew/model/drive_batch.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <iterator>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/parallel.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::model {

namespace {

// The loads a case may set, as constants (after the scalar fields).
struct LoadSetter {
  const char* name;
  void (*set)(DriveParameters&, double);
};
const LoadSetter kLoadSetters[] = {
    {"drive_torque", [](DriveParameters& p, double v) { p.drive_torque = ConstantExcitation{v}; }},
    {"drive_speed", [](DriveParameters& p, double v) { p.drive_speed = ConstantExcitation{v}; }},
    {"axial_force", [](DriveParameters& p, double v) { p.axial_force = ConstantExcitation{v}; }},
};

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "\"" : ", \"") + name + "\"";
  return out;
}

// The row of a case that did not run to its samples.
void fail_case(DriveBatchResult& result, Eigen::Index i, CaseFailure failure,
               const char* message) {
  result.samples.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
  result.failures[static_cast<std::size_t>(i)] = failure;
  result.messages[static_cast<std::size_t>(i)] = message;
  result.wall_time[i] = std::numeric_limits<double>::quiet_NaN();
}

// Index of each requested channel in a result (whose names depend on the
// model: the backlash channels exist only with backlash).
// Each requested channel's index in a result (SimulationResult::channel_index).
void find_channels(const std::vector<std::string>& requested,
                   const integrate::SimulationResult& run, std::vector<int>& index) {
  for (std::size_t c = 0; c < requested.size(); ++c) {
    index[c] = run.channel_index(requested[c]);
    if (index[c] < 0)
      throw InvalidArgument("channels entry \"" + requested[c] +
                            "\" is invalid: must be one of this model's channels " +
                            quoted_list(run.channel_names));
  }
}

// The elements' sections' numbers by attribute (element_section.hpp), after
// the scalar fields and the loads.
struct SectionAttribute {
  const SectionType* type;
  int field;
  const char* name;
};
const std::vector<SectionAttribute>& section_attributes() {
  static const std::vector<SectionAttribute> attributes = [] {
    std::vector<SectionAttribute> out;
    for (const SectionType& type : element_section_types())
      for (std::size_t i = 0; i < type.fields.size(); ++i)
        if (type.fields[i].kind == SectionField::Kind::number && type.fields[i].attribute)
          out.push_back({&type, static_cast<int>(i), type.fields[i].attribute});
    return out;
  }();
  return attributes;
}

// An override against the elements that drive the rotor in place of the
// loads (element_section.hpp, RotorDrive): the loads drive_torque and
// drive_speed are unused with one, its fields (by its prefix) without it.
void check_rotor_drive_override(const std::string& entry, const std::string& name,
                                const DriveParameters& base) {
  const SectionType* present = rotor_drive_section(base);
  if (present != nullptr && (name == "drive_torque" || name == "drive_speed"))
    throw InvalidArgument(entry + " = \"" + name + "\" is invalid for a drive with " +
                          present->rotor_drive->what +
                          ": the motor drives the rotor; vary its " +
                          present->rotor_drive->prefix + "* fields instead");
  for (const SectionType& type : element_section_types())
    if (type.rotor_drive != nullptr && &type != present &&
        name.rfind(type.rotor_drive->prefix, 0) == 0)
      throw InvalidArgument(entry + " = \"" + name + "\" is invalid for a drive without " +
                            type.rotor_drive->absent);
}

}  // namespace

std::string case_failure_name(CaseFailure failure) {
  static const char* const names[] = {"none", "invalid_argument", "simulation", "jamming",
                                      "other"};
  return names[static_cast<int>(failure)];
}

std::vector<std::string> DriveParameterOverrides::allowed_names() {
  std::vector<std::string> names;
  for (const ScalarField& field : scalar_fields()) names.emplace_back(field.name);
  for (const LoadSetter& load : kLoadSetters) names.emplace_back(load.name);
  for (const SectionAttribute& a : section_attributes()) names.emplace_back(a.name);
  return names;
}

DriveParameterOverrides::DriveParameterOverrides(const std::vector<std::string>& names,
                                                 const DriveParameters& base) {
  const std::vector<std::string> allowed = allowed_names();
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string entry = "parameters entry";
    const int index = require_choice(entry, names[k], allowed);
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(k), names[k]) !=
        names.begin() + static_cast<std::ptrdiff_t>(k))
      throw InvalidArgument(entry + " = \"" + names[k] +
                            "\" is invalid: must not repeat an earlier entry");
    // An element that drives the rotor (a DC motor) does so instead of
    // either load; its fields mean nothing without it.
    check_rotor_drive_override(entry, names[k], base);
    // The motor is either torque-driven or speed-controlled (the Scene's
    // loads.drive_torque / loads.drive_speed): the other load is unused.
    if ((names[k] == "drive_speed" && !base.speed_controlled) ||
        (names[k] == "drive_torque" && base.speed_controlled))
      throw InvalidArgument(entry + " = \"" + names[k] + "\" is invalid for a " +
                            (base.speed_controlled ? "speed-controlled" : "torque-driven") +
                            " drive: must be " +
                            (base.speed_controlled ? "\"drive_speed\"" : "\"drive_torque\"") +
                            " or another parameter");
    fields_.push_back(index);
  }
}

void DriveParameterOverrides::apply(const double* values, DriveParameters& p) const {
  const std::vector<ScalarField>& scalars = scalar_fields();
  for (std::size_t k = 0; k < fields_.size(); ++k) {
    const std::size_t index = static_cast<std::size_t>(fields_[k]);
    const std::size_t loads = std::size(kLoadSetters);
    const bool scalar = index < scalars.size();
    const bool load = !scalar && index < scalars.size() + loads;
    const SectionAttribute* section =
        scalar || load ? nullptr : &section_attributes()[index - scalars.size() - loads];
    // No parameter is infinite or NaN (DriveModel checks the ranges of some).
    if (!std::isfinite(values[k]))
      require_finite(scalar ? scalars[index].name
                            : load ? kLoadSetters[index - scalars.size()].name : section->name,
                     values[k]);
    if (scalar)
      p.*scalars[index].member = values[k];
    else if (load)
      kLoadSetters[index - scalars.size()].set(p, values[k]);
    else
      set_section_number(p, *section->type, section->field, values[k]);
  }
}

DriveBatch::DriveBatch(DriveParameters base, const std::vector<std::string>& parameters,
                       std::vector<std::string> channels, DriveSimulationOptions options)
    : base_(std::move(base)),
      overrides_(parameters, base_),
      channels_(std::move(channels)),
      options_(std::move(options)) {
  if (channels_.empty())
    throw InvalidArgument("channels = [] is invalid: must name at least one channel");
  if (options_.output.t_eval.empty())
    throw InvalidArgument("t_eval = [] is invalid: a batch samples its channels at given times");
  // Refused here what would fail every case alike (each case's simulate()
  // checks again: a scalar field may still change what fits, e.g. exact
  // backlash of zero clearance is the thread without play). Building the
  // base model checks the base parameters as well.
  check_simulation_options(DriveModel(base_), options_);
}

DriveBatchResult DriveBatch::run(const Eigen::Ref<const BatchValues>& values,
                                 int workers) const {
  if (values.cols() != overrides_.size())
    throw InvalidArgument("values has " + std::to_string(values.cols()) +
                          " columns: must have one per parameters entry (" +
                          std::to_string(overrides_.size()) + ")");
  if (workers < 1)
    throw InvalidArgument("workers = " + std::to_string(workers) +
                          " is invalid: must be an integer >= 1");
  DriveBatchResult result;
  const Eigen::Index cases = values.rows();
  result.channel_count = static_cast<int>(channels_.size());
  result.time_count = static_cast<int>(options_.output.t_eval.size());
  result.samples.resize(cases, result.channel_count * result.time_count);
  result.failures.assign(static_cast<std::size_t>(cases), CaseFailure::none);
  result.messages.assign(static_cast<std::size_t>(cases), std::string());
  result.wall_time.setZero(cases);

  const Eigen::Index threads = std::min<Eigen::Index>(workers, cases);
  if (threads <= 1) {  // the calling thread alone, row after row
    Workspace workspace{DriveParameters(), std::vector<int>(channels_.size())};
    for (Eigen::Index i = 0; i < cases; ++i) run_case(values, i, workspace, result);
    return result;
  }

  // Rows go to whichever thread is free (a shared counter, not fixed blocks):
  // a jamming or stiff case may cost a hundred cheap ones. Each thread writes
  // only the rows it took (distinct elements of the result, sized above), the
  // batch itself is read-only, and simulate() keeps its state (integrator,
  // SUNDIALS context, LCP workspace) per call, so the threads share nothing
  // mutable but the counter; run_in_parallel's return makes their rows visible
  // here.
  std::atomic<Eigen::Index> next_row{0};
  std::mutex error_mutex;
  std::exception_ptr error;  // what escaped a thread (run_case catches a case's own failures)
  auto work = [&]() noexcept {
    try {
      Workspace workspace{DriveParameters(), std::vector<int>(channels_.size())};
      for (Eigen::Index i = next_row.fetch_add(1, std::memory_order_relaxed); i < cases;
           i = next_row.fetch_add(1, std::memory_order_relaxed))
        run_case(values, i, workspace, result);
    } catch (...) {  // e.g. bad_alloc recording a failure: stop every thread, rethrow below
      next_row.store(cases, std::memory_order_relaxed);
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  // The calling thread is one of the workers; the others are the process's
  // helper threads (core/parallel.hpp): a sweep of 150 cheap cases is over in
  // a millisecond, of which starting and joining a std::thread per call took
  // a tenth on the 2-core test machine.
  run_in_parallel(static_cast<int>(threads), work);
  if (error) std::rethrow_exception(error);
  return result;
}

void DriveBatch::run_case(const Eigen::Ref<const BatchValues>& values, Eigen::Index i,
                          Workspace& workspace, DriveBatchResult& result) const {
  const std::vector<double>& times = options_.output.t_eval;
  DriveParameters& p = workspace.parameters;
  std::vector<int>& index = workspace.channel_index;
  try {
    p = base_;
    overrides_.apply(values.row(i).data(), p);
    const DriveModel model(std::move(p));  // p is reset from the base per case
    // An empty integrator is each case's default (simulate resolves it
    // from the model, which may resolve parameters: exact backlash of zero
    // play is the thread without play).
    const integrate::SimulationResult run = simulate(model, options_);
    find_channels(channels_, run, index);
    if (run.time.size() != times.size())
      throw std::logic_error("a simulation returned " + std::to_string(run.time.size()) +
                             " points for " + std::to_string(times.size()) +
                             " sample times");
    double* row = result.samples.row(i).data();
    for (std::size_t c = 0; c < channels_.size(); ++c) {
      run.copy_channel(static_cast<std::size_t>(index[c]), row + c * times.size());
    }
    result.wall_time[i] = run.stats.wall_time;
  } catch (const JammingError& e) {  // before its base class SimulationError
    fail_case(result, i, CaseFailure::jamming, e.what());
  } catch (const SimulationError& e) {
    fail_case(result, i, CaseFailure::simulation, e.what());
  } catch (const std::invalid_argument& e) {  // InvalidArgument too
    fail_case(result, i, CaseFailure::invalid_argument, e.what());
  } catch (const std::exception& e) {  // a case never ends the batch
    fail_case(result, i, CaseFailure::other, e.what());
  }
}

}  // namespace leadscrew::model
