// A direct solve of a shock-propagation group under the hypothesis that every touching point
// sticks: each moving body of the group rests on bodies that do not move while its level is solved
// (frozen lower levels, fixed bodies, the ground), and the contacts between two moving bodies end
// without impulse. A pyramid's box on the four boxes below it, a stack's box on the one below, a
// Jenga layer of three blocks lying side by side on the layer below.
//
// The passes solve such a group by projected Gauss-Seidel, some 15 passes to 1e-12 m/s. When every
// touching point sticks, the answer is known in closed form: each body's velocity that brings its
// points to their targets, by least squares, and the smallest impulses that give the body that
// velocity. The solve checks that this is a solution of what the passes solve (every touching
// point at its target, every impulse in its friction cone, a point with a gap or between two moving
// bodies free of impulse and not approaching faster than it may) and otherwise leaves the group to
// the passes. A group it declines is tried once more with the points a rounding away from touching
// (kNearTouchingGap) counted as touching. docs/solver.md, "Sticking groups solved directly", has
// the derivation, and "Points a rounding away from touching" the second try.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "boxpile/sim/solver/impulse.hpp"
#include "boxpile/sim/solver/shock_propagation.hpp"
#include "boxpile/sim/solver/solver_body.hpp"

namespace boxpile {

// Why a group was, or was not, solved directly.
enum class StickingOutcome : std::uint8_t {
  solved,
  too_large,        // more bodies or points than the solve holds: the passes solve it
  frictionless,     // a point without friction: the passes solve it (no sticking to ask for)
  too_few_points,   // a body with fewer than three touching points: it can turn or slide freely
  ill_conditioned,  // a body's touching points are (nearly) on one line
  off_target,       // the points' targets ask for no single rigid motion (a sliding or pushed box)
  outside_cone,     // sticking needs an impulse that pulls or leaves the friction cone
  gap_closes,       // a point with a gap, or between two moving bodies, would approach too fast
};

// Tries the direct solve of one group of a shock-propagation level. On `solved` it has set each
// contact's accumulated impulse and the bodies' velocities and momenta, and counted one impulse
// per contact; otherwise nothing has changed. `worst_residual` receives the largest distance of a
// touching point's velocity from its target (m/s), when solved.
StickingOutcome solve_sticking_group(SolverBodyArray& sb, std::vector<SolverContact>& contacts,
                                     std::span<const ShockPropagation::LevelContact> group, bool friction,
                                     ImpulseCounters& counters, double& worst_residual);

}  // namespace boxpile
