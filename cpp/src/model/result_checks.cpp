#include "leadscrew/model/result_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/friction/law.hpp"

namespace leadscrew::model {

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// One channel of the result (point-major storage): its value at point i;
// an absent channel reads 0. (A column pointer and a stride, no branch per
// read: the checks read a dozen channels per row, issue 17's benchmark.)
class Column {
 public:
  Column(const integrate::SimulationResult& r, int k)
      : data_(k < 0 ? &kAbsent : r.values.data() + k), stride_(k < 0 ? 0 : r.channel_count()) {}
  double operator[](std::size_t i) const { return data_[i * stride_]; }

 private:
  static constexpr double kAbsent = 0.0;
  const double* data_;
  std::size_t stride_;
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

integrate::InvariantCheck make_check(const char* name, const char* what, const char* unit) {
  integrate::InvariantCheck c;
  c.name = name;
  c.what = what;
  c.unit = unit;
  return c;
}

// Keeps the worst excess (value - bound) of an invariant value <= bound.
struct Worst {
  integrate::InvariantCheck& check;
  double excess = -std::numeric_limits<double>::infinity();
  void offer(double value, double bound, double t) {
    const double e = value - bound;
    if (!(e <= excess)) {  // the first, a larger one, or NaN
      excess = e;
      check.value = value;
      check.bound = bound;
      check.time = t;
    }
    if (!(value <= bound)) check.passed = false;
  }
};

}  // namespace

void check_result(const ResultCheckSpec& spec, integrate::SimulationResult& result) {
  // Two passes over the rows: the scales (largest forces, energies, slip),
  // then every pointwise check at once. (Ten passes, one per check, cost a
  // seventh of the friction block's whole run; issue 17's benchmark.)
  std::vector<integrate::InvariantCheck>& checks = result.checks;
  checks.clear();
  checks.reserve(9);
  const std::size_t n = result.point_count();
  auto column = [&](const std::string& name) { return Column(result, result.channel_index(name)); };
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

  const Column slip = column(spec.slip), friction = column(spec.friction),
               normal = column(spec.normal);
  const Column kinetic = column("kinetic"), elastic = column("elastic");
  const Column friction_loss = column(spec.friction_loss), residual = column(spec.residual);
  const Column stick = column(spec.stick), play = column("play");
  const int gap_index = result.channel_index("gap");
  const Column gap(result, gap_index);
  // The channels present (an absent one counts as 0): the energy account's
  // (work, stored, losses, in that order), the applied loads', and the
  // losses `losses` checks (the friction loss has its own check).
  std::vector<Column> flow_channels, load_forces, load_torques, other_losses;
  flow_channels.reserve(spec.work.size() + spec.stored.size() + spec.losses.size());
  load_forces.reserve(spec.load_forces.size());
  load_torques.reserve(spec.load_torques.size());
  other_losses.reserve(spec.losses.size());
  for (const auto* names : {&spec.work, &spec.stored, &spec.losses})
    for (const auto& name : *names)
      if (const int k = result.channel_index(name); k >= 0) flow_channels.emplace_back(result, k);
  for (const auto& name : spec.load_forces)
    if (const int k = result.channel_index(name); k >= 0) load_forces.emplace_back(result, k);
  for (const auto& name : spec.load_torques)
    if (const int k = result.channel_index(name); k >= 0) load_torques.emplace_back(result, k);
  for (const auto& name : spec.losses)
    if (const int k = result.channel_index(name); k >= 0 && name != spec.friction_loss)
      other_losses.emplace_back(result, k);

  const friction::Resolution resolution =
      spec.law ? spec.law->resolution() : friction::Resolution::acceleration;
  const bool set_valued = resolution == friction::Resolution::set_valued;
  // mu_static' of a set-valued law (its cone), < 0: none.
  const double cone_mu = set_valued ? spec.law->mu_static() * spec.coefficient_scale : -1.0;
  const double viscous = spec.law ? spec.law->viscous() : 0.0;

  // Pass 1: the run's scales.
  double max_slip = 0.0, max_friction = 0.0, max_normal = 0.0, max_kinetic = 0.0;
  // E, the largest energy flow; G, the energy's gradient bound; the largest
  // friction loss, applied force, play rate and each other loss.
  double energy = 0.0, gradient = 0.0, max_loss = 0.0, force_scale = 0.0;
  double play_rate = spec.step_play_rate;
  std::vector<double> largest_loss(other_losses.size(), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    max_slip = std::max(max_slip, std::abs(slip[i]));
    max_friction = std::max(max_friction, std::abs(friction[i]));
    max_normal = std::max(max_normal, spec.flank_normal
                                          ? spec.flank_normal(normal[i],
                                                              spec.friction_sign * friction[i])
                                          : std::abs(normal[i]));
    max_kinetic = std::max(max_kinetic, kinetic[i]);
    double flow = 0.0;
    for (const Column& c : flow_channels) flow += std::abs(c[i]);
    energy = std::max(energy, flow);
    const double g = spec.momentum_factor * std::sqrt(std::max(0.0, kinetic[i])) +
                     spec.force_factor * std::sqrt(std::max(0.0, elastic[i]));
    gradient = std::max(gradient, g);
    max_loss = std::max(max_loss, std::abs(friction_loss[i]));
    for (const Column& c : load_forces) force_scale = std::max(force_scale, std::abs(c[i]));
    for (const Column& c : load_torques)
      force_scale = std::max(force_scale, std::abs(c[i]) / spec.lever);
    for (std::size_t j = 0; j < other_losses.size(); ++j)
      largest_loss[j] = std::max(largest_loss[j], std::abs(other_losses[j][i]));
    if (spec.time_stepping && i > 0) {  // (flank_gap's tolerance)
      const double dt = result.time[i] - result.time[i - 1];
      if (dt > 0.0) play_rate = std::max(play_rate, std::abs(play[i] - play[i - 1]) / dt);
    }
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
    const double t = result.time[i];
    if (i + 1 < n && result.time[i + 1] == t) return true;  // before the event (every step)
    if (i > 0 && result.time[i - 1] == t) return false;      // after it
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
  auto slip_rate = [&](std::size_t i) {
    double rate = 0.0;
    for (const std::size_t j : {i == 0 ? i : i - 1, i + 1 < n ? i + 1 : i}) {
      const double dt = std::abs(result.time[j] - result.time[i]);
      if (dt > 0.0) rate = std::max(rate, std::abs(slip[j] - slip[i]) / dt);
    }
    return rate;
  };

  // The energies' round-off: the work of the run's largest force over the
  // round-off of its longest length (the positions' own resolution; a
  // stuck drive's round-off creep of 1e-20 m under 586 N books 8e-18 J of
  // work and nothing else).
  const double energy_round_off = 64.0 * kEpsilon * force_scale * spec.length_scale;
  const double integration_error =
      kEnergyToleranceFactor *
          (std::max(spec.rtol, 64.0 * kEpsilon) * energy + spec.atol * gradient) +
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
  // checked where the law's slip coefficient is one number.)
  law.applies = (set_valued || resolution == friction::Resolution::velocity) &&
                !(spec.time_stepping && (result.interpolated || !spec.law->plain_coulomb()));

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
          : "|energy_residual| within the integration tolerances carried through the energy",
      "J");
  const double balance_bound =
      spec.time_stepping
          ? kTimeSteppingCreation * energy +
                std::min(spec.step_friction_excess, kFrictionBookingShare * energy) +
                energy_round_off
          : integration_error;

  // Pass 2: every pointwise check.
  Worst worst_power{power}, worst_loss{loss}, worst_cone{cone}, worst_other{other},
      worst_law{law}, worst_flank{flank}, worst_balance{balance};
  const bool pointwise_forces = power.applies || cone.applies || law.applies;
  double highest_loss = -std::numeric_limits<double>::infinity();
  std::vector<double> highest_other(other_losses.size(),
                                    -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i) {
    const double t = result.time[i];
    if (pointwise_forces && !at_event_root(i)) {
      const double f = spec.friction_sign * friction[i];
      const double v = slip[i];
      const double normal_force =
          spec.flank_normal ? spec.flank_normal(normal[i], f) : std::abs(normal[i]);
      const double band = slip_band + (spec.time_stepping ? 0.0 : slip_rate(i) * time_resolution);
      if (power.applies) worst_power.offer(f * v, std::abs(f) * band + std::abs(v) * force_resolution, t);
      if (cone.applies)
        worst_cone.offer(std::abs(f) - (cone_mu * normal_force + viscous * std::abs(v)),
                         force_resolution, t);
      if (law.applies) {
        if (set_valued) {
          // Slipping: not in stick, and the slip beyond what is resolved.
          // (The viscous term acts where the flanks touch: not in open play.)
          if (stick[i] == 0.0 && std::abs(v) > band) {
            const double expected = spec.law->slip_mu(std::abs(v)) * spec.coefficient_scale *
                                        normal_force +
                                    (normal_force > 0.0 ? viscous * std::abs(v) : 0.0);
            worst_law.offer(std::abs(expected - std::abs(f)), force_resolution, t);
          }
        } else {
          const double expected =
              -spec.law->velocity_coefficient(v) * spec.coefficient_scale * normal_force -
              (normal_force > 0.0 ? viscous * v : 0.0);
          worst_law.offer(std::abs(f - expected), force_resolution, t);
        }
      }
    }
    if (loss.applies) {
      const double value = friction_loss[i];
      highest_loss = std::max(highest_loss, value);
      worst_loss.offer(highest_loss - value, loss_tolerance, t);
    }
    for (std::size_t j = 0; j < other_losses.size(); ++j) {
      const double value = other_losses[j][i];
      highest_other[j] = std::max(highest_other[j], value);
      worst_other.offer(highest_other[j] - value, other_tolerance[j], t);
    }
    if (flank.applies) worst_flank.offer(-gap[i], gap_tolerance, t);
    const double r = residual[i];
    worst_balance.offer(spec.time_stepping ? -r : std::abs(r), balance_bound, t);
  }
  for (integrate::InvariantCheck* c : {&power, &loss, &cone, &other, &law, &flank, &balance})
    checks.push_back(*c);
}

}  // namespace leadscrew::model
