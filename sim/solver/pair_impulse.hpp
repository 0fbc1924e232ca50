// The collision impulses of one pair's contact points, solved together.
//
// Sequential push-only impulses treat the points of a face one at a time: a box landing flat gets
// its whole impulse at the first corner met, which turns it, and the later corners then push a
// turning box (a flat drop at e = 0.5 left the ground spinning at 3.1 rad/s). Here the normal
// impulses lambda_i >= 0 of all approaching points of a pair solve one system,
//   sum_j n_i . K_ij n_j lambda_j = -(1 + e) u_n,i,  with K_ij = (1/mA) E - [r_Ai]x IA^-1 [r_Aj]x + (B alike),
// the minimum-norm solution where the points are redundant (four coplanar corners fix only three
// velocities), so a symmetric landing gets symmetric impulses. A point whose lambda would be
// negative is dropped and the rest solved again. Friction follows per point, the tangential impulse
// that stops the point's sliding clamped to mu lambda_i.
#pragma once

#include <span>

#include "boxpile/sim/solver/impulse_step.hpp"

namespace boxpile {

// The largest number of points solved together; a pair with more (compounds) is solved in
// consecutive blocks of this size.
inline constexpr int kMaxBlockPoints = 16;

// Applies the collision impulses of one pair's points (all with the same bodies a and b) for
// restitution e (per point: each contact's own when `restitution`, else 0). Only active points
// that approach (u_n < 0) take part. Adds each point's normal impulse to its
// `collision_impulse`; counters count one normal impulse per point solved.
void pair_collision_impulses(SolverBodies& sb, std::span<SolverContact> points, bool restitution, bool friction,
                             ImpulseCounters& counters);

}  // namespace boxpile
