// Moreau-Jean time stepping: fixed steps on the velocity level, the theta
// method for the smooth forces, and one LCP per step for the contact and
// friction impulses. First order; robust when events pile up (backlash with
// many impacts), never needs to locate an event.
#pragma once

#include <string>
#include <vector>

#include "leadscrew/integrate/simulation_result.hpp"
#include <Eigen/Core>

namespace leadscrew::integrate {

class TimeSteppingSystem {
 public:
  virtual ~TimeSteppingSystem() = default;
  virtual int size() const = 0;
  // One Moreau-Jean step from (t, y) over h with parameter theta in [0, 1]:
  // writes y_next. Must not allocate.
  virtual void step(double t, double h, double theta, const double* y, double* y_next) = 0;
  virtual const std::vector<std::string>& channel_names() const = 0;
  // Channels of the last step ending at (t, y): a function of them alone
  // (simulate_moreau calls it only after the steps whose end a row reads).
  virtual void channels(double t, const double* y, double* out) = 0;
  virtual long lcp_solves() const { return 0; }
};

struct MoreauOptions {
  double dt = 1e-3;
  double theta = 0.5;
  long max_steps = 1000000;  // as IntegratorOptions: the steps t_end / dt may take
};

// The checks simulate_moreau makes of its options for a run over `span`
// (t_end - t0 >= 0) before it steps: dt > 0, theta in [0, 1], max_steps >= 1
// and at most max_steps steps. Returns the step count (the last step
// shortened to land on t_end). Throws InvalidArgument naming the option.
long check_moreau_options(double span, const MoreauOptions& options);

// Steps of exactly dt (the last one shortened to land on t_end). Output at
// every step, or at t_eval by linear interpolation of the step ends (the
// scheme's own first-order accuracy).
SimulationResult simulate_moreau(TimeSteppingSystem& system, double t0,
                                 const Eigen::Ref<const Eigen::VectorXd>& y0,
                                 const OutputRequest& output, const MoreauOptions& options);

}  // namespace leadscrew::integrate
