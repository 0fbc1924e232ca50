// The integrators every contact method shares: external forces on the momenta, and the pose
// update of one body from the velocities a method chooses.
#pragma once

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/solver/step_context.hpp"

namespace boxpile {

// Gravity and air damping on every moving body's momenta over ctx.dt; velocities follow.
void integrate_momenta(StepContext& ctx);

// Moves `b` over dt with linear velocity v and angular velocity w, and keeps omega or L as the
// scene's gyroscopic effect says.
void advance_pose(RigidBody& b, const Vec3& v, const Vec3& w, double dt, bool gyroscopic,
                  WorldCounters& counters);

}  // namespace boxpile
