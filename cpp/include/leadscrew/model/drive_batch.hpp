// A batch of drive simulations that differ only in a few scalar parameters
// (one row of a parameter sweep per case), each reduced in C++ to the values
// of some output channels at a few sample times.
//
// A study's sweep calls this once per chunk of cases: the per-case work (the
// parameter edit, the model assembly, the simulation, picking out the
// samples) stays in C++, so that the Python around it is per chunk. The batch
// may also spread its rows over its own threads (run's `workers`): then the
// thread pool stays in C++ and a sweep of microsecond cases is one call. A
// case that fails becomes a failure entry of its row; the other cases run on.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_simulation.hpp"

namespace leadscrew::model {

// Setters of the scalar DriveParameters a batch may vary, by the names of the
// fields (the binding's DriveParameters attributes): every double field, and
// the loads drive_torque, drive_speed and axial_force as constants. The values
// go in unchanged: a field the Scene derives from others (e.g. a damping from
// a stiffness) does not follow, so a sweep varies only fields that are inputs.
class DriveParameterOverrides {
 public:
  // InvalidArgument naming an unknown or repeated name (and the allowed ones),
  // or a load the base cannot take (drive_speed on a torque-driven base,
  // drive_torque on a speed-controlled one).
  DriveParameterOverrides(const std::vector<std::string>& names, const DriveParameters& base);

  int size() const noexcept { return static_cast<int>(fields_.size()); }
  // Sets one value per name, in the order of the names; InvalidArgument
  // naming the field for a value that is not finite.
  void apply(const double* values, DriveParameters& p) const;

  // Every name the constructor accepts.
  static std::vector<std::string> allowed_names();

 private:
  std::vector<int> fields_;  // into allowed_names()
};

// How a case failed; the bindings name the matching Python exception.
enum class CaseFailure {
  none,
  invalid_argument,  // InvalidArgument or std::invalid_argument (ValueError)
  simulation,        // SimulationError
  jamming,           // JammingError
  other,             // any other std::exception (RuntimeError)
};
// "none", "invalid_argument", "simulation", "jamming", "other"
std::string case_failure_name(CaseFailure failure);

struct DriveBatchResult {
  int channel_count = 0;
  int time_count = 0;
  // samples(i, c * time_count + k): channel c at sample time k in case i;
  // NaN throughout a failed case's row (its failure says why).
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> samples;
  std::vector<CaseFailure> failures;  // one per case
  std::vector<std::string> messages;  // what() of the failure, "" where none
  Eigen::VectorXd wall_time;          // [s] each simulation's own clock, NaN where it failed

  // Cases that failed (a sweep mostly has none: then it need not look at
  // the failures one by one).
  int failure_count() const noexcept {
    return static_cast<int>(failures.size() - static_cast<std::size_t>(std::count(
                                                  failures.begin(), failures.end(),
                                                  CaseFailure::none)));
  }
};

using BatchValues = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A batch request (immutable, like a DriveModel): the base parameters, which
// of them each case sets, the channels to sample and the simulation options,
// checked once; run() may be called from several threads at once, and runs
// its rows on several threads itself when asked.
class DriveBatch {
 public:
  // options.output.t_eval are the sample times (required, non-empty: with
  // them every result has one point per sample time). An empty
  // options.integrator takes each case's default (drive_integrators(...)[0]),
  // as leadscrew.simulate does. InvalidArgument for a bad request: parameter
  // names (see DriveParameterOverrides), no channel, no sample time.
  DriveBatch(DriveParameters base, const std::vector<std::string>& parameters,
             std::vector<std::string> channels, DriveSimulationOptions options);

  // Simulates one case per row of `values` (one column per parameter name)
  // from the base with those fields set, and samples the channels. Throws
  // InvalidArgument if `values` has the wrong width or `workers` < 1; a case
  // that fails (its parameters, an unknown channel, the simulation) only sets
  // its row's failure.
  //
  // workers: threads that simulate the rows, >= 1, capped at the row count.
  // 1 runs every row on the calling thread; w > 1 runs the calling thread and
  // w - 1 helper threads (run_in_parallel, core/parallel.hpp: kept asleep
  // between calls), each taking the next row from a shared counter (cheap and
  // expensive cases balance). Each row's result depends only on that row:
  // the result is bit-for-bit the same for every worker count (only the
  // message of an exception from a CallableExcitation may describe the
  // thread that called it, e.g. a Python traceback).
  DriveBatchResult run(const Eigen::Ref<const BatchValues>& values, int workers = 1) const;

  int parameter_count() const noexcept { return overrides_.size(); }
  const std::vector<std::string>& channels() const noexcept { return channels_; }

 private:
  // What one thread of run() reuses from case to case.
  struct Workspace {
    DriveParameters parameters;  // copied from the base, then the overrides set
    std::vector<int> channel_index;
  };
  // Simulates row i into result's row i (and only that row), or records its
  // failure there.
  void run_case(const Eigen::Ref<const BatchValues>& values, Eigen::Index i,
                Workspace& workspace, DriveBatchResult& result) const;

  DriveParameters base_;
  DriveParameterOverrides overrides_;
  std::vector<std::string> channels_;
  DriveSimulationOptions options_;
};

}  // namespace leadscrew::model
