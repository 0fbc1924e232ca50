// Body-level contact generation: every box of a compound against every box of the other body
// (or against the ground), collected with the indices that say where each point came from.
#pragma once

#include <span>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/collision/box.hpp"
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

// Every box of every body placed in the world, once per step: each pair test then reads the
// boxes instead of composing a body's pose with its shape's again for every pair it is in.
class PlacedBoxes {
 public:
  // Sizes the storage for the bodies' boxes (their number never changes).
  explicit PlacedBoxes(const std::vector<RigidBody>& bodies);
  // Places every box at its body's current pose.
  void place(const std::vector<RigidBody>& bodies);
  // The boxes of body i, in shape order.
  std::span<const OrientedBox> of(int i) const {
    return {boxes_.data() + first_[i], boxes_.data() + first_[i + 1]};
  }

 private:
  std::vector<OrientedBox> boxes_;
  std::vector<int> first_;  // body i's boxes are boxes_[first_[i] .. first_[i + 1])
};

// Appends the contacts between bodies ia and ib (every shape pair) to `out`.
void collide_bodies(const PlacedBoxes& boxes, int ia, int ib, const CollisionSettings& settings,
                    std::vector<BodyContact>& out);

// Appends the contacts between body ia and the ground to `out`.
void collide_body_ground(const PlacedBoxes& boxes, int ia, const HalfSpace& ground,
                         const CollisionSettings& settings, std::vector<BodyContact>& out);

// Deepest penetration between two bodies over all their shape pairs (exact SAT depth; negative
// when separated: the largest separation found by the test, a lower bound on the gap).
double body_pair_depth(const RigidBody& a, const RigidBody& b);
// The same for two bodies' boxes already placed (PlacedBoxes::of): the same numbers.
double placed_pair_depth(std::span<const OrientedBox> a, std::span<const OrientedBox> b);

}  // namespace boxpile
