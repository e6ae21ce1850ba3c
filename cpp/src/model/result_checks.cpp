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

// The channels the checks read, each copied once into a column of its
// own (contiguous; an absent channel reads the zero column last): the
// scales below are vectorized reductions and each pointwise check one
// short loop. (One fused loop over the point-major rows read each value
// twice through a stride: 420 instructions per row, 43k of the friction
// block's 550k per call; copying every channel through Eigen's
// row-to-column assignment cost 7 per value; issue 17's benchmark.)
class ChannelColumns {
 public:
  // `buffer`: n * (channels + 1) doubles.
  ChannelColumns(const integrate::SimulationResult& result, double* buffer)
      : result_(result),
        rows_(static_cast<Eigen::Index>(result.point_count())),
        width_(static_cast<Eigen::Index>(result.channel_count())),
        table_(buffer, rows_, width_ + 1),
        copied_(result.channel_count(), false) {
    table_.col(width_).setZero();
  }

  bool has(const std::string& name) const { return result_.channel_index(name) >= 0; }

  const double* column(const std::string& name) {
    const int k = result_.channel_index(name);
    if (k < 0) return static_cast<const double*>(table_.col(width_).data());
    if (!copied_[static_cast<std::size_t>(k)]) {
      table_.col(k) = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>(
          result_.values.data() + k, rows_, Eigen::InnerStride<>(width_));
      copied_[static_cast<std::size_t>(k)] = true;
    }
    return static_cast<const double*>(table_.col(k).data());
  }

 private:
  const integrate::SimulationResult& result_;
  Eigen::Index rows_, width_;
  Eigen::Map<Eigen::MatrixXd> table_;
  std::vector<bool> copied_;
};

// What the pointwise checks read: the run's columns, the law's character,
// the run's scales (pass 1) and the resolutions derived from them, and the
// force checks' slip band per row.
struct CheckContext {
  CheckContext(const ResultCheckSpec& s, const integrate::SimulationResult& r)
      : spec(s), result(r), n(r.point_count()), rows(static_cast<Eigen::Index>(n)) {}

  const ResultCheckSpec& spec;
  const integrate::SimulationResult& result;
  std::size_t n;
  Eigen::Index rows;

  // The columns (ChannelColumns; the friction and normal forces computed).
  const double *time = nullptr, *slip = nullptr, *stick = nullptr, *play = nullptr,
               *gap = nullptr, *friction_loss = nullptr, *residual = nullptr,
               *friction = nullptr, *normal = nullptr;
  // A 2-D cone's transverse slip and friction (null: a 1-D contact).
  const double *transverse_slip = nullptr, *transverse_friction = nullptr;
  int gap_index = -1;
  // The losses of the `losses` check (the friction loss has its own) and
  // the largest of each.
  std::vector<const double*> other_losses;
  std::vector<double> largest_loss;

  // The law: its resolution, mu_static' of a set-valued law (its cone; < 0:
  // none), its viscous term, whether its slip coefficient is one number.
  friction::Resolution resolution = friction::Resolution::acceleration;
  bool set_valued = false, one_slip_coefficient = false;
  double cone_mu = -1.0, viscous = 0.0;

  // The run's scales (pass 1).
  double energy = 0.0, force_scale = 0.0, max_slip = 0.0, max_friction = 0.0,
         max_normal = 0.0, max_kinetic = 0.0, gradient = 0.0, max_loss = 0.0, play_rate = 0.0;

  // The resolutions (resolve_round_off).
  double force_resolution = 0.0, slip_band = 0.0, time_resolution = 0.0,
         energy_round_off = 0.0, integration_error = 0.0;
  std::vector<double> event_times;  // sorted

  // Which of the force checks apply, and their slip band per row (< 0: a
  // row at an event's root, skipped; fill_slip_band).
  bool power_applies = false, cone_applies = false, law_applies = false;
  double* band = nullptr;

  Eigen::Map<const Eigen::ArrayXd> array(const double* values) const {
    return Eigen::Map<const Eigen::ArrayXd>(values, rows);
  }
  // Row i's friction magnitude, its power on the slip and the slip speed:
  // the 2-D vectors' where the contact has a transverse slip.
  double friction_magnitude(std::size_t i) const {
    return transverse_friction ? std::hypot(friction[i], transverse_friction[i])
                               : std::abs(friction[i]);
  }
  double friction_power(std::size_t i) const {
    return transverse_friction ? friction[i] * slip[i] + transverse_friction[i] * transverse_slip[i]
                               : friction[i] * slip[i];
  }
  double slip_speed(std::size_t i) const {
    return transverse_slip ? std::hypot(slip[i], transverse_slip[i]) : std::abs(slip[i]);
  }
  // The largest value of a column (>= 0; the finite check passed).
  template <class Values>
  double largest(const Values& values) const {
    return rows > 0 ? std::max(0.0, values.maxCoeff()) : 0.0;
  }
};

// finite: every value and time (one flat loop; the row only on failure).
integrate::InvariantCheck check_finite(const integrate::SimulationResult& result) {
  const std::size_t n = result.point_count();
  const std::size_t channels = result.channel_count();
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
  return c;
}

// event_times: within [0, t_end], in order.
integrate::InvariantCheck check_event_times(const ResultCheckSpec& spec,
                                            const integrate::SimulationResult& result) {
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
  return c;
}

// The columns the checks read, and the friction force on the slipping body
// and the normal force mu' multiplies (a preloaded nut's halves:
// flank_normal), into `forces` (2 n doubles; 3 n with a transverse slip:
// the transverse friction last).
void read_columns(CheckContext& x, ChannelColumns& columns, double* forces) {
  const ResultCheckSpec& spec = x.spec;
  x.slip = columns.column(spec.slip);
  x.stick = columns.column(spec.stick);
  x.play = columns.column("play");
  x.gap_index = x.result.channel_index("gap");
  x.gap = columns.column("gap");
  x.friction_loss = columns.column(spec.friction_loss);
  x.residual = columns.column(spec.residual);
  x.time = x.result.time.data();
  Eigen::Map<Eigen::ArrayXd> friction_force(forces, x.rows), normal_force(forces + x.n, x.rows);
  friction_force = spec.friction_sign * x.array(columns.column(spec.friction));
  if (spec.flank_normal) {
    const double* normal_channel = columns.column(spec.normal);
    for (Eigen::Index i = 0; i < x.rows; ++i)
      normal_force[i] = spec.flank_normal(normal_channel[i], friction_force[i]);
  } else {
    normal_force = x.array(columns.column(spec.normal)).abs();
  }
  x.friction = friction_force.data();
  x.normal = normal_force.data();
  if (!spec.transverse_friction.empty()) {
    Eigen::Map<Eigen::ArrayXd> across(forces + 2 * x.n, x.rows);
    across = spec.friction_sign * x.array(columns.column(spec.transverse_friction));
    x.transverse_friction = across.data();
    x.transverse_slip = columns.column(spec.transverse_slip);
  }
}

// The law's character, and which of the force checks apply to it.
void describe_law(CheckContext& x) {
  const ResultCheckSpec& spec = x.spec;
  x.resolution = spec.law ? spec.law->resolution() : friction::Resolution::acceleration;
  x.set_valued = x.resolution == friction::Resolution::set_valued;
  x.cone_mu = x.set_valued ? spec.law->mu_static() * spec.coefficient_scale : -1.0;
  x.viscous = spec.law ? spec.law->viscous() : 0.0;
  // Interpolated between time steps, a force and a slip velocity come
  // from two steps: their product is not the scheme's (each step's friction
  // impulse opposes that step's slip exactly, by its LCP).
  const bool interpolated_steps = spec.time_stepping && x.result.interpolated;
  x.power_applies = spec.friction_dissipates && !interpolated_steps;
  x.cone_applies = x.set_valued && !interpolated_steps;
  // (Moreau-Jean's slip friction is the law's at the step's start speed:
  // checked where the law's slip coefficient is one number, mu at every
  // slip speed and no viscous term: Coulomb's, with or without mu_static.)
  x.one_slip_coefficient =
      spec.law != nullptr && spec.law->viscous() == 0.0 &&
      spec.law->slip_mu(1e-300) == spec.law->mu() && spec.law->slip_mu(1.0) == spec.law->mu();
  x.law_applies = (x.set_valued || x.resolution == friction::Resolution::velocity) &&
                  !(spec.time_stepping && (x.result.interpolated || !x.one_slip_coefficient));
}

// Pass 1: the run's scales. E, the largest energy flow: the channels of
// the energy account present (work, stored, losses, in that order: an
// absent one counts as 0), summed row by row, into `flow` (n doubles); G,
// the energy's gradient bound; the largest applied force (a torque over its
// lever), play rate and each other loss (those `losses` checks; the
// friction loss has its own check).
void measure_scales(CheckContext& x, ChannelColumns& columns, double* flow_buffer) {
  const ResultCheckSpec& spec = x.spec;
  Eigen::Map<Eigen::ArrayXd> flow(flow_buffer, x.rows);
  flow.setZero();
  for (const auto* names : {&spec.work, &spec.stored, &spec.losses})
    for (const auto& name : *names)
      if (columns.has(name)) flow += x.array(columns.column(name)).abs();
  x.energy = x.largest(flow);
  double force_scale = 0.0;
  for (const auto& name : spec.load_forces)
    if (columns.has(name))
      force_scale = std::max(force_scale, x.largest(x.array(columns.column(name)).abs()));
  for (const auto& name : spec.load_torques)
    if (columns.has(name))
      force_scale =
          std::max(force_scale, x.largest(x.array(columns.column(name)).abs() / spec.lever));
  for (const auto& name : spec.losses)
    if (columns.has(name) && name != spec.friction_loss) {
      x.other_losses.push_back(columns.column(name));
      x.largest_loss.push_back(x.largest(x.array(x.other_losses.back()).abs()));
    }
  const Eigen::Map<const Eigen::ArrayXd> friction_force(x.friction, x.rows);
  x.max_slip = x.largest(x.array(x.slip).abs());
  x.max_friction = x.largest(friction_force.abs());
  x.max_normal = x.largest(x.array(x.normal));
  x.max_kinetic = x.largest(x.array(columns.column("kinetic")));
  x.gradient =
      x.largest(spec.momentum_factor * x.array(columns.column("kinetic")).max(0.0).sqrt() +
                spec.force_factor * x.array(columns.column("elastic")).max(0.0).sqrt());
  x.max_loss = x.largest(x.array(x.friction_loss).abs());
  x.play_rate = spec.step_play_rate;
  if (spec.time_stepping)  // (flank_gap's tolerance)
    for (std::size_t i = 1; i < x.n; ++i) {
      const double dt = x.time[i] - x.time[i - 1];
      if (dt > 0.0)
        x.play_rate = std::max(x.play_rate, std::abs(x.play[i] - x.play[i - 1]) / dt);
    }
  x.gradient += spec.quadratures;
  x.force_scale = std::max(force_scale, std::max(x.max_friction, x.max_normal));
}

// The resolutions of the forces, the slip, the time and the energies, from
// the run's scales.
void resolve_round_off(CheckContext& x) {
  const ResultCheckSpec& spec = x.spec;
  // The forces' round-off: relative to the largest forces of the run, and to
  // the momentum the solves balance them against (a drive whose thread
  // carries nothing has flank forces of pure round-off, 1e-18 N, from terms
  // of M v / h of 0.1 N), per step (Moreau-Jean) or per run.
  const double momentum = spec.momentum_factor * std::sqrt(x.max_kinetic);
  x.force_resolution =
      kForceResolution *
      (x.max_friction + std::max(x.cone_mu, 1.0) * x.max_normal +
       momentum / (spec.time_stepping && spec.time_step > 0.0 ? spec.time_step : spec.t_end));
  // The values recorded just before an event are those at its located root,
  // where its root function (a flank normal force, the cone's margin) has
  // just changed sign: by up to its rate times the root's time resolution
  // (1e5 N/s and more with a flexible drive's stiff springs), and by a
  // whole jump where a load jumps (a callable's step). Those rows describe
  // the instant the mode ends, not a state of the mode: the pointwise force
  // checks skip them (the rows after the event are the new mode's).
  x.event_times.reserve(x.result.events.size());
  for (const integrate::Event& e : x.result.events) x.event_times.push_back(e.time);
  std::sort(x.event_times.begin(), x.event_times.end());
  // The slip velocity below which its sign is not resolved: the
  // integrator's tolerances on the velocities through |W_T| (atol, and rtol
  // of the largest slip), and round-off (time stepping: the step's slip is
  // its LCP's, exact up to round-off).
  x.slip_band = spec.time_stepping
                    ? 64.0 * kEpsilon * x.max_slip
                    : spec.slip_resolution + (spec.rtol + 64.0 * kEpsilon) * x.max_slip;
  // The root location's time resolution (CVODE's 100 ulp of the time; our
  // Runge-Kutta engines locate to 4 ulp): the slip velocity just before a
  // slip's end is its rate times that, on either side of zero.
  x.time_resolution = 128.0 * kEpsilon * spec.t_end;

  // The energies' round-off: the work of the run's largest force over the
  // round-off of its longest length (the positions' own resolution; a
  // stuck drive's round-off creep of 1e-20 m under 586 N books 8e-18 J of
  // work and nothing else).
  x.energy_round_off = 64.0 * kEpsilon * x.force_scale * spec.length_scale;
  // (at most kResolvedEnergyShare of the flow, whatever the tolerances:
  // K rtol E alone is the whole flow at rtol = 1e-3, and atol G with a
  // stiff contact's G far more; result_checks.md, "energy_balance")
  const double tolerance_error =
      kEnergyToleranceFactor *
      (std::max(spec.rtol, 64.0 * kEpsilon) * x.energy + spec.atol * x.gradient);
  x.integration_error =
      (spec.rows_are_steps ? std::min(tolerance_error, kResolvedEnergyShare * x.energy)
                           : tolerance_error) +
      x.energy_round_off;
}

// Whether row i is at an event's root (resolve_round_off).
bool at_event_root(const CheckContext& x, std::size_t i) {
  const double t = x.time[i];
  if (i + 1 < x.n && x.time[i + 1] == t) return true;  // before the event (every step)
  if (i > 0 && x.time[i - 1] == t) return false;        // after it
  // (a requested time)
  return std::binary_search(x.event_times.begin(), x.event_times.end(), t);
}

// The force checks' slip band per row into `band` (n doubles; < 0: a row at
// an event's root, skipped): what is resolved, plus the slip's rate toward
// its neighbours times the root's time resolution (not for time stepping).
void fill_slip_band(CheckContext& x, double* band) {
  x.band = band;
  if (!(x.power_applies || x.cone_applies || x.law_applies)) return;
  double rate_before = 0.0;  // |slip change| / dt over the interval to the row before
  for (std::size_t i = 0; i < x.n; ++i) {
    double rate_after = 0.0;
    if (i + 1 < x.n) {
      const double dt = std::abs(x.time[i + 1] - x.time[i]);
      if (dt > 0.0) rate_after = std::abs(x.slip[i + 1] - x.slip[i]) / dt;
    }
    const double rate = std::max(std::max(0.0, rate_before), rate_after);
    rate_before = rate_after;
    // (Moreau-Jean's first row precedes its first step: it reports no
    // step's forces, zero, which a preloaded nut's halves, bearing at every
    // instant, never have.)
    band[i] = at_event_root(x, i) || (x.spec.time_stepping && i == 0)
                  ? -1.0
                  : x.slip_band + (x.spec.time_stepping ? 0.0 : rate * x.time_resolution);
  }
}

// Pass 2: every pointwise check, one loop each (the worst row kept in row
// order, as one loop over the rows would).

// friction_power: lambda_T gamma_T <= |lambda_T| slip_band.
integrate::InvariantCheck check_friction_power(const CheckContext& x) {
  integrate::InvariantCheck power = make_check(
      "friction_power",
      "friction never does positive work: friction_force * slip_velocity <= |friction_force| "
      "times the slip velocity the integration resolves",
      "W");
  power.applies = x.power_applies;  // (describe_law)
  Worst worst{power};
  if (power.applies)
    for (std::size_t i = 0; i < x.n; ++i)
      if (x.band[i] >= 0.0) {
        worst.offer(x.friction_power(i),
                    x.friction_magnitude(i) * x.band[i] + x.slip_speed(i) * x.force_resolution,
                    x.time[i]);
      }
  return power;
}

// friction_loss: never falls by more than its integration error (and what
// friction may push within the slip band over the run).
integrate::InvariantCheck check_friction_loss(const CheckContext& x) {
  const ResultCheckSpec& spec = x.spec;
  integrate::InvariantCheck loss = make_check(
      "friction_loss", "the friction loss never falls (beyond its integration error)", "J");
  loss.applies = spec.friction_dissipates;
  const double loss_tolerance =
      spec.time_stepping
          ? 64.0 * kEpsilon * x.max_loss + x.energy_round_off
          : kEnergyToleranceFactor *
                    (std::max(spec.rtol, 64.0 * kEpsilon) * x.max_loss + spec.atol) +
                x.max_friction * x.slip_band * spec.t_end;
  Worst worst{loss};
  if (loss.applies) {
    double highest_loss = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < x.n; ++i) {
      highest_loss = std::max(highest_loss, x.friction_loss[i]);
      worst.offer(highest_loss - x.friction_loss[i], loss_tolerance, x.time[i]);
    }
  }
  return loss;
}

// friction_cone: |lambda_T| <= mu' |lambda_N| (exact Coulomb).
integrate::InvariantCheck check_friction_cone(const CheckContext& x) {
  integrate::InvariantCheck cone = make_check(
      "friction_cone",
      "|friction_force| <= mu_static' |normal_force| + viscous |slip_velocity| (Coulomb's cone)",
      "N");
  cone.applies = x.cone_applies;  // (describe_law)
  Worst worst{cone};
  if (cone.applies)
    for (std::size_t i = 0; i < x.n; ++i)
      if (x.band[i] >= 0.0)
        worst.offer(x.friction_magnitude(i) -
                        (x.cone_mu * x.normal[i] + x.viscous * x.slip_speed(i)),
                    x.force_resolution, x.time[i]);
  return cone;
}

// losses: damping, contact, impact (the friction loss has its own check).
integrate::InvariantCheck check_other_losses(const CheckContext& x) {
  const ResultCheckSpec& spec = x.spec;
  integrate::InvariantCheck other = make_check(
      "losses", "the other losses (damping, contact, impact; the train's motor_friction_loss "
                "and gear_loss) never fall (beyond their integration error)", "J");
  const std::size_t count = x.other_losses.size();
  std::vector<double> other_tolerance(count);
  for (std::size_t j = 0; j < count; ++j)
    other_tolerance[j] =
        spec.time_stepping
            ? 64.0 * kEpsilon * x.largest_loss[j] + x.energy_round_off
            : kEnergyToleranceFactor *
                  (std::max(spec.rtol, 64.0 * kEpsilon) * x.largest_loss[j] + spec.atol);
  Worst worst{other};
  if (count > 0) {
    std::vector<double> highest_other(count, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < x.n; ++i)
      for (std::size_t j = 0; j < count; ++j) {
        const double value = x.other_losses[j][i];
        highest_other[j] = std::max(highest_other[j], value);
        worst.offer(highest_other[j] - value, other_tolerance[j], x.time[i]);
      }
  }
  return other;
}

// friction_law of a set-valued law: slipping, not in stick and the slip
// beyond what is resolved. (The viscous term acts where the flanks touch:
// not in open play.) Plain Coulomb's slip coefficient is its mu at every
// speed.
void offer_set_valued_law(const CheckContext& x, Worst& worst) {
  const friction::Law& law = *x.spec.law;
  const double scale = x.spec.coefficient_scale;
  const bool plain = x.one_slip_coefficient;
  const double plain_mu = law.mu();
  for (std::size_t i = 0; i < x.n; ++i) {
    const double speed = x.slip_speed(i);
    if (x.band[i] < 0.0 || x.stick[i] != 0.0 || !(speed > x.band[i])) continue;
    const double normal_force = x.normal[i];
    const double expected = (plain ? plain_mu : law.slip_mu(speed)) * scale * normal_force +
                            (normal_force > 0.0 ? x.viscous * speed : 0.0);
    worst.offer(std::abs(expected - x.friction_magnitude(i)), x.force_resolution, x.time[i]);
  }
}

// friction_law of a velocity law (eq. 3.16), at every row.
void offer_velocity_law(const CheckContext& x, Worst& worst) {
  const friction::Law& law = *x.spec.law;
  const double scale = x.spec.coefficient_scale;
  for (std::size_t i = 0; i < x.n; ++i) {
    if (x.band[i] < 0.0) continue;
    const double v = x.slip[i], normal_force = x.normal[i];
    const double expected = -law.velocity_coefficient(v) * scale * normal_force -
                            (normal_force > 0.0 ? x.viscous * v : 0.0);
    worst.offer(std::abs(x.friction[i] - expected), x.force_resolution, x.time[i]);
  }
}

// friction_law: where the contact slips, the friction force is the law's.
integrate::InvariantCheck check_friction_law(const CheckContext& x) {
  integrate::InvariantCheck law = make_check(
      "friction_law",
      "where it slips, the friction force is the law's: mu(|slip_velocity|)' |normal_force| "
      "+ viscous |slip_velocity| (where the flanks touch) against the slip (set-valued laws), "
      "-kappa(slip_velocity)' "
      "|normal_force| - viscous slip_velocity (velocity laws, eq. 3.16)",
      "N");
  law.applies = x.law_applies;  // (describe_law)
  Worst worst{law};
  if (law.applies) {
    if (x.set_valued)
      offer_set_valued_law(x, worst);
    else
      offer_velocity_law(x, worst);
  }
  return law;
}

// flank_gap: exact play, the nut never passes a flank.
integrate::InvariantCheck check_flank_gap(const CheckContext& x) {
  const ResultCheckSpec& spec = x.spec;
  integrate::InvariantCheck flank = make_check(
      "flank_gap", "the nut never passes a flank of the play (gap >= 0)", "m");
  flank.applies = spec.clearance > 0.0 && x.gap_index >= 0;
  // The free flight's own check (drive/hybrid_impacts.cpp, kFlankTolerance)
  // allows 1e-3 of the clearance; Moreau-Jean closes a flank at the
  // velocity level, up to three steps of the play's motion late (and a
  // play that drifts beyond that through its flank is a step too long).
  double gap_tolerance = 1e-3 * spec.clearance + 10.0 * spec.atol;
  if (spec.time_stepping)
    gap_tolerance = std::min(spec.clearance, gap_tolerance + 3.0 * spec.time_step * x.play_rate);
  Worst worst{flank};
  if (flank.applies)
    for (std::size_t i = 0; i < x.n; ++i) worst.offer(-x.gap[i], gap_tolerance, x.time[i]);
  return flank;
}

// energy_balance.
integrate::InvariantCheck check_energy_balance(const CheckContext& x) {
  const ResultCheckSpec& spec = x.spec;
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
          ? kTimeSteppingCreation * x.energy +
                std::min(spec.step_friction_excess, kFrictionBookingShare * x.energy) +
                x.energy_round_off
          : x.integration_error;
  Worst worst{balance};
  for (std::size_t i = 0; i < x.n; ++i)
    worst.offer(spec.time_stepping ? -x.residual[i] : std::abs(x.residual[i]), balance_bound,
                x.time[i]);
  return balance;
}

}  // namespace

void check_result(const ResultCheckSpec& spec, integrate::SimulationResult& result) {
  // The channels in columns, the run's scales (largest forces, energies,
  // slip), then every pointwise check.
  std::vector<integrate::InvariantCheck>& checks = result.checks;
  checks.clear();
  checks.reserve(11);  // (with check_bristle_bound's two)
  checks.push_back(check_finite(result));
  if (!checks.back().passed) return;  // the others would compare NaNs
  checks.push_back(check_event_times(spec, result));

  const std::size_t n = result.point_count();
  // The columns (ChannelColumns), the friction and normal forces, the
  // energy flow and the slip band in one buffer (ScratchBuffer).
  ScratchBuffer scratch(n * (result.channel_count() + 1) +
                        (spec.transverse_friction.empty() ? 4 : 5) * n);
  ChannelColumns columns(result, scratch.data());
  double* const extra = scratch.data() + n * (result.channel_count() + 1);
  CheckContext context(spec, result);
  read_columns(context, columns, extra);
  describe_law(context);
  // (a transverse slip's friction after the two forces)
  double* const scales = extra + (spec.transverse_friction.empty() ? 2 : 3) * n;
  measure_scales(context, columns, scales);
  resolve_round_off(context);
  fill_slip_band(context, scales + n);

  checks.push_back(check_friction_power(context));
  checks.push_back(check_friction_loss(context));
  checks.push_back(check_friction_cone(context));
  checks.push_back(check_other_losses(context));
  checks.push_back(check_friction_law(context));
  checks.push_back(check_flank_gap(context));
  checks.push_back(check_energy_balance(context));
  check_bristle_bound(spec, result);
}

}  // namespace leadscrew::model
