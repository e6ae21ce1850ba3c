#include "leadscrew/thread/thread.hpp"

#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew {

namespace {
constexpr double kPi = 3.14159265358979323846;

void validate_friction(double mu, double collar_mu, double collar_diameter) {
  require_nonnegative("mu", mu);
  require_nonnegative("collar_mu", collar_mu);
  require_nonnegative("collar_diameter", collar_diameter);
}

// tan(alpha) + mu' and 1 - mu' tan(alpha): numerator and denominator of the
// thread's raise torque per unit load and radius, tan(alpha + rho') with
// tan(rho') = mu'.
struct WedgeTerms {
  double tan_alpha;
  double mu_eff;
};

WedgeTerms wedge(const Thread& thread, double mu) {
  return {std::tan(thread.lead_angle()), thread.effective_mu(mu)};
}
}  // namespace

Thread::Thread(double pitch, double mean_diameter, int starts, double flank_angle, Hand hand)
    : pitch_(require_positive("pitch", pitch)),
      mean_diameter_(require_positive("mean_diameter", mean_diameter)),
      starts_(starts),
      flank_angle_(require_in_range("flank_angle", flank_angle, 0.0, kPi, false, true)),
      hand_(hand),
      lead_angle_(0.0) {
  if (starts < 1)
    throw InvalidArgument("starts = " + std::to_string(starts) +
                          " is invalid: must be an integer >= 1");
  lead_angle_ = std::atan(lead() / (kPi * mean_diameter_));
}

double Thread::lead_per_radian() const noexcept { return lead() / (2.0 * kPi); }

double Thread::flank_factor() const noexcept { return 1.0 / std::cos(0.5 * flank_angle_); }

double Thread::effective_mu(double mu) const {
  return require_nonnegative("mu", mu) * flank_factor();
}

Hand parse_hand(const std::string& hand) {
  return require_choice("hand", hand, {"right", "left"}) == 0 ? Hand::right : Hand::left;
}

std::string hand_name(Hand hand) { return hand == Hand::right ? "right" : "left"; }

double raise_torque(const Thread& thread, double mu, double load, double collar_mu,
                    double collar_diameter) {
  validate_friction(mu, collar_mu, collar_diameter);
  require_nonnegative("load", load);
  const WedgeTerms w = wedge(thread, mu);
  const double denominator = 1.0 - w.mu_eff * w.tan_alpha;
  if (!(denominator > 0.0)) return std::numeric_limits<double>::infinity();
  const double thread_torque =
      load * thread.mean_radius() * (w.tan_alpha + w.mu_eff) / denominator;
  return thread_torque + load * collar_mu * 0.5 * collar_diameter;
}

double lower_torque(const Thread& thread, double mu, double load, double collar_mu,
                    double collar_diameter) {
  validate_friction(mu, collar_mu, collar_diameter);
  require_nonnegative("load", load);
  const WedgeTerms w = wedge(thread, mu);
  // tan(rho' - alpha): the denominator 1 + mu' tan(alpha) is always positive.
  const double thread_torque = load * thread.mean_radius() * (w.mu_eff - w.tan_alpha) /
                               (1.0 + w.mu_eff * w.tan_alpha);
  return thread_torque + load * collar_mu * 0.5 * collar_diameter;
}

double efficiency(const Thread& thread, double mu, double collar_mu, double collar_diameter,
                  bool backdrive) {
  validate_friction(mu, collar_mu, collar_diameter);
  const WedgeTerms w = wedge(thread, mu);
  // Per unit load the useful torque is r_m tan(alpha) = lead / (2 pi).
  const double useful = thread.mean_radius() * w.tan_alpha;
  const double collar = collar_mu * 0.5 * collar_diameter;
  if (!backdrive) {
    const double denominator = 1.0 - w.mu_eff * w.tan_alpha;
    if (!(denominator > 0.0)) return 0.0;
    const double torque = thread.mean_radius() * (w.tan_alpha + w.mu_eff) / denominator + collar;
    return useful / torque;
  }
  const double torque = thread.mean_radius() * (w.mu_eff - w.tan_alpha) /
                            (1.0 + w.mu_eff * w.tan_alpha) +
                        collar;
  return -torque / useful;
}

bool is_self_locking(const Thread& thread, double mu) {
  const WedgeTerms w = wedge(thread, mu);
  // Same expression as the sign of lower_torque's thread term.
  return w.mu_eff - w.tan_alpha > 0.0;
}

bool is_drivable(const Thread& thread, double mu) {
  const WedgeTerms w = wedge(thread, mu);
  // mu' < cot(alpha)  <=>  1 - mu' tan(alpha) > 0 (tan(alpha) > 0): the same
  // expression as raise_torque's denominator.
  return 1.0 - w.mu_eff * w.tan_alpha > 0.0;
}

}  // namespace leadscrew
