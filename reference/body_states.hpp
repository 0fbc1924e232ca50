// What every native engine's body_states() shares: one state per scene body, named as the scene
// names it, and the state of a body the engine holds fixed. Internal to boxpile::reference.
#pragma once

#include <cstddef>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/engine.hpp"

namespace boxpile::reference_detail {

// A body the engine does not move (fixed, or not simulated): its frame pose from the scene, at rest.
inline void set_fixed_state(const RigidBody& body, BodyState& state) {
  const Pose frame = body.frame_pose();
  state.position = frame.position;
  state.orientation = frame.orientation;
  state.velocity.setZero();
  state.angular_velocity.setZero();
}

// `out` holds one state per body, in the scene's order and named as in the scene; fill(i, state)
// writes body i's pose and velocities as the engine reports them.
template <class Fill>
void collect_body_states(const std::vector<RigidBody>& bodies, std::vector<BodyState>& out, Fill fill) {
  out.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    out[i].name = bodies[i].name;
    fill(i, out[i]);
  }
}

}  // namespace boxpile::reference_detail
