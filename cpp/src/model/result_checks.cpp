#include "leadscrew/model/result_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "leadscrew/friction/law.hpp"
#include "check_rows.hpp"

namespace leadscrew::model {

namespace {

using check_rows::make_check;
using check_rows::Worst;

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// The checks' working memory [doubles]: kept by the thread between runs up
// to kKeptScratch (512 KB), beyond that the run's own. (Freed after every
// run, a buffer at the heap's top let glibc trim the heap and the next run
// fault its pages in again: the friction block's checks took 20-30 % of its
// call's time for 8 % of its instructions; issue 17's benchmark.)
class ScratchBuffer {
 public:
  explicit ScratchBuffer(std::size_t size) {
    static constexpr std::size_t kKeptScratch = std::size_t{1} << 16;
    thread_local std::vector<double> kept;
    std::vector<double>& buffer = size <= kKeptScratch ? kept : own_;
    if (buffer.size() < size) buffer.resize(size);
    data_ = buffer.data();
  }
  double* data() { return data_; }

 private:
  std::vector<double> own_;
  double* data_ = nullptr;
};

// Whether every value is finite. v - v is 0 for a finite v and NaN for an
// infinite or NaN one; four independent sums of it vectorize. (Measured on
// the friction block's 1,300 values: 1.1k instructions against 5.3k for a
// loop of std::isfinite and 7k for Eigen's allFinite, which does not
// vectorize its all(); issue 17's benchmark.)
bool all_finite(const double* values, std::size_t count) {
  double sums[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t i = 0;
  for (; i + 4 <= count; i += 4)
    for (std::size_t k = 0; k < 4; ++k) sums[k] += values[i + k] - values[i + k];
  for (; i < count; ++i) sums[0] += values[i] - values[i];
  return sums[0] == 0.0 && sums[1] == 0.0 && sums[2] == 0.0 && sums[3] == 0.0;
}

}  // namespace

void check_result(const ResultCheckSpec& spec, integrate::SimulationResult& result) {
  // The channels in columns, the run's scales (largest forces, energies,
  // slip), then every pointwise check.
  std::vector<integrate::InvariantCheck>& checks = result.checks;
  checks.clear();
  checks.reserve(11);  // (with check_bristle_bound's two)
  const std::size_t n = result.point_count();
  const std::size_t channels = result.channel_count();

  // finite: every value and time (one flat loop; the row only on failure).
  {
    integrate::InvariantCheck c =
        make_check("finite", "every channel and output time is a finite number", "");
    const bool finite = all_finite(result.time.data(), n) &&
                        all_finite(result.values.data(), result.values.size());
    for (std::size_t i = 0; i < n && !finite; ++i) {
      bool ok = std::isfinite(result.time[i]);
      for (std::size_t k = 0; k < channels && ok; ++k)
        ok = std::isfinite(result.values[i * channels + k]);
      if (!ok) {
        c.passed = false;
        c.value = 1.0;
        c.time = std::isfinite(result.time[i]) ? result.time[i] : 0.0;
        c.bound = static_cast<double>(i);  // the output point (value 1: not finite)
        break;
      }
    }
    checks.push_back(c);
    if (!checks.back().passed) return;  // the others would compare NaNs
  }

  // event_times: within [0, t_end], in order.
  {
    integrate::InvariantCheck c =
        make_check("event_times", "every event lies in [0, t_end], in order", "s");
    double previous = 0.0;
    c.bound = spec.t_end;
    for (const integrate::Event& e : result.events) {
      if (!(e.time >= previous && e.time <= spec.t_end)) {
        c.passed = false;
        c.value = e.time;
        c.time = std::isfinite(e.time) ? e.time : 0.0;
        break;
      }
      previous = e.time;
    }
    checks.push_back(c);
  }

  // The channels the checks read, each copied once into a column of its
  // own (contiguous; an absent channel reads the zero column last): the
  // scales below are vectorized reductions and each pointwise check one
  // short loop. (One fused loop over the point-major rows read each value
  // twice through a stride: 420 instructions per row, 43k of the friction
  // block's 550k per call; copying every channel through Eigen's
  // row-to-column assignment cost 7 per value; issue 17's benchmark.)
  const auto rows = static_cast<Eigen::Index>(n);
  const auto width = static_cast<Eigen::Index>(channels);
  // The columns, the friction and normal forces, the energy flow and the
  // slip band in one buffer (ScratchBuffer).
  ScratchBuffer scratch(n * (channels + 1) + 4 * n);
  Eigen::Map<Eigen::MatrixXd> table(scratch.data(), rows, width + 1);
  table.col(width).setZero();
  double* const extra = scratch.data() + n * (channels + 1);
  std::vector<bool> copied(channels, false);
  auto column = [&](const std::string& name) {
    const int k = result.channel_index(name);
    if (k < 0) return static_cast<const double*>(table.col(width).data());
    if (!copied[static_cast<std::size_t>(k)]) {
      table.col(k) = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>(
          result.values.data() + k, rows, Eigen::InnerStride<>(width));
      copied[static_cast<std::size_t>(k)] = true;
    }
    return static_cast<const double*>(table.col(k).data());
  };
  auto array = [&](const double* values) { return Eigen::Map<const Eigen::ArrayXd>(values, rows); };
  // The largest value of a column (>= 0; the finite check above passed).
  auto largest = [&](const auto& values) {
    return rows > 0 ? std::max(0.0, values.maxCoeff()) : 0.0;
  };

  const double* const slip = column(spec.slip);
  const double* const stick = column(spec.stick);
  const double* const play = column("play");
  const int gap_index = result.channel_index("gap");
  const double* const gap = column("gap");
  const double* const friction_loss = column(spec.friction_loss);
  const double* const residual = column(spec.residual);
  const double* const time = result.time.data();
  // The friction force on the slipping body, and the normal force mu'
  // multiplies (a preloaded nut's halves: flank_normal).
  Eigen::Map<Eigen::ArrayXd> friction_force(extra, rows), normal_force(extra + n, rows);
  friction_force = spec.friction_sign * array(column(spec.friction));
  if (spec.flank_normal) {
    const double* normal_channel = column(spec.normal);
    for (Eigen::Index i = 0; i < rows; ++i)
      normal_force[i] = spec.flank_normal(normal_channel[i], friction_force[i]);
  } else {
    normal_force = array(column(spec.normal)).abs();
  }
  const double* const friction = friction_force.data();
  const double* const normal = normal_force.data();

  const friction::Resolution resolution =
      spec.law ? spec.law->resolution() : friction::Resolution::acceleration;
  const bool set_valued = resolution == friction::Resolution::set_valued;
  // mu_static' of a set-valued law (its cone), < 0: none.
  const double cone_mu = set_valued ? spec.law->mu_static() * spec.coefficient_scale : -1.0;
  const double viscous = spec.law ? spec.law->viscous() : 0.0;

  // Pass 1: the run's scales. E, the largest energy flow: the channels of
  // the energy account present (work, stored, losses, in that order: an
  // absent one counts as 0), summed row by row; G, the energy's gradient
  // bound; the largest applied force (a torque over its lever), play rate
  // and each other loss (those `losses` checks; the friction loss has its
  // own check).
  Eigen::Map<Eigen::ArrayXd> flow(extra + 2 * n, rows);
  flow.setZero();
  for (const auto* names : {&spec.work, &spec.stored, &spec.losses})
    for (const auto& name : *names)
      if (result.channel_index(name) >= 0) flow += array(column(name)).abs();
  const double energy = largest(flow);
  double force_scale = 0.0;
  for (const auto& name : spec.load_forces)
    if (result.channel_index(name) >= 0)
      force_scale = std::max(force_scale, largest(array(column(name)).abs()));
  for (const auto& name : spec.load_torques)
    if (result.channel_index(name) >= 0)
      force_scale = std::max(force_scale, largest(array(column(name)).abs() / spec.lever));
  std::vector<const double*> other_losses;
  std::vector<double> largest_loss;
  for (const auto& name : spec.losses)
    if (result.channel_index(name) >= 0 && name != spec.friction_loss) {
      other_losses.push_back(column(name));
      largest_loss.push_back(largest(array(other_losses.back()).abs()));
    }
  const double max_slip = largest(array(slip).abs());
  const double max_friction = largest(friction_force.abs());
  const double max_normal = largest(normal_force);
  const double max_kinetic = largest(array(column("kinetic")));
  double gradient = largest(spec.momentum_factor * array(column("kinetic")).max(0.0).sqrt() +
                            spec.force_factor * array(column("elastic")).max(0.0).sqrt());
  const double max_loss = largest(array(friction_loss).abs());
  double play_rate = spec.step_play_rate;
  if (spec.time_stepping)  // (flank_gap's tolerance)
    for (std::size_t i = 1; i < n; ++i) {
      const double dt = time[i] - time[i - 1];
      if (dt > 0.0) play_rate = std::max(play_rate, std::abs(play[i] - play[i - 1]) / dt);
    }
  gradient += spec.quadratures;
  force_scale = std::max(force_scale, std::max(max_friction, max_normal));

  // The forces' round-off: relative to the largest forces of the run, and to
  // the momentum the solves balance them against (a drive whose thread
  // carries nothing has flank forces of pure round-off, 1e-18 N, from terms
  // of M v / h of 0.1 N), per step (Moreau-Jean) or per run.
  const double momentum = spec.momentum_factor * std::sqrt(max_kinetic);
  const double force_resolution =
      kForceResolution *
      (max_friction + std::max(cone_mu, 1.0) * max_normal +
       momentum / (spec.time_stepping && spec.time_step > 0.0 ? spec.time_step : spec.t_end));
  // The values recorded just before an event are those at its located root,
  // where its root function (a flank normal force, the cone's margin) has
  // just changed sign: by up to its rate times the root's time resolution
  // (1e5 N/s and more with a flexible drive's stiff springs), and by a
  // whole jump where a load jumps (a callable's step). Those rows describe
  // the instant the mode ends, not a state of the mode: the pointwise force
  // checks skip them (the rows after the event are the new mode's).
  std::vector<double> event_times;
  event_times.reserve(result.events.size());
  for (const integrate::Event& e : result.events) event_times.push_back(e.time);
  std::sort(event_times.begin(), event_times.end());
  auto at_event_root = [&](std::size_t i) {
    const double t = time[i];
    if (i + 1 < n && time[i + 1] == t) return true;  // before the event (every step)
    if (i > 0 && time[i - 1] == t) return false;      // after it
    return std::binary_search(event_times.begin(), event_times.end(), t);  // a requested time
  };
  // The slip velocity below which its sign is not resolved: the
  // integrator's tolerances on the velocities through |W_T| (atol, and rtol
  // of the largest slip), and round-off (time stepping: the step's slip is
  // its LCP's, exact up to round-off).
  const double slip_band =
      spec.time_stepping ? 64.0 * kEpsilon * max_slip
                         : spec.slip_resolution + (spec.rtol + 64.0 * kEpsilon) * max_slip;
  // The root location's time resolution (CVODE's 100 ulp of the time; our
  // Runge-Kutta engines locate to 4 ulp): the slip velocity just before a
  // slip's end is its rate times that, on either side of zero.
  const double time_resolution = 128.0 * kEpsilon * spec.t_end;

  // The energies' round-off: the work of the run's largest force over the
  // round-off of its longest length (the positions' own resolution; a
  // stuck drive's round-off creep of 1e-20 m under 586 N books 8e-18 J of
  // work and nothing else).
  const double energy_round_off = 64.0 * kEpsilon * force_scale * spec.length_scale;
  // (at most kResolvedEnergyShare of the flow, whatever the tolerances:
  // K rtol E alone is the whole flow at rtol = 1e-3, and atol G with a
  // stiff contact's G far more; result_checks.md, "energy_balance")
  const double tolerance_error =
      kEnergyToleranceFactor *
      (std::max(spec.rtol, 64.0 * kEpsilon) * energy + spec.atol * gradient);
  const double integration_error =
      (spec.rows_are_steps ? std::min(tolerance_error, kResolvedEnergyShare * energy)
                           : tolerance_error) +
      energy_round_off;

  // friction_power: lambda_T gamma_T <= |lambda_T| slip_band.
  integrate::InvariantCheck power = make_check(
      "friction_power",
      "friction never does positive work: friction_force * slip_velocity <= |friction_force| "
      "times the slip velocity the integration resolves",
      "W");
  // Interpolated between time steps, a force and a slip velocity come
  // from two steps: their product is not the scheme's (each step's friction
  // impulse opposes that step's slip exactly, by its LCP).
  power.applies = spec.friction_dissipates && !(spec.time_stepping && result.interpolated);

  // friction_loss: never falls by more than its integration error (and what
  // friction may push within the slip band over the run).
  integrate::InvariantCheck loss = make_check(
      "friction_loss", "the friction loss never falls (beyond its integration error)", "J");
  loss.applies = spec.friction_dissipates;
  const double loss_tolerance =
      spec.time_stepping
          ? 64.0 * kEpsilon * max_loss + energy_round_off
          : kEnergyToleranceFactor * (std::max(spec.rtol, 64.0 * kEpsilon) * max_loss + spec.atol) +
                max_friction * slip_band * spec.t_end;

  // friction_cone: |lambda_T| <= mu' |lambda_N| (exact Coulomb).
  integrate::InvariantCheck cone = make_check(
      "friction_cone",
      "|friction_force| <= mu_static' |normal_force| + viscous |slip_velocity| (Coulomb's cone)",
      "N");
  cone.applies = set_valued && !(spec.time_stepping && result.interpolated);

  // losses: damping, contact, impact (the friction loss above).
  integrate::InvariantCheck other = make_check(
      "losses", "the other losses (damping, contact, impact; the train's motor_friction_loss "
                "and gear_loss) never fall (beyond their integration error)", "J");
  std::vector<double> other_tolerance(other_losses.size());
  for (std::size_t j = 0; j < other_losses.size(); ++j)
    other_tolerance[j] =
        spec.time_stepping ? 64.0 * kEpsilon * largest_loss[j] + energy_round_off
                           : kEnergyToleranceFactor *
                                 (std::max(spec.rtol, 64.0 * kEpsilon) * largest_loss[j] + spec.atol);

  // friction_law: where the contact slips, the friction force is the law's.
  integrate::InvariantCheck law = make_check(
      "friction_law",
      "where it slips, the friction force is the law's: mu(|slip_velocity|)' |normal_force| "
      "+ viscous |slip_velocity| (where the flanks touch) against the slip (set-valued laws), "
      "-kappa(slip_velocity)' "
      "|normal_force| - viscous slip_velocity (velocity laws, eq. 3.16)",
      "N");
  // (Moreau-Jean's slip friction is the law's at the step's start speed:
  // checked where the law's slip coefficient is one number, mu at every
  // slip speed and no viscous term: Coulomb's, with or without mu_static.)
  const bool one_slip_coefficient =
      spec.law != nullptr && spec.law->viscous() == 0.0 &&
      spec.law->slip_mu(1e-300) == spec.law->mu() && spec.law->slip_mu(1.0) == spec.law->mu();
  law.applies = (set_valued || resolution == friction::Resolution::velocity) &&
                !(spec.time_stepping && (result.interpolated || !one_slip_coefficient));

  // flank_gap: exact play, the nut never passes a flank.
  integrate::InvariantCheck flank = make_check(
      "flank_gap", "the nut never passes a flank of the play (gap >= 0)", "m");
  flank.applies = spec.clearance > 0.0 && gap_index >= 0;
  // The free flight's own check (drive/hybrid_impacts.cpp, kFlankTolerance)
  // allows 1e-3 of the clearance; Moreau-Jean closes a flank at the
  // velocity level, up to three steps of the play's motion late (and a
  // play that drifts beyond that through its flank is a step too long).
  double gap_tolerance = 1e-3 * spec.clearance + 10.0 * spec.atol;
  if (spec.time_stepping)
    gap_tolerance = std::min(spec.clearance, gap_tolerance + 3.0 * spec.time_step * play_rate);

  // energy_balance.
  integrate::InvariantCheck balance = make_check(
      "energy_balance",
      spec.time_stepping
          ? "the energy account creates no energy beyond 1e-3 of the run's largest energy "
            "flow and what the friction impulses book beyond the steps' work, (1 - theta) "
            "|P_T (gamma+ - gamma-)| where the slip speeds up (first order in dt), up to "
            "1e-2 of that flow"
          : "|energy_residual| within the integration tolerances carried through the energy, "
            "and (output at every step) within 1e-2 of the run's largest energy flow",
      "J");
  const double balance_bound =
      spec.time_stepping
          ? kTimeSteppingCreation * energy +
                std::min(spec.step_friction_excess, kFrictionBookingShare * energy) +
                energy_round_off
          : integration_error;

  // Pass 2: every pointwise check, one loop each (the worst row kept in
  // row order, as one loop over the rows would).
  Worst worst_power{power}, worst_loss{loss}, worst_cone{cone}, worst_other{other},
      worst_law{law}, worst_flank{flank}, worst_balance{balance};
  const bool pointwise_forces = power.applies || cone.applies || law.applies;
  // The force checks' slip band per row (< 0: a row at an event's root,
  // skipped): what is resolved, plus the slip's rate toward its neighbours
  // times the root's time resolution (not for time stepping).
  double* const band = extra + 3 * n;
  if (pointwise_forces) {
    double rate_before = 0.0;  // |slip change| / dt over the interval to the row before
    for (std::size_t i = 0; i < n; ++i) {
      double rate_after = 0.0;
      if (i + 1 < n) {
        const double dt = std::abs(time[i + 1] - time[i]);
        if (dt > 0.0) rate_after = std::abs(slip[i + 1] - slip[i]) / dt;
      }
      const double rate = std::max(std::max(0.0, rate_before), rate_after);
      rate_before = rate_after;
      band[i] = at_event_root(i)
                    ? -1.0
                    : slip_band + (spec.time_stepping ? 0.0 : rate * time_resolution);
    }
  }
  if (power.applies)
    for (std::size_t i = 0; i < n; ++i)
      if (band[i] >= 0.0) {
        const double f = friction[i], v = slip[i];
        worst_power.offer(f * v, std::abs(f) * band[i] + std::abs(v) * force_resolution, time[i]);
      }
  if (cone.applies)
    for (std::size_t i = 0; i < n; ++i)
      if (band[i] >= 0.0)
        worst_cone.offer(std::abs(friction[i]) - (cone_mu * normal[i] + viscous * std::abs(slip[i])),
                         force_resolution, time[i]);
  if (law.applies) {
    const double scale = spec.coefficient_scale;
    if (set_valued) {
      // Slipping: not in stick, and the slip beyond what is resolved.
      // (The viscous term acts where the flanks touch: not in open play.)
      // Plain Coulomb's slip coefficient is its mu at every speed.
      const bool plain = one_slip_coefficient;
      const double plain_mu = spec.law->mu();
      for (std::size_t i = 0; i < n; ++i) {
        const double speed = std::abs(slip[i]);
        if (band[i] < 0.0 || stick[i] != 0.0 || !(speed > band[i])) continue;
        const double normal_force = normal[i];
        const double expected = (plain ? plain_mu : spec.law->slip_mu(speed)) * scale * normal_force +
                                (normal_force > 0.0 ? viscous * speed : 0.0);
        worst_law.offer(std::abs(expected - std::abs(friction[i])), force_resolution, time[i]);
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        if (band[i] < 0.0) continue;
        const double v = slip[i], normal_force = normal[i];
        const double expected = -spec.law->velocity_coefficient(v) * scale * normal_force -
                                (normal_force > 0.0 ? viscous * v : 0.0);
        worst_law.offer(std::abs(friction[i] - expected), force_resolution, time[i]);
      }
    }
  }
  if (loss.applies) {
    double highest_loss = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      highest_loss = std::max(highest_loss, friction_loss[i]);
      worst_loss.offer(highest_loss - friction_loss[i], loss_tolerance, time[i]);
    }
  }
  if (!other_losses.empty()) {
    std::vector<double> highest_other(other_losses.size(),
                                      -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < other_losses.size(); ++j) {
        const double value = other_losses[j][i];
        highest_other[j] = std::max(highest_other[j], value);
        worst_other.offer(highest_other[j] - value, other_tolerance[j], time[i]);
      }
  }
  if (flank.applies)
    for (std::size_t i = 0; i < n; ++i) worst_flank.offer(-gap[i], gap_tolerance, time[i]);
  for (std::size_t i = 0; i < n; ++i)
    worst_balance.offer(spec.time_stepping ? -residual[i] : std::abs(residual[i]), balance_bound,
                        time[i]);
  for (integrate::InvariantCheck* c : {&power, &loss, &cone, &other, &law, &flank, &balance})
    checks.push_back(*c);
  check_bristle_bound(spec, result);
}

}  // namespace leadscrew::model
