// The wire constraint of the lab text's "bone": a point of a body (its anchor) slides without
// friction along a straight segment and stops at its ends, while the body swings freely about
// it. Enforced the way the course treats the bone, approximately: an impulse that cancels the
// anchor's velocity across the wire (and along it at an end, when it would leave), and after
// the position update a projection of the anchor back onto the wire.
#pragma once

#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

struct WireJoint {
  int body = 0;
  Vec3 from = Vec3::Zero();        // world
  Vec3 direction = Vec3::UnitX();  // unit, from `from` toward `to`
  double length = 1.0;             // m
  Vec3 anchor = Vec3::Zero();      // body axes, relative to the centre of mass

  // Where the anchor of `b` is now, in world coordinates.
  Vec3 anchor_world(const RigidBody& b) const { return b.x + b.R * anchor; }
  // The anchor's position along the wire, m from `from` (may leave [0, length] by drift).
  double along(const RigidBody& b) const { return direction.dot(anchor_world(b) - from); }
};

// The wires of a scene's bodies, in body order (bodies as built by make_bodies).
std::vector<WireJoint> make_wire_joints(const Scene& scene, const std::vector<RigidBody>& bodies);

// Velocity constraint: the impulse at the anchor that leaves its velocity along the wire only,
// j = T (T^T K T)^-1 (-T^T v_p) with T a basis across the wire and K the body's collision matrix
// at the anchor (impulse.hpp); at an end, moving outward, the whole anchor velocity is cancelled,
// j = -K^-1 v_p. Updates the body's momenta and velocities.
void enforce_wire_velocity(RigidBody& body, const WireJoint& wire);

// Position projection: moves the body so that its anchor lies on the segment (the closest point).
void project_onto_wire(RigidBody& body, const WireJoint& wire);

// The two wire stages of a step, over every wire: the velocity constraint on each wired body,
// and the projection of its anchor after the position update.
void enforce_wires(std::vector<RigidBody>& bodies, const std::vector<WireJoint>& wires);
void project_wires(std::vector<RigidBody>& bodies, const std::vector<WireJoint>& wires);

}  // namespace boxpile
