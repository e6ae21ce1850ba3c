#include "leadscrew/model/result_checks.hpp"

#include "leadscrew/friction/law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace leadscrew::model {

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// Channel k of the result at point i (point-major storage), or 0 if absent.
class Channels {
 public:
  explicit Channels(const integrate::SimulationResult& r) : r_(r), stride_(r.channel_count()) {}
  int index(const std::string& name) const { return r_.channel_index(name); }
  double at(int k, std::size_t i) const {
    return k < 0 ? 0.0 : r_.values[i * stride_ + static_cast<std::size_t>(k)];
  }
  std::size_t points() const { return r_.point_count(); }

 private:
  const integrate::SimulationResult& r_;
  std::size_t stride_;
};

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
  bool seen = false;
  double excess = 0.0;
  void offer(double value, double bound, double t) {
    const double e = value - bound;
    if (!seen || e > excess || std::isnan(value)) {
      seen = true;
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
  const Channels ch(result);
  const std::size_t n = ch.points();
  const std::size_t channels = result.channel_count();

  // finite: every value and time (one flat loop; the row only on failure).
  {
    integrate::InvariantCheck c =
        make_check("finite", "every channel and output time is a finite number", "");
    bool finite = true;
    for (std::size_t i = 0; i < n; ++i) finite &= std::isfinite(result.time[i]);
    for (const double v : result.values) finite &= std::isfinite(v);
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

  const int slip = ch.index(spec.slip), friction = ch.index(spec.friction),
            normal = ch.index(spec.normal);
  const int kinetic = ch.index("kinetic"), elastic = ch.index("elastic");
  const int friction_loss = ch.index(spec.friction_loss), residual = ch.index(spec.residual);
  const int stick = ch.index(spec.stick), gap = ch.index("gap"), play = ch.index("play");
  // The channels present (an absent one counts as 0): the energy account's
  // (work, stored, losses, in that order), the applied loads', and the
  // losses `losses` checks (the friction loss has its own check).
  std::vector<int> flow_channels, load_forces, load_torques, other_losses;
  for (const auto* names : {&spec.work, &spec.stored, &spec.losses})
    for (const auto& name : *names)
      if (const int k = ch.index(name); k >= 0) flow_channels.push_back(k);
  for (const auto& name : spec.load_forces)
    if (const int k = ch.index(name); k >= 0) load_forces.push_back(k);
  for (const auto& name : spec.load_torques)
    if (const int k = ch.index(name); k >= 0) load_torques.push_back(k);
  for (const auto& name : spec.losses)
    if (const int k = ch.index(name); k >= 0 && name != spec.friction_loss)
      other_losses.push_back(k);

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
    max_slip = std::max(max_slip, std::abs(ch.at(slip, i)));
    max_friction = std::max(max_friction, std::abs(ch.at(friction, i)));
    max_normal = std::max(max_normal, std::abs(ch.at(normal, i)));
    max_kinetic = std::max(max_kinetic, ch.at(kinetic, i));
    double flow = 0.0;
    for (int k : flow_channels) flow += std::abs(ch.at(k, i));
    energy = std::max(energy, flow);
    const double g = spec.momentum_factor * std::sqrt(std::max(0.0, ch.at(kinetic, i))) +
                     spec.force_factor * std::sqrt(std::max(0.0, ch.at(elastic, i)));
    gradient = std::max(gradient, g);
    max_loss = std::max(max_loss, std::abs(ch.at(friction_loss, i)));
    for (int k : load_forces) force_scale = std::max(force_scale, std::abs(ch.at(k, i)));
    for (int k : load_torques)
      force_scale = std::max(force_scale, std::abs(ch.at(k, i)) / spec.lever);
    for (std::size_t j = 0; j < other_losses.size(); ++j)
      largest_loss[j] = std::max(largest_loss[j], std::abs(ch.at(other_losses[j], i)));
    if (spec.time_stepping && i > 0) {  // (flank_gap's tolerance)
      const double dt = result.time[i] - result.time[i - 1];
      if (dt > 0.0) play_rate = std::max(play_rate, std::abs(ch.at(play, i) - ch.at(play, i - 1)) / dt);
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
      if (dt > 0.0) rate = std::max(rate, std::abs(ch.at(slip, j) - ch.at(slip, i)) / dt);
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
      "losses", "the damping, contact and impact losses never fall (beyond their "
                "integration error)", "J");
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
  flank.applies = spec.clearance > 0.0 && gap >= 0;
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
      const double f = spec.friction_sign * ch.at(friction, i);
      const double v = ch.at(slip, i);
      const double normal_force = std::abs(ch.at(normal, i));
      const double band = slip_band + (spec.time_stepping ? 0.0 : slip_rate(i) * time_resolution);
      if (power.applies) worst_power.offer(f * v, std::abs(f) * band + std::abs(v) * force_resolution, t);
      if (cone.applies)
        worst_cone.offer(std::abs(f) - (cone_mu * normal_force + viscous * std::abs(v)),
                         force_resolution, t);
      if (law.applies) {
        if (set_valued) {
          // Slipping: not in stick, and the slip beyond what is resolved.
          // (The viscous term acts where the flanks touch: not in open play.)
          if (ch.at(stick, i) == 0.0 && std::abs(v) > band) {
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
      const double value = ch.at(friction_loss, i);
      highest_loss = std::max(highest_loss, value);
      worst_loss.offer(highest_loss - value, loss_tolerance, t);
    }
    for (std::size_t j = 0; j < other_losses.size(); ++j) {
      const double value = ch.at(other_losses[j], i);
      highest_other[j] = std::max(highest_other[j], value);
      worst_other.offer(highest_other[j] - value, other_tolerance[j], t);
    }
    if (flank.applies) worst_flank.offer(-ch.at(gap, i), gap_tolerance, t);
    const double r = ch.at(residual, i);
    worst_balance.offer(spec.time_stepping ? -r : std::abs(r), balance_bound, t);
  }
  for (integrate::InvariantCheck* c : {&power, &loss, &cone, &other, &law, &flank, &balance})
    checks.push_back(*c);
}

}  // namespace leadscrew::model
