// Stick or slip at zero slip velocity, decided by a linear complementarity
// problem (Pfeiffer & Glocker's decomposition of Coulomb's law, thesis
// section 2.2.1, eq. 2.15-2.24, and its single-contact form eq. 3.10-3.14).
//
// The contact's mechanics enter through two affine maps of the friction force
// lambda_T, obtained from the equations of motion with every other constraint
// enforced:
//   slip acceleration     gamma' = c + d lambda_T          (d > 0)
//   normal force          lambda_N = beta + alpha lambda_T (alpha = 0 when the
//                                                            normal force is given)
// and the assumed sign sigma of the normal force. Coulomb's law
// |lambda_T| <= mu sigma lambda_N, with lambda_T = -mu sigma lambda_N when
// gamma' > 0 and +mu sigma lambda_N when gamma' < 0, becomes the LCP
//   w = A z + b,  z = (x+, y-),  w = (y+, x-)
// with the friction reserves x+- = mu sigma lambda_N +- lambda_T and the
// positive and negative parts y+- of gamma'. For the block of eq. 3.9
// (alpha = 0, beta = m g, c = F/m, d = 1/m) it is
//   A = [[1/m, 1], [-1, 0]],  b = ((F - mu m g)/m, 2 mu m g).
// (Eq. 3.14 prints A = diag(1/m) with b = ((F - mu m g)/m, (F + mu m g)/m):
// the second row there needs the opposite sign of F + mu m g and decouples the
// two reserves, which then no longer add up to 2 mu lambda_N. The form here
// keeps that sum.)
// The same LCP on the velocity level (c = free slip velocity, d = Delassus
// term, beta = impulse bound) gives the Moreau-Jean friction impulse.
#pragma once

#include "leadscrew/lcp/lcp.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace leadscrew::friction {

struct FlankLcpResult {
  lcp::Status status = lcp::Status::singular;
  bool consistent = false;          // solved and sigma lambda_N >= 0
  double friction_force = 0.0;      // lambda_T
  double normal_force = 0.0;        // lambda_N
  double slip_acceleration = 0.0;   // gamma' (or the new slip velocity on the velocity level)
  int lcp_iterations = 0;
};

FlankLcpResult solve_flank_lcp(double c, double d, double alpha, double beta, double mu,
                               int sigma, lcp::Workspace& workspace, const lcp::Options& options);

// The same decision where the slip is prescribed (d = 0): a speed-controlled
// motor on the rigid thread without play, or on a closed flank, fixes every
// velocity, so the friction force no longer changes the slip acceleration
// (or velocity) c. Then c decides: slip against friction at the cone's edge
// where c != 0; where c = 0 the friction force is statically indeterminate
// (the motor and the thread share the load), and of the forces the cone
// admits the one is taken that leaves the motor the least to carry:
// |motor| minimal with motor = motor0 + motor1 lambda_T (the thread holds
// what its friction can; a self-locking thread holds an axial load with no
// motor torque). `slip_zero` says c counts as 0 (within its round-off).
FlankLcpResult solve_flank_prescribed_slip(double c, bool slip_zero, double alpha, double beta,
                                           double mu, int sigma, double motor0, double motor1);

// The stick solution alone: lambda_T = -c / d keeps the slip at zero; it is
// admissible where d > 0, its normal force lambda_N = beta + alpha lambda_T
// lies on the side sigma (0: either) and |lambda_T| <= mu |lambda_N|. In the
// Painleve regime (mu |alpha| >= 1 on the velocity or impulse level) the
// LCP of one sign may miss it; at zero slip the drive keeps sticking
// wherever stick is admissible (docs/physics/rigid_drive.md, "uniqueness").
// With a static coefficient above the kinetic one it is the first of the
// two steps of the decision (docs/physics/friction_laws.md).
FlankLcpResult flank_stick(double c, double d, double alpha, double beta, double mu, int sigma);

}  // namespace leadscrew::friction
