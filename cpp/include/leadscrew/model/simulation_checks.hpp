// Options that would make a simulation's answer meaningless, refused before
// it runs (InvalidArgument naming the option, its value, the valid range and
// why): the drive's and the friction block's simulate() both check them.
#pragma once

#include <initializer_list>

#include "leadscrew/excitation/excitation.hpp"
#include "leadscrew/integrate/ode.hpp"

namespace leadscrew::model {

// The loosest tolerances that still bound an answer. rtol: beyond 1e-3 the
// global error, which accumulates over the steps, is no longer small (at
// rtol 0.5 a drive's load travel came out with the wrong sign); atol [m,
// rad, m/s, rad/s, J]: above 1e-3 the error allowed in a position exceeds
// a lead screw's play and pitch; below 1e-100 the error weights 1 / atol
// overflow when squared, and the solver's norms became NaN.
constexpr double kLoosestRelativeTolerance = 1e-3;
constexpr double kLoosestAbsoluteTolerance = 1e-3;
constexpr double kTightestAbsoluteTolerance = 1e-100;
// Also the step controls over a run of t_end: a max_step that needs more
// than max_steps steps to reach t_end (5e-324 s ended in a NaN time), and a
// first_step below the time's resolution (64 ulp of t_end).
void check_meaningful_tolerances(const integrate::IntegratorOptions& options, double t_end);

// A Moreau-Jean step must fit the run (dt <= t_end: a longer step sampled a
// 50 N sine once, at 1e-16 N) and resolve the loads: at least four steps per
// period of every sine load (fewer cannot show its sign changes: the step
// samples the load once, at t + theta dt).
void check_step_resolves_loads(double dt, double t_end,
                               std::initializer_list<const Excitation*> loads);

}  // namespace leadscrew::model
