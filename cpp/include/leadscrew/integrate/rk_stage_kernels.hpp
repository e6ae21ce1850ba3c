// The stage loop of an explicit Runge-Kutta step for a state size N and a
// stage count S fixed at compile time, with the system's right-hand side
// called through its own class: a model whose class is final gets its rhs
// inlined into the loop (OdeSystem::explicit_rk_stages).
//
// Why: the stages of a small system are a chain of dependent latencies
// (stage i needs k_i-1; in the friction laws an arctan with a division on
// the way). Through the virtual call every stage stores its argument and
// its k to memory and loads them back on the other side; inlined, they can
// stay in registers (if the rhs reads its state before it stores anything:
// see RegularizedBlock::rhs). Measured on the friction block (arctan
// velocity law, k_V = 10, rk_verner6 at rtol 1.8e-6, 4 states), old and new
// binary alternating: 11 % less time per simulation.
//
// The arithmetic is ExplicitRungeKutta's own (it runs these templates with
// System = OdeSystem), operation for operation and in the same order: the
// same numbers, bit for bit, with or without the system's own loop on
// x86-64, whose baseline has no FMA to contract into
// (benchmarks/integrate/rk_kernel_check.cpp, run by
// tests/test_integrate_native.py).
#pragma once

#include <cassert>
#include <utility>

#include "leadscrew/integrate/ode.hpp"

namespace leadscrew::integrate::rk_kernels {

// out = base + h sum_j coefficients_j k_j over Count stages of N states
// (base null: 0). Zero coefficients are not skipped, so that 0 * inf = NaN
// still flags a non-finite stage. The sums stay in registers.
template <int N, int Count>
inline void combine(const double* base, double h, const double* coefficients, const double* k,
                    double* out) {
  double sum[N];
  for (int r = 0; r < N; ++r) sum[r] = base ? base[r] : 0.0;
  for (int j = 0; j < Count; ++j) {
    const double w = h * coefficients[j];
    for (int r = 0; r < N; ++r) sum[r] += w * k[j * N + r];
  }
  for (int r = 0; r < N; ++r) out[r] = sum[r];
}

template <class System, int N, int S, int... I>
inline void stages(System& system, const double* a, const double* c, double t, const double* y,
                   double h, double* k, double* y_stage, std::integer_sequence<int, I...>) {
  // Stage I + 1 from the stages 0..I, in order (the fold runs left to right).
  ((combine<N, I + 1>(y, h, a + (I + 1) * S, k, y_stage),
    system.rhs(t + c[I + 1] * h, y_stage, k + (I + 1) * N)),
   ...);
}

// Stages 2..S (stage 1 in k[0..N)) of a step of size h from (t, y), each
// k_i = f(t + c_i h, y + h sum_j a_ij k_j); y_stage ends as the last
// stage's argument. An RkStageKernel (ode.hpp); System is OdeSystem (a
// virtual call per stage) or the system's own final class.
template <class System, int N, int S>
void stage_kernel(OdeSystem& system, const double* a, const double* c, double t,
                  const double* y, double h, double* k, double* y_stage) {
  // Only the object that offered this loop may be passed (ode.hpp).
  assert(dynamic_cast<System*>(&system) != nullptr);
  stages<System, N, S>(static_cast<System&>(system), a, c, t, y, h, k, y_stage,
                       std::make_integer_sequence<int, S - 1>{});
}

// The kernel of System for the engine's methods (7 stages: Dormand-Prince
// 5(4); 8: Verner 6(5)), null for other stage counts.
template <class System, int N>
RkStageKernel stage_kernel_for(int stage_count) {
  switch (stage_count) {
    case 7: return &stage_kernel<System, N, 7>;
    case 8: return &stage_kernel<System, N, 8>;
    default: return nullptr;
  }
}

}  // namespace leadscrew::integrate::rk_kernels
