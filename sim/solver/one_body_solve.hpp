// A direct solve of a shock-propagation group whose contacts all reach from one moving body down
// to bodies that do not move while its level is solved (frozen lower levels, fixed bodies, the
// ground): a pyramid's box on the four boxes below it, a stack's box on the one below.
//
// The passes solve such a group by projected Gauss-Seidel, some 15 passes to 1e-12 m/s. When every
// touching point sticks, the answer is known in closed form: the body's velocity that brings each
// point to its target, by least squares over the points, and the smallest impulses that give the
// body that velocity. The solve checks that this is a solution of what the passes solve (every
// touching point at its target, every impulse in its friction cone, a point with a gap free of
// impulse and not approaching faster than its gap allows) and otherwise leaves the group to the
// passes. docs/solver.md, "A one-body group solved directly", has the derivation.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "boxpile/sim/solver/impulse.hpp"
#include "boxpile/sim/solver/shock_propagation.hpp"
#include "boxpile/sim/solver/solver_body.hpp"

namespace boxpile {

// Why a group was, or was not, solved directly.
enum class OneBodyOutcome : std::uint8_t {
  solved,
  not_one_body,     // two of its bodies move, or its contacts reach from different bodies
  frictionless,     // a point without friction: the passes solve it (no sticking to ask for)
  too_few_points,   // fewer than three touching points: the body can turn or slide freely
  ill_conditioned,  // the touching points are (nearly) on one line
  off_target,       // the points' targets ask for no single rigid motion (a sliding or pushed box)
  outside_cone,     // sticking needs an impulse that pulls or leaves the friction cone
  gap_closes,       // a point with a gap would approach faster than its gap allows
};

// Tries the direct solve of one group of a shock-propagation level. On `solved` it has set each
// contact's accumulated impulse and the body's velocities and momenta, and counted one impulse per
// contact; otherwise nothing has changed. `worst_residual` receives the largest distance of a
// touching point's velocity from its target after the solve (m/s), when solved.
OneBodyOutcome solve_one_body_group(SolverBodyArray& sb, std::vector<SolverContact>& contacts,
                                    std::span<const ShockPropagation::LevelContact> group, bool friction,
                                    ImpulseCounters& counters, double& worst_residual);

}  // namespace boxpile
