// Friction laws as types: every law of a contact behind one interface, listed
// in one registry (cpp/src/friction/registry.cpp), from which the scene
// schema, describe_schema() and leadscrew.friction_laws() take the laws,
// their parameters, units, defaults and ranges (docs/physics/
// friction_laws.md describes them in words). A new law is one source file under
// cpp/src/friction/laws/ and one line of the registry.
//
// A law gives the friction force of a contact from its flank normal force
// |N| (the flank angle applied: mu' = mu / cos(beta / 2) of the thread's
// normal force), its slip velocity gamma and, where the law has them, its
// slip acceleration or internal states. Its resolution says how the drivers
// treat it:
//   set_valued    exact at zero slip: stick while |T| <= mu_static |N|,
//                 slip at mu(|gamma|) |N| + viscous |gamma| against the slip
//                 (exact Coulomb, thesis eq. 2.17; Stribeck's curve): the
//                 event-driven scheme's modes and LCP, Moreau-Jean;
//   velocity      T = -kappa(gamma) |N| - viscous gamma, a smooth function
//                 of the slip velocity (eq. 3.16; a set-valued law run by an
//                 ODE integrator through its regularization, regularized());
//   acceleration  kappa of the slip acceleration (eq. 3.15), solved inside
//                 the right-hand side;
//   bristle       LuGre: one internal state z per contact,
//                 z' = gamma - sigma0 |gamma| z / mu(|gamma|),
//                 T = -|N| (sigma0 z + sigma1 z') - viscous gamma.
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace leadscrew {

// 2/pi of the arctan laws lambda_T = (2/pi) mu' lambda_N atan(k_V x), eq. (3.15)/(3.16).
constexpr double kTwoOverPi = 0.63661977236758134308;

}  // namespace leadscrew

namespace leadscrew::friction {

enum class Resolution { set_valued, velocity, acceleration, bristle };

// One parameter of a law, as a scene's friction section gives it.
struct ParameterInfo {
  const char* key;   // e.g. "mu", "k_v"
  const char* unit;  // SI, "" for a pure number
  const char* doc;
  // The default: a number, or NaN with `default_from` another key whose
  // value it takes (mu_static: mu), or NaN and nullptr: required.
  double default_value = std::numeric_limits<double>::quiet_NaN();
  const char* default_from = nullptr;
  double low = 0.0, high = std::numeric_limits<double>::infinity();
  bool low_open = false, high_open = false;
  // Another key this one may not fall below (mu_static >= mu).
  const char* at_least = nullptr;
};

// Parameter values by key (what a scene or a block gives; make_law checks
// them against the law's ParameterInfo and fills the defaults).
using LawValues = std::vector<std::pair<std::string, double>>;

class Law;

// A law of the registry: its name, what it is, its parameters, which
// integrators fit it, and how to make it.
struct LawType {
  const char* name;
  const char* doc;
  std::vector<ParameterInfo> parameters;
  // Which integrators fit: the event-driven scheme always; Moreau-Jean's
  // time stepping (set-valued laws); the ODE methods (smooth laws, and
  // set-valued ones through their regularization). The default: the
  // event-driven scheme for a set-valued law, else the first ODE method.
  bool time_stepping = false;
  bool ode = false;
  // Makes the law from complete values (in the order of `parameters`).
  std::unique_ptr<Law> (*make)(const std::vector<double>& values);
};

class Law {
 public:
  virtual ~Law() = default;
  virtual Resolution resolution() const = 0;
  // Coefficients of the flank normal force.
  virtual double mu() const = 0;                          // kinetic
  virtual double mu_static() const { return mu(); }        // the stick limit
  virtual double slip_mu(double /*speed*/) const { return mu(); }  // in slip at |gamma|
  virtual double viscous() const { return 0.0; }           // [N s/m]
  // The largest coefficient the law reaches (the Painleve condition's).
  virtual double max_mu() const { return std::max(mu(), mu_static()); }
  // velocity: the signed coefficient kappa(gamma), |kappa| < max_mu.
  virtual double velocity_coefficient(double /*slip*/) const { return 0.0; }
  // acceleration: kappa of the slip acceleration.
  virtual double acceleration_coefficient(double /*slip_acceleration*/) const { return 0.0; }
  // The regularization gain of the velocity and acceleration laws [s/m, s^2/m].
  virtual double gain() const { return 0.0; }
  // bristle: z' and the coefficient sigma0 z + sigma1 z' at (gamma, z).
  virtual double bristle_rate(double /*slip*/, double /*z*/) const { return 0.0; }
  virtual double bristle_coefficient(double /*slip*/, double /*z*/) const { return 0.0; }
  virtual double bristle_stiffness() const { return 0.0; }  // sigma0 [1/m]
  virtual double bristle_damping() const { return 0.0; }    // sigma1 [s/m]
  // The largest deflection the bristles reach from rest [m],
  // max(mu, mu_static) / sigma0 (0: no bristles): the set |z| <= it is
  // invariant under z' = gamma - sigma0 |gamma| z / mu(|gamma|), since on
  // its boundary z' points inward wherever mu(|gamma|) <= max(mu, mu_static).
  // The integrators carry z / bristle_range(), a state of size 1, whose
  // error they control at its own scale (docs/physics/friction_laws.md).
  virtual double bristle_range() const { return 0.0; }
  // The law's own part of the energy account, per unit normal force: the
  // energy its internal state stores (LuGre's bristles, sigma0 z^2 / 2 [m])
  // and the power of the friction that goes into it rather than into the
  // loss (sigma0 z z' [m/s]); 0 for a law without such a state.
  virtual double stored_energy(double /*z*/) const { return 0.0; }
  virtual double storing_power(double /*slip*/, double /*z*/) const { return 0.0; }
  // The law's own internal states, by name, in the order a run carries them
  // (the thread pair that runs it declares them into the run's state vector;
  // LuGre's: its deflection as a share of bristle_range(), and the energy
  // its bristles store); none for a law without (drive/declaration.hpp).
  virtual std::vector<const char*> state_names() const { return {}; }
  // A set-valued law run by an ODE integrator: its velocity law (nullptr:
  // none, the law needs the event-driven scheme or Moreau-Jean).
  virtual std::unique_ptr<Law> regularized() const { return nullptr; }
  // True if the law exerts no force at all: no coefficient (mu = mu_static
  // = 0) and no viscous term. Only then has a touching flank no friction
  // modes; mu = 0 alone leaves a static coefficient's stick and the viscous
  // force -viscous gamma (docs/physics/friction_laws.md).
  bool frictionless() const { return max_mu() == 0.0 && viscous() == 0.0; }
  // True if the law is exact Coulomb with one coefficient (mu_static = mu,
  // no viscous term): the thesis's single LCP decides stick and slip.
  bool plain_coulomb() const {
    return resolution() == Resolution::set_valued && mu_static() == mu() && viscous() == 0.0 &&
           slip_mu(1.0) == mu() && slip_mu(0.0) == mu();
  }
};

// The registry, in the order the docs list the laws.
const std::vector<LawType>& law_types();
// The law named `name` (InvalidArgument naming `key` and the names).
const LawType& law_type(const std::string& name, const std::string& key = "friction.law");
// The law from values by key: unknown keys, missing required ones and values
// out of range raise InvalidArgument naming "<prefix><key>", the value and
// the range; defaults are filled.
std::unique_ptr<Law> make_law(const std::string& name, const LawValues& values,
                              const std::string& prefix = "friction.");
// The complete values (defaults filled) in the order of the law's parameters.
std::vector<double> complete_values(const LawType& type, const LawValues& values,
                                    const std::string& prefix = "friction.");

}  // namespace leadscrew::friction
