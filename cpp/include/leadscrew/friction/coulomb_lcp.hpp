// Coulomb friction as linear complementarity problems (thesis sec. 2.2.1,
// eq. 2.13-2.24, and sec. 3.2.6, eq. 3.9-3.14; Pfeiffer & Glocker 1996).
//
// Conventions (thesis eq. 2.18, 2.21): the contact forces act on the
// generalized coordinates y through the force directions W,
//     M y'' = h + W_N lambda_N + W_T lambda_T,
// and the relative contact accelerations are g'' = W^T y'' + w_hat. With the
// Delassus matrix G = W^T M^-1 W and the free accelerations
// c = W^T M^-1 h + w_hat (those with all contact forces zero),
//     g'' = G lambda + c                                   (thesis eq. 2.24).
// Coulomb's law on acceleration level for a contact that is not sliding
// (thesis eq. 2.17, Pfeiffer & Glocker): g_T'' > 0 => lambda_T = -mu lambda_N,
// g_T'' < 0 => lambda_T = +mu lambda_N, g_T'' = 0 => |lambda_T| <= mu lambda_N.
//
// Tangential decomposition (thesis fig. 2.4-2.5, eq. 3.10-3.13): split
// g_T'' = g_T''+ - g_T''- with both parts >= 0, and the friction reserves
//     x1 = mu lambda_N - lambda_T >= 0,   x2 = mu lambda_N + lambda_T >= 0.
// Then Coulomb's law is the pair of complementarities
//     g_T''- _|_ x1   (sliding backwards: lambda_T = +mu lambda_N),
//     g_T''+ _|_ x2   (sliding forwards:  lambda_T = -mu lambda_N).
// The thesis's block (eq. 3.9, m u'' = F_Exc - lambda_T) has W_T = -1, so
// g_T'' = -u'': its (|u''| + u'')/2 is g_T''- and (|u''| - u'')/2 is g_T''+.
//
// Every builder writes into caller-provided storage and never allocates; all
// throw InvalidArgument (naming the argument) for non-finite input, mu < 0,
// lambda_N < 0 or inconsistent sizes.
#pragma once

#include <Eigen/Core>

namespace leadscrew::friction {

// ---------------------------------------------------------------------------
// (a) Known normal forces: friction LCPs in the thesis's unknowns x1, x2.

// One contact, the thesis's 2x2 form (eq. 3.10, 3.14): z = (x1, x2),
// w = (g_T''-, g_T''+), each row the tangential acceleration part that
// results if the other reserve were not the bounding one:
//     w1 = G x1 - (G mu lambda_N + c)     (g_T''- with lambda_T = mu lambda_N - x1)
//     w2 = G x2 - (G mu lambda_N - c)     (g_T''+ with lambda_T = x2 - mu lambda_N)
// For the block (G = 1/m, c = -F_Exc/m, lambda_N = m g) this is A = I/m of
// eq. (3.14) and b = ((F_Exc - m g mu)/m, -(F_Exc + m g mu)/m). The thesis
// prints b2 = +(F_Exc + m g mu)/m; substituting eq. (3.12)-(3.13) into
// w2 = (|u''| - u'')/2 gives the minus sign, and only with it does the LCP
// stick for |F_Exc| < mu m g. The rows decouple, which is exact for a single
// contact (scalar G) only; for several coupled contacts use friction_lcp.
struct SingleFrictionLcp {
  Eigen::Matrix2d A;
  Eigen::Vector2d b;
};
// delassus G = W_T^T M^-1 W_T > 0, free_acceleration c = W_T^T M^-1 h.
SingleFrictionLcp single_friction_lcp(double delassus, double free_acceleration, double mu,
                                      double normal_force);

struct TangentialState {
  double friction_force;  // lambda_T
  double acceleration;    // g_T''
};
// lambda_T and g_T'' = w2 - w1 from a solution (z, w = A z + b) of single_friction_lcp:
// lambda_T = mu lambda_N - x1 unless the contact slides forwards (w2 > w1),
// then x2 - mu lambda_N.
// z, w of size 2.
TangentialState single_friction_state(const Eigen::Ref<const Eigen::VectorXd>& z,
                                      const Eigen::Ref<const Eigen::VectorXd>& w, double mu,
                                      double normal_force);

// n contacts with coupled tangential directions (G an n x n Delassus matrix,
// symmetric positive semidefinite): the 2n-LCP
//     z = (x1, g_T''+),  w = (g_T''-, x2),
//     g_T''- = G x1 + g_T''+ - (G r + c),   x2 = 2 r - x1,   r = mu lambda_N,
//     A = [[G, I], [-I, 0]],  b = (-(G r + c), 2 r).
// It follows from g_T'' = G lambda_T + c with lambda_T = r - x1, and keeps
// exactly the thesis's complementarity pairs. A + A^T = diag(2G, 0) is
// positive semidefinite and x1 = r, g_T''+ = max(c, 0) is feasible, so Lemke
// always solves it (PGS cannot: the diagonal has zeros).
// A must be 2n x 2n and b of size 2n.
void friction_lcp(const Eigen::Ref<const Eigen::MatrixXd>& delassus,
                  const Eigen::Ref<const Eigen::VectorXd>& free_acceleration,
                  const Eigen::Ref<const Eigen::VectorXd>& mu,
                  const Eigen::Ref<const Eigen::VectorXd>& normal_force,
                  Eigen::Ref<Eigen::MatrixXd> A, Eigen::Ref<Eigen::VectorXd> b);

// lambda_T = mu lambda_N - x1 and g_T'' = g_T''+ - g_T''- from a solution of
// friction_lcp (z, w of size 2n; outputs of size n).
void friction_state(const Eigen::Ref<const Eigen::VectorXd>& z,
                    const Eigen::Ref<const Eigen::VectorXd>& w,
                    const Eigen::Ref<const Eigen::VectorXd>& mu,
                    const Eigen::Ref<const Eigen::VectorXd>& normal_force,
                    Eigen::Ref<Eigen::VectorXd> friction_force,
                    Eigen::Ref<Eigen::VectorXd> tangential_acceleration);

// ---------------------------------------------------------------------------
// (b) Unilateral normal contact with Coulomb friction, normal force unknown
// (Pfeiffer & Glocker's planar contact; thesis eq. 2.14, 2.17, 2.24): per
// contact three complementarities g_N'' _|_ lambda_N, g_T''+ _|_ x2,
// g_T''- _|_ x1. With lambda_T = x2 - mu lambda_N and x1 = 2 mu lambda_N - x2:
//     z = (lambda_N, x2, g_T''-),   w = (g_N'', g_T''+, x1),
//     g_N''  = (G_NN - G_NT mu) lambda_N + G_NT x2 + c_N
//     g_T''+ = (G_TN - G_TT mu) lambda_N + G_TT x2 + g_T''- + c_T
//     x1     = 2 mu lambda_N - x2
// G = [W_N W_T]^T M^-1 [W_N W_T] (order: all normal, then all tangential
// directions), c = (c_N, c_T). This A is not copositive in general: for large
// mu with G_NT != 0 the LCP may have no solution or several (Painleve), which
// a solver reports as ray_termination.

// One contact: G 2x2, c = (c_N, c_T).
struct PlanarContactLcp {
  Eigen::Matrix3d A;
  Eigen::Vector3d b;
};
PlanarContactLcp planar_contact_lcp(const Eigen::Matrix2d& delassus,
                                    const Eigen::Vector2d& free_acceleration, double mu);

struct ContactState {
  double normal_force;             // lambda_N
  double friction_force;           // lambda_T
  double normal_acceleration;      // g_N''
  double tangential_acceleration;  // g_T''
};
// From a solution (z, w of size 3) of planar_contact_lcp.
ContactState planar_contact_state(const Eigen::Ref<const Eigen::VectorXd>& z,
                                  const Eigen::Ref<const Eigen::VectorXd>& w, double mu);

// n contacts: G 2n x 2n, c of size 2n, mu of size n; A 3n x 3n, b of size 3n,
// ordered (lambda_N, x2, g_T''-) and (g_N'', g_T''+, x1), each block of size n.
void contact_lcp(const Eigen::Ref<const Eigen::MatrixXd>& delassus,
                 const Eigen::Ref<const Eigen::VectorXd>& free_acceleration,
                 const Eigen::Ref<const Eigen::VectorXd>& mu, Eigen::Ref<Eigen::MatrixXd> A,
                 Eigen::Ref<Eigen::VectorXd> b);

// From a solution (z, w of size 3n) of contact_lcp; outputs of size n.
void contact_state(const Eigen::Ref<const Eigen::VectorXd>& z,
                   const Eigen::Ref<const Eigen::VectorXd>& w,
                   const Eigen::Ref<const Eigen::VectorXd>& mu,
                   Eigen::Ref<Eigen::VectorXd> normal_force,
                   Eigen::Ref<Eigen::VectorXd> friction_force,
                   Eigen::Ref<Eigen::VectorXd> normal_acceleration,
                   Eigen::Ref<Eigen::VectorXd> tangential_acceleration);

}  // namespace leadscrew::friction
