// The force element interface (cpp/include/leadscrew/model/elements/
// spring_damper.hpp) against its own definitions, by central differences:
// the force is minus the gradient of the elastic energy (the screw's
// stiffness following the nut included, eq. 4.24), the stiffness and
// damping matrices are minus the force's Jacobians, and the damping power
// is what add_forces books. Prints `PASS <label> (<count>)` per check, or
// `FAIL <label>: ...` and exits 1.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "leadscrew/model/elements/drive_elements.hpp"

using leadscrew::model::elements::ForceElements;
using leadscrew::model::elements::SpringDamper;
using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

namespace {

int failures = 0;

void report(const char* label, int count, double worst, double bound) {
  if (worst <= bound) {
    std::printf("PASS %s (%d)\n", label, count);
  } else {
    std::printf("FAIL %s: worst relative error %.3e > %.3e\n", label, worst, bound);
    ++failures;
  }
}

// The elements of a flexible drive's model over 4 coordinates
// (phi_rotor, u_screw, phi_screw, u_load): constant and screw laws, to a
// coordinate and to the ground.
std::vector<SpringDamper> springs() {
  std::vector<SpringDamper> out;
  SpringDamper torsion;
  torsion.name = "screw torsion";
  torsion.first = 2;
  torsion.second = 0;
  torsion.law = SpringDamper::Law::screw_torsional;
  torsion.rigidity = 3.1e3;
  torsion.screw_length = 0.5;
  torsion.damping = 0.02;
  out.push_back(torsion);
  SpringDamper axial;
  axial.name = "screw axial";
  axial.first = 1;
  axial.second = -1;
  axial.law = SpringDamper::Law::screw_axial;
  axial.rigidity = 6.6e7;
  axial.screw_length = 0.5;
  axial.far_segment = true;
  axial.damping = 40.0;
  out.push_back(axial);
  SpringDamper nut;
  nut.name = "nut axial";
  nut.first = 1;
  nut.second = 3;
  nut.stiffness = 2.5e8;
  nut.damping = 150.0;
  out.push_back(nut);
  return out;
}

}  // namespace

int main() {
  const int n = 4;
  std::mt19937 generator(20261127);
  std::uniform_real_distribution<double> small(-1e-4, 1e-4), speed(-1.0, 1.0);
  // The nut position a = a0 + g . q (the nut moves with the load, the screw
  // against it).
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  g[3] = 1.0;
  g[1] = -1.0;
  const double a0 = 0.1;
  ForceElements elements;
  for (const SpringDamper& s : springs()) elements.of<SpringDamper>().push_back(s);
  auto nut_position = [&](const Vector& q) { return a0 + g.dot(q); };
  auto evaluate = [&](const Vector& q, const Vector& v, const Eigen::VectorXd& gradient,
                      double& elastic, double& damping_power) {
    Vector f = Vector::Zero(n);
    elastic = damping_power = 0.0;
    elements.for_each([&](const auto& element) {
      element.add_forces(q, v, nut_position(q), gradient, f, elastic, damping_power);
    });
    return f;
  };
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(n);
  double worst_potential = 0.0, worst_stiffness = 0.0, worst_damping = 0.0,
         worst_power = 0.0;
  int cases = 0;
  for (int trial = 0; trial < 200; ++trial, ++cases) {
    Vector q(n), v(n);
    for (int i = 0; i < n; ++i) {
      q[i] = small(generator);
      v[i] = speed(generator);
    }
    const Vector zero = Vector::Zero(n);
    double elastic = 0.0, power = 0.0;
    // The force at rest is minus the energy's gradient, with the force of
    // the stiffness's change along the nut.
    const Vector f = evaluate(q, zero, g, elastic, power);
    for (int j = 0; j < n; ++j) {
      const double h = 1e-9;
      Vector up = q, down = q;
      up[j] += h;
      down[j] -= h;
      double e_up = 0.0, e_down = 0.0, p = 0.0;
      evaluate(up, zero, g, e_up, p);
      evaluate(down, zero, g, e_down, p);
      const double gradient = (e_up - e_down) / (2.0 * h);
      const double scale = f.cwiseAbs().maxCoeff() + 1e-30;
      worst_potential = std::max(worst_potential, std::abs(-gradient - f[j]) / scale);
    }
    // The stiffness matrix: minus the Jacobian of the force at a fixed nut
    // position (the terms of k's change along the nut left out, as
    // documented).
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), C = Eigen::MatrixXd::Zero(n, n);
    const double a = nut_position(q);
    elements.for_each([&](const auto& element) {
      element.add_stiffness(K, a);
      element.add_damping(C);
    });
    auto fixed_nut_force = [&](const Vector& positions, const Vector& velocities) {
      Vector out = Vector::Zero(n);
      double e = 0.0, p = 0.0;
      elements.for_each([&](const auto& element) {
        element.add_forces(positions, velocities, a, none, out, e, p);
      });
      return out;
    };
    const double k_scale = K.cwiseAbs().maxCoeff(), c_scale = C.cwiseAbs().maxCoeff();
    for (int j = 0; j < n; ++j) {
      Vector up = q, down = q;
      const double h = 1e-7;
      up[j] += h;
      down[j] -= h;
      const Vector column = (fixed_nut_force(up, v) - fixed_nut_force(down, v)) / (2.0 * h);
      worst_stiffness =
          std::max(worst_stiffness, (column + K.col(j)).cwiseAbs().maxCoeff() / k_scale);
      Vector faster = v, slower = v;
      faster[j] += 1e-3;
      slower[j] -= 1e-3;
      const Vector damping_column =
          (fixed_nut_force(q, faster) - fixed_nut_force(q, slower)) / 2e-3;
      worst_damping =
          std::max(worst_damping, (damping_column + C.col(j)).cwiseAbs().maxCoeff() / c_scale);
    }
    // The damping power booked by add_forces, by damping_power(v), and
    // v' C v.
    double booked = 0.0, e = 0.0;
    evaluate(q, v, g, e, booked);
    double summed = 0.0;
    elements.for_each([&](const auto& element) { summed += element.damping_power(v); });
    const double quadratic = v.dot(C * v);
    worst_power = std::max({worst_power, std::abs(booked - summed) / quadratic,
                            std::abs(booked - quadratic) / quadratic});
  }
  report("force is minus the energy gradient", cases, worst_potential, 1e-5);
  report("stiffness matrix is minus the force Jacobian", cases, worst_stiffness, 1e-6);
  report("damping matrix is minus the velocity Jacobian", cases, worst_damping, 1e-9);
  report("damping power", cases, worst_power, 1e-12);
  std::printf(failures ? "FAILED\n" : "OK\n");
  return failures ? 1 : 0;
}
