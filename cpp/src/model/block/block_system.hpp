// The friction block's systems (model/friction_block.hpp), one file each:
// exact_block.cpp (set-valued laws, event-driven), regularized_block.cpp (the
// arctan laws of the thesis, a fast path), smooth_block.cpp (velocity laws and
// LuGre), moreau_block.cpp (set-valued laws, Moreau-Jean); what they share is
// here. Internal to cpp/src/model.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "leadscrew/friction/law.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/integrate/moreau.hpp"
#include "leadscrew/model/friction_block.hpp"

namespace leadscrew::model::block {

// State: position, velocity, the two work integrals, and LuGre's bristle
// state (kBristle: the deflection over friction::Law::bristle_range) where
// the law has it.
enum State { kPosition = 0, kVelocity = 1, kWorkForce = 2, kFrictionLoss = 3, kStateSize = 4 };
constexpr int kBristle = 4;
// A block with a transverse slip (cone_block.cpp): the transverse
// excitation's work, lambda_transverse w, after the four (no bristles).
constexpr int kTransverseWork = 4;
constexpr int kConeStateSize = 5;

// The channels of a block's result (the bristle deflection last, for LuGre).
const std::vector<std::string>& channel_names(bool bristle);

// One output row besides the state.
struct Row {
  double force = 0.0;         // F_Exc(t)
  double acceleration = 0.0;
  double friction = 0.0;      // lambda_T (opposing +u)
  bool stick = false;
  double bristle_energy = 0.0;  // LuGre's |N| sigma0 z^2 / 2
  double bristle_deflection = 0.0;  // LuGre's z [m]
};

// Writes a row of channel_names(bristle): the state y at t, and `row`.
// `elastic0` is the elastic energy at t = 0.
void write_channels(const FrictionBlock& block, double kinetic0, double elastic0, double t,
                    const double* y, const Row& row, bool bristle, double* out);

// The channels of a block with a transverse slip: channel_names(false),
// then transverse_velocity (w), transverse_friction (lambda along +w) and
// work_transverse; write_cone_channels writes them, energy_residual with the
// transverse work.
const std::vector<std::string>& cone_channel_names();
void write_cone_channels(const FrictionBlock& block, double kinetic0, double t, const double* y,
                         const Row& row, double transverse_velocity, double transverse_friction,
                         double* out);

// The times at which a block with a transverse slip is not smooth: its
// loads' breakpoints, merged.
std::vector<double> cone_breakpoints(const FrictionBlock& block);

// Kinetic and elastic energy at the start.
double initial_kinetic(const FrictionBlock& block);

// The load F(t) with a one-entry memo. Evaluations repeat their time: the
// last two stages of Dormand-Prince share t_n + h, the root functions and the
// output are evaluated at the step end, where the last stage was.
class LoadAtTime {
 public:
  explicit LoadAtTime(const Excitation& load) : load_(load) {}
  double operator()(double t) {
    if (t != time_) {  // always true for the initial NaN
      value_ = load_(t);
      time_ = t;
    }
    return value_;
  }

 private:
  const Excitation& load_;
  double time_ = std::numeric_limits<double>::quiet_NaN();
  double value_ = 0.0;
};

// The work integrand of the applied forces: F v plus the spring's moving end,
// F_spring V.
inline double applied_power(const FrictionBlock& block, double force, double spring,
                            double velocity) {
  return force * velocity + spring * block.pull_speed;
}

// A Moreau-Jean step's friction-free part (the spring implicit with the
// theta method, as the drive's springs): W v+ = m v + h (F + F_spring(t +
// theta h, u)) - theta (1 - theta) h^2 k v - impulse, W = m + theta^2 h^2 k.
struct MoreauFreeStep {
  double force;          // F(t + theta h)
  double spring_start;   // F_spring(t + theta h, u)
  double mass;           // W
  double free_velocity;  // v+ without the friction impulse
};
inline MoreauFreeStep moreau_free_step(const FrictionBlock& block, double t, double h,
                                       double theta, const double* y) {
  MoreauFreeStep s;
  s.force = block.force(t + theta * h);
  const double k = block.stiffness;
  s.spring_start = block.spring_force(t + theta * h, y[kPosition]);
  s.mass = block.mass + theta * theta * h * h * k;
  s.free_velocity = (block.mass * y[kVelocity] + h * (s.force + s.spring_start) -
                     theta * (1.0 - theta) * h * h * k * y[kVelocity]) /
                    s.mass;
  return s;
}

// The step's end from the new velocity: the position by the theta method,
// the applied forces' work (the spring's force at the step's theta point,
// the pulled end's work).
inline void moreau_advance(const FrictionBlock& block, const MoreauFreeStep& s, double h,
                           double theta, double velocity, const double* y, double* y_next) {
  y_next[kVelocity] = velocity;
  const double v_theta = (1.0 - theta) * y[kVelocity] + theta * velocity;
  y_next[kPosition] = y[kPosition] + h * v_theta;
  const double spring = s.spring_start - block.stiffness * theta * h * v_theta;
  y_next[kWorkForce] = y[kWorkForce] + s.force * (y_next[kPosition] - y[kPosition]) +
                       spring * block.pull_speed * h;
}

// The systems. `law` outlives the system.
std::unique_ptr<integrate::HybridSystem> make_exact_block(const FrictionBlock& block,
                                                          const friction::Law& law);
std::unique_ptr<integrate::HybridSystem> make_regularized_block(const FrictionBlock& block,
                                                                const friction::Law& law);
std::unique_ptr<integrate::HybridSystem> make_smooth_block(const FrictionBlock& block,
                                                           const friction::Law& law);
std::unique_ptr<integrate::TimeSteppingSystem> make_moreau_block(const FrictionBlock& block,
                                                                 const friction::Law& law);
// With a transverse slip (block.has_transverse()): a set-valued law's cone.
std::unique_ptr<integrate::HybridSystem> make_cone_block(const FrictionBlock& block,
                                                         const friction::Law& law);
std::unique_ptr<integrate::TimeSteppingSystem> make_moreau_cone_block(const FrictionBlock& block,
                                                                      const friction::Law& law);
// LuGre's bristles as a 2-D vector (cone_bristle_block.cpp): state
// kConeStateSize + 2, the bristles' channels after the cone's.
std::unique_ptr<integrate::HybridSystem> make_cone_bristle_block(const FrictionBlock& block,
                                                                 const friction::Law& law);

}  // namespace leadscrew::model::block
