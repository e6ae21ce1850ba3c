// The result checks of LuGre's bristles (docs/physics/result_checks.md,
// "bristle_bound"): the deflection stays inside the set the law leaves
// invariant, and so the friction inside LuGre's largest force.
#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/model/result_checks.hpp"
#include "check_rows.hpp"

namespace leadscrew::model {

namespace {

// The integrators carry w = z / range, a state of size 1
// (Law::bristle_range), whose local error each step keeps within
// rtol |w| + atol <= rtol + atol. Where the bristles saturate, the flow
// contracts onto the boundary within mu / (sigma0 |gamma|), far below a
// step: BDF's steps overshoot it by up to 44 such errors, its interpolation
// at requested times by up to 206 (thesis drive, sigma0 1e4 ... 1e6, rtol
// 1e-10 ... 1e-3; result_checks.md, "bristle_bound").
constexpr double kBristleResolution = 1e3;

// The bristles as a 2-D vector (a transverse slip, the friction block's
// cone_bristle_block.cpp): the same bounds on the magnitudes, |z| over both
// components, |lambda| against N (sigma0 z_bound + sigma1 |z'|) + viscous
// |gamma|, z' = gamma - sigma0 |gamma| z / mu(|gamma|) from the row.
void check_planar_bristles(const ResultCheckSpec& spec, const integrate::SimulationResult& result,
                           double z_bound, double force_resolution, check_rows::Worst& deflection,
                           check_rows::Worst& force) {
  const friction::Law& law = *spec.law;
  const std::size_t n = result.point_count(), width = result.channel_count();
  const int columns[] = {result.channel_index("bristle_deflection"),
                         result.channel_index("bristle_deflection_transverse"),
                         result.channel_index(spec.slip),
                         result.channel_index(spec.transverse_slip),
                         result.channel_index(spec.friction),
                         result.channel_index(spec.transverse_friction),
                         result.channel_index(spec.normal)};
  double row[7];
  const double sigma0 = law.bristle_stiffness(), sigma1 = law.bristle_damping();
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 7; ++k)
      row[k] = columns[k] < 0 ? 0.0 : result.values[i * width + static_cast<std::size_t>(columns[k])];
    const double speed = std::hypot(row[2], row[3]);
    const double relaxation = sigma0 * speed / law.slip_mu(speed);
    const double rate = std::hypot(row[2] - relaxation * row[0], row[3] - relaxation * row[1]);
    const double normal = std::abs(row[6]) * spec.coefficient_scale;
    deflection.offer(std::hypot(row[0], row[1]), z_bound, result.time[i]);
    force.offer(std::hypot(row[4], row[5]),
                normal * (sigma0 * z_bound + sigma1 * rate) + law.viscous() * speed +
                    force_resolution,
                result.time[i]);
  }
}

}  // namespace

void check_bristle_bound(const ResultCheckSpec& spec, integrate::SimulationResult& result) {
  integrate::InvariantCheck deflection = check_rows::make_check(
      "bristle_bound",
      "|bristle_deflection| <= max(mu, mu_static) / sigma0, the set LuGre's bristle law leaves "
      "invariant from rest (within the integration's resolution of the bristle state)",
      "m");
  integrate::InvariantCheck force = check_rows::make_check(
      "bristle_friction",
      "|friction_force| <= max(mu, mu_static)' |normal_force| + sigma1' |normal_force| |z'| + "
      "viscous |slip_velocity| (LuGre's largest friction, from the bristles' bound)",
      "N");
  // (the law first: the other laws' runs pay no channel lookup)
  const bool bristle = spec.law && spec.law->resolution() == friction::Resolution::bristle;
  const int z_index = bristle ? result.channel_index("bristle_deflection") : -1;
  deflection.applies = force.applies = z_index >= 0;
  if (deflection.applies) {
    const friction::Law& law = *spec.law;
    const std::size_t n = result.point_count(), width = result.channel_count();
    const int slip_index = result.channel_index(spec.slip),
              friction_index = result.channel_index(spec.friction),
              normal_index = result.channel_index(spec.normal);
    const auto at = [&](std::size_t i, int k) {  // (an absent channel reads 0)
      return k < 0 ? 0.0 : result.values[i * width + static_cast<std::size_t>(k)];
    };
    const double z_bound = law.bristle_range() *
                           (1.0 + kBristleResolution * (spec.rtol + spec.atol) +
                            64.0 * std::numeric_limits<double>::epsilon());
    double largest_friction = 0.0, largest_normal = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      largest_friction = std::max(largest_friction, std::abs(at(i, friction_index)));
      largest_normal = std::max(largest_normal, std::abs(at(i, normal_index)));
    }
    // The forces' round-off (as result_checks.cpp's force resolution).
    const double force_resolution =
        kForceResolution *
        (largest_friction + law.max_mu() * spec.coefficient_scale * largest_normal);
    check_rows::Worst worst_deflection{deflection}, worst_force{force};
    if (!spec.transverse_friction.empty()) {  // the 2-D bristles of a transverse slip
      check_planar_bristles(spec, result, z_bound, force_resolution, worst_deflection,
                            worst_force);
      result.checks.push_back(deflection);
      result.checks.push_back(force);
      return;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double t = result.time[i], z = at(i, z_index), slip = at(i, slip_index);
      worst_deflection.offer(std::abs(z), z_bound, t);
      // |N|' of the row (a preloaded nut's halves: flank_normal)
      const double friction = spec.friction_sign * at(i, friction_index);
      const double normal = (spec.flank_normal ? spec.flank_normal(at(i, normal_index), friction)
                                               : std::abs(at(i, normal_index))) *
                            spec.coefficient_scale;
      // sigma1 z': the law's coefficient sigma0 z + sigma1 z' less sigma0 z
      const double damping =
          std::abs(law.bristle_coefficient(slip, z) - law.bristle_stiffness() * z);
      worst_force.offer(std::abs(friction),
                        normal * (law.bristle_stiffness() * z_bound + damping) +
                            law.viscous() * std::abs(slip) + force_resolution,
                        t);
    }
  }
  result.checks.push_back(deflection);
  result.checks.push_back(force);
}

}  // namespace leadscrew::model
