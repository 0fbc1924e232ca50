// Body-level contact generation: every box of a compound against every box of the other body
// (or against the ground), collected with the indices that say where each point came from.
#pragma once

#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// Index used for the ground in BodyContact::body_b.
inline constexpr int kGround = -1;

struct BodyContact {
  Contact contact;  // normal from body_b toward body_a
  int body_a = 0;
  int body_b = kGround;
  int shape_a = 0;
  int shape_b = 0;
};

// Appends the contacts between bodies ia and ib (every shape pair) to `out`.
void collide_bodies(const std::vector<RigidBody>& bodies, int ia, int ib,
                    const CollisionSettings& settings, std::vector<BodyContact>& out);

// Appends the contacts between body ia and the ground to `out`.
void collide_body_ground(const std::vector<RigidBody>& bodies, int ia, const HalfSpace& ground,
                         const CollisionSettings& settings, std::vector<BodyContact>& out);

// Deepest penetration between two bodies over all their shape pairs (exact SAT depth; negative
// when separated: the largest separation found by the test, a lower bound on the gap).
double body_pair_depth(const RigidBody& a, const RigidBody& b);

}  // namespace boxpile
