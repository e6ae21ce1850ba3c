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

// The systems. `law` outlives the system.
std::unique_ptr<integrate::HybridSystem> make_exact_block(const FrictionBlock& block,
                                                          const friction::Law& law);
std::unique_ptr<integrate::HybridSystem> make_regularized_block(const FrictionBlock& block,
                                                                const friction::Law& law);
std::unique_ptr<integrate::HybridSystem> make_smooth_block(const FrictionBlock& block,
                                                           const friction::Law& law);
std::unique_ptr<integrate::TimeSteppingSystem> make_moreau_block(const FrictionBlock& block,
                                                                 const friction::Law& law);

}  // namespace leadscrew::model::block
