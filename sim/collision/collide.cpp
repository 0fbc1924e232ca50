#include "boxpile/sim/collision/collide.hpp"

#include <algorithm>
#include <limits>

#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"

namespace boxpile {
namespace {

OrientedBox world_box(const RigidBody& body, int shape) {
  return OrientedBox::from(body.shape_pose(shape), body.shapes[shape].half_extents);
}

// Every box of the body placed at its current pose, in shape order (as PlacedBoxes places them).
std::vector<OrientedBox> world_boxes(const RigidBody& body) {
  std::vector<OrientedBox> boxes;
  boxes.reserve(body.shapes.size());
  for (int k = 0; k < static_cast<int>(body.shapes.size()); ++k) boxes.push_back(world_box(body, k));
  return boxes;
}

void append(const Manifold& m, int ia, int ib, int sa, int sb, std::vector<BodyContact>& out) {
  for (const Contact& c : m) out.push_back({c, ia, ib, sa, sb});
}

}  // namespace

PlacedBoxes::PlacedBoxes(const std::vector<RigidBody>& bodies) {
  first_.reserve(bodies.size() + 1);
  first_.push_back(0);
  for (const RigidBody& b : bodies) first_.push_back(first_.back() + static_cast<int>(b.shapes.size()));
  boxes_.resize(static_cast<std::size_t>(first_.back()));
}

void PlacedBoxes::place(const std::vector<RigidBody>& bodies) {
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i)
    for (int k = 0; k < static_cast<int>(bodies[i].shapes.size()); ++k)
      boxes_[static_cast<std::size_t>(first_[i] + k)] = world_box(bodies[i], k);
}

void collide_bodies(const PlacedBoxes& boxes, int ia, int ib, const CollisionSettings& settings,
                    std::vector<BodyContact>& out) {
  const std::span<const OrientedBox> a = boxes.of(ia);
  const std::span<const OrientedBox> b = boxes.of(ib);
  Manifold m;
  for (int sa = 0; sa < static_cast<int>(a.size()); ++sa) {
    for (int sb = 0; sb < static_cast<int>(b.size()); ++sb) {
      m.clear();
      collide_box_box(a[sa], b[sb], settings, m);
      append(m, ia, ib, sa, sb, out);
    }
  }
}

void collide_body_ground(const PlacedBoxes& boxes, int ia, const HalfSpace& ground,
                         const CollisionSettings& settings, std::vector<BodyContact>& out) {
  const std::span<const OrientedBox> a = boxes.of(ia);
  Manifold m;
  for (int sa = 0; sa < static_cast<int>(a.size()); ++sa) {
    m.clear();
    collide_box_plane(a[sa], ground, settings.margin, m);
    append(m, ia, kGround, sa, 0, out);
  }
}

double body_pair_depth(const RigidBody& a, const RigidBody& b) {
  return placed_pair_depth(world_boxes(a), world_boxes(b));
}

double placed_pair_depth(std::span<const OrientedBox> a, std::span<const OrientedBox> b) {
  double deepest = -std::numeric_limits<double>::infinity();
  for (const OrientedBox& box_a : a)
    for (const OrientedBox& box_b : b) deepest = std::max(deepest, -box_box_sat(box_a, box_b).separation);
  return deepest;
}

}  // namespace boxpile
