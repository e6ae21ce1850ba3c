#include "leadscrew/model/elements/thread_pair.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "leadscrew/model/drive.hpp"

namespace leadscrew::model::elements {

namespace {

void add_gradient(Eigen::VectorXd& gradient, int index, double value) {
  if (index >= 0) gradient[index] += value;
}

// Adams' cubic STEP from 0 at x <= 0 to 1 at x >= 1.
double smooth_step(double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  return x * x * (3.0 - 2.0 * x);
}

}  // namespace

std::shared_ptr<const friction::Law> ThreadPair::make_law(const DriveParameters& p) {
  const friction::LawType& type = friction::law_type(p.friction);
  friction::LawValues values = {{"mu", p.mu}};
  for (const friction::ParameterInfo& parameter : type.parameters)
    if (std::string(parameter.key) == "k_v") values.emplace_back("k_v", p.k_v);
  values.insert(values.end(), p.friction_values.begin(), p.friction_values.end());
  return friction::make_law(p.friction, values);
}

ThreadPair::ThreadPair(const DriveParameters& p, std::shared_ptr<const friction::Law> law,
                       const ContactCoordinates& c, int n)
    : contact_(p.backlash),
      bilateral_(p.backlash == BacklashContact::none),
      penalty_(p.backlash == BacklashContact::bistop || p.backlash == BacklashContact::cubic),
      exact_play_(p.backlash == BacklashContact::exact),
      bistop_(p.backlash == BacklashContact::bistop),
      clearance_(p.clearance),
      stiffness_(p.contact_stiffness),
      exponent_(p.contact_exponent),
      damping_(p.contact_damping),
      depth_(p.contact_penetration),
      play_position_(p.play_position),
      nut_position_(p.nut_position),
      cos_lead_(std::cos(p.thread.lead_angle())),
      law_(std::move(law)) {
  position_gradient_ = Eigen::VectorXd::Zero(n);
  add_gradient(position_gradient_, c.nut_u, 1.0);
  add_gradient(position_gradient_, c.screw_u, -1.0);

  const double h = p.thread.hand_sign();
  const double lead_per_radian = p.thread.lead_per_radian();
  const double r_m = p.thread.mean_radius();
  const double alpha = p.thread.lead_angle();
  play_gradient_ = Eigen::VectorXd::Zero(n);
  add_gradient(play_gradient_, c.screw_u, 1.0);
  add_gradient(play_gradient_, c.nut_u, -1.0);
  add_gradient(play_gradient_, c.screw_phi, -h * lead_per_radian);
  add_gradient(play_gradient_, c.nut_phi, h * lead_per_radian);
  normal_ = std::cos(alpha) * play_gradient_;
  tangent_ = Eigen::VectorXd::Zero(n);
  add_gradient(tangent_, c.screw_u, std::sin(alpha));
  add_gradient(tangent_, c.nut_u, -std::sin(alpha));
  add_gradient(tangent_, c.screw_phi, h * r_m * std::cos(alpha));
  add_gradient(tangent_, c.nut_phi, -h * r_m * std::cos(alpha));
  mu_eff_ = p.thread.effective_mu(p.mu);
  flank_factor_ = p.mu > 0.0 ? mu_eff_ / p.mu : p.thread.effective_mu(1.0);

  // Without play the thread is a kinematic constraint e = 0: eliminate a
  // translational coordinate of the thread pair (the nut's, as the thesis
  // eliminates u_2 in eq. 4.9 and 4.13), keeping the rotor independent.
  if (bilateral_) {
    for (int candidate : {c.nut_u, c.screw_u, c.nut_phi, c.screw_phi}) {
      if (candidate > 0 && play_gradient_[candidate] != 0.0) {
        eliminated_ = candidate;
        break;
      }
    }
    if (eliminated_ < 0) eliminated_ = 0;
  }
}

double ThreadPair::flank_force(double penetration) const noexcept {
  const double k = stiffness_;
  const double depth = depth_;
  // Adams BISTOP: k d^e (its damping ramped in over the penetration depth).
  if (bistop_) return k * std::pow(penetration, exponent_);
  // Cubic onset joining the linear spring k with matching slope at the
  // depth: a C1 approximation of the dead zone with walls (thesis Fig. 2.6).
  if (penetration < depth) return k * penetration * penetration * penetration / (3.0 * depth * depth);
  return k * (penetration - depth) + k * depth / 3.0;
}

void ThreadPair::penalty_force(double play, double play_rate, Penalty& out) const {
  out.normal_force = 0.0;
  out.penetration[0] = out.penetration[1] = 0.0;
  out.loss_power = 0.0;
  if (!penalty_) return;
  const double half = 0.5 * clearance_;
  const double depth = depth_;
  double axial = 0.0;  // generalized force along grad e
  for (int flank = 0; flank < 2; ++flank) {
    const double sign = flank == 0 ? 1.0 : -1.0;  // upper flank e = +c/2, lower e = -c/2
    const double penetration = sign * play - half;
    if (penetration <= 0.0) continue;
    out.penetration[flank] = penetration;
    const double rate = sign * play_rate;
    const double elastic_force = flank_force(penetration);
    double force = elastic_force + damping_ * smooth_step(penetration / depth) * rate;
    if (force < 0.0) force = 0.0;  // flanks push, they do not pull
    axial -= sign * force;
    out.loss_power += (force - elastic_force) * rate;
  }
  out.normal_force = axial / cos_lead_;
}

double ThreadPair::contact_energy(const double penetration[2]) const noexcept {
  const double k = stiffness_;
  const double depth = depth_;
  double energy = 0.0;
  for (int flank = 0; flank < 2; ++flank) {
    const double d = penetration[flank];
    if (d <= 0.0) continue;
    // The potentials of penalty_force's elastic forces.
    if (bistop_) {
      energy += k * std::pow(d, exponent_ + 1.0) / (exponent_ + 1.0);
    } else if (d < depth) {
      energy += k * std::pow(d, 4) / (12.0 * depth * depth);
    } else {
      const double beyond = d - depth;
      energy += k * depth * depth / 12.0 + k * depth * beyond / 3.0 + 0.5 * k * beyond * beyond;
    }
  }
  return energy;
}

namespace {

// The penetrated flank at the play e: its sign (+1 upper, -1 lower, 0 none)
// and its penetration d = |e| - c/2 > 0.
int penetrated_flank(double play, double half, double& penetration) noexcept {
  penetration = std::abs(play) - half;
  if (!(penetration > 0.0)) return 0;
  return play > 0.0 ? 1 : -1;
}

}  // namespace

double ThreadPair::flank_potential(double play) const noexcept {
  double d = 0.0;
  const int flank = penetrated_flank(play, 0.5 * clearance_, d);
  if (!penalty_ || flank == 0) return 0.0;
  const double penetration[2] = {flank > 0 ? d : 0.0, flank < 0 ? d : 0.0};
  return contact_energy(penetration);
}

double ThreadPair::flank_slope(double play) const noexcept {
  double d = 0.0;
  const int flank = penetrated_flank(play, 0.5 * clearance_, d);
  if (!penalty_ || flank == 0) return 0.0;
  return flank * flank_force(d);
}

double ThreadPair::flank_curvature(double play) const noexcept {
  double d = 0.0;
  const int flank = penetrated_flank(play, 0.5 * clearance_, d);
  if (!penalty_ || flank == 0) return 0.0;
  if (bistop_) return stiffness_ * exponent_ * std::pow(d, exponent_ - 1.0);
  if (d < depth_) return stiffness_ * d * d / (depth_ * depth_);
  return stiffness_;
}

double ThreadPair::flank_damping(double play) const noexcept {
  double d = 0.0;
  const int flank = penetrated_flank(play, 0.5 * clearance_, d);
  if (!penalty_ || flank == 0) return 0.0;
  return damping_ * smooth_step(d / depth_);
}

double ThreadPair::penetration_for(double force) const {
  if (force <= 0.0) return 0.0;
  const double k = stiffness_;
  if (bistop_) return std::pow(force / k, 1.0 / exponent_);
  const double depth = depth_;
  if (force < k * depth / 3.0) return std::cbrt(3.0 * depth * depth * force / k);
  return depth + (force - k * depth / 3.0) / k;
}

}  // namespace leadscrew::model::elements
