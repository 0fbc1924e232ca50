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

void append(const Manifold& m, int ia, int ib, int sa, int sb, std::vector<BodyContact>& out) {
  for (const Contact& c : m) out.push_back({c, ia, ib, sa, sb});
}

}  // namespace

void collide_bodies(const std::vector<RigidBody>& bodies, int ia, int ib,
                    const CollisionSettings& settings, std::vector<BodyContact>& out) {
  const RigidBody& a = bodies[ia];
  const RigidBody& b = bodies[ib];
  Manifold m;
  for (int sa = 0; sa < static_cast<int>(a.shapes.size()); ++sa) {
    const OrientedBox box_a = world_box(a, sa);
    for (int sb = 0; sb < static_cast<int>(b.shapes.size()); ++sb) {
      m.clear();
      collide_box_box(box_a, world_box(b, sb), settings, m);
      append(m, ia, ib, sa, sb, out);
    }
  }
}

void collide_body_ground(const std::vector<RigidBody>& bodies, int ia, const HalfSpace& ground,
                         const CollisionSettings& settings, std::vector<BodyContact>& out) {
  const RigidBody& a = bodies[ia];
  Manifold m;
  for (int sa = 0; sa < static_cast<int>(a.shapes.size()); ++sa) {
    m.clear();
    collide_box_plane(world_box(a, sa), ground, settings.margin, m);
    append(m, ia, kGround, sa, 0, out);
  }
}

double body_pair_depth(const RigidBody& a, const RigidBody& b) {
  double deepest = -std::numeric_limits<double>::infinity();
  for (int sa = 0; sa < static_cast<int>(a.shapes.size()); ++sa) {
    const OrientedBox box_a = world_box(a, sa);
    for (int sb = 0; sb < static_cast<int>(b.shapes.size()); ++sb)
      deepest = std::max(deepest, -box_box_sat(box_a, world_box(b, sb)).separation);
  }
  return deepest;
}

}  // namespace boxpile
