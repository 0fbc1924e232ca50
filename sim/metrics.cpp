#include "boxpile/sim/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/sim/collision/broadphase.hpp"
#include "boxpile/sim/collision/collide.hpp"

namespace boxpile {

namespace {

double ground_depth(std::span<const OrientedBox> boxes, const HalfSpace& ground) {
  double deepest = -std::numeric_limits<double>::infinity();
  for (const OrientedBox& box : boxes) deepest = std::max(deepest, box_plane_depth(box, ground));
  return deepest;
}

}  // namespace

Energy measure_energy(const std::vector<RigidBody>& bodies, const Vec3& gravity) {
  Energy e;
  for (const RigidBody& b : bodies) {
    if (b.fixed) continue;
    e.translational += 0.5 * b.mass * b.v.squaredNorm();
    e.rotational += 0.5 * b.omega.dot(b.R * b.inertia_body * b.R.transpose() * b.omega);
    e.potential -= b.mass * gravity.dot(b.x);
  }
  return e;
}

Penetration measure_penetration(const std::vector<RigidBody>& bodies, const std::optional<HalfSpace>& ground) {
  Penetration worst;
  const int n = static_cast<int>(bodies.size());
  // Every box placed and every body's bounding box taken once, not once per pair: the harness
  // measures every step, and under the sanitizers recomputing them for each of the n^2 / 2 pairs
  // cost more than the separating-axis tests. The same numbers either way (PlacedBoxes).
  PlacedBoxes placed(bodies);
  placed.place(bodies);
  std::vector<Aabb> aabbs;
  aabbs.reserve(bodies.size());
  for (int i = 0; i < n; ++i) aabbs.push_back(boxes_aabb(placed.of(i), 0.0));
  for (int i = 0; i < n; ++i) {
    if (ground && !bodies[i].fixed) {
      const double d = ground_depth(placed.of(i), *ground);
      if (d > worst.depth) worst = {d, i, kGround};
    }
    const Aabb& box_i = aabbs[static_cast<std::size_t>(i)];
    for (int j = i + 1; j < n; ++j) {
      if (bodies[i].fixed && bodies[j].fixed) continue;
      if (!box_i.overlaps(aabbs[static_cast<std::size_t>(j)])) continue;
      const double d = placed_pair_depth(placed.of(i), placed.of(j));
      if (d > worst.depth) worst = {d, i, j};
    }
  }
  return worst;
}

double measure_levitation(const std::vector<RigidBody>& bodies, const std::optional<HalfSpace>& ground,
                          const Vec3& gravity, double rest_speed) {
  const Vec3 down = gravity.norm() > 0.0 ? Vec3(gravity.normalized()) : Vec3(-Vec3::UnitZ());
  // Every box placed once, not once per pair (as measure_penetration).
  PlacedBoxes placed(bodies);
  placed.place(bodies);
  const int n = static_cast<int>(bodies.size());
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const RigidBody& b = bodies[static_cast<std::size_t>(i)];
    if (b.fixed) continue;
    const Aabb bounds = boxes_aabb(placed.of(i), 0.0);
    const double size = bounds.hi.maxCoeff() - bounds.lo.minCoeff();
    if (b.v.norm() > rest_speed || b.omega.norm() * size > rest_speed) continue;
    double gap = std::numeric_limits<double>::infinity();
    if (ground) gap = -ground_depth(placed.of(i), *ground);
    for (int j = 0; j < n; ++j) {
      if (j == i || down.dot(bodies[static_cast<std::size_t>(j)].x - b.x) <= 0.0) continue;  // only supports below
      gap = std::min(gap, -placed_pair_depth(placed.of(i), placed.of(j)));
    }
    if (std::isfinite(gap)) worst = std::max(worst, gap);
  }
  return worst;
}

void set_body_states(std::vector<RigidBody>& bodies, const std::vector<BodyState>& states) {
  for (std::size_t i = 0; i < bodies.size() && i < states.size(); ++i) {
    RigidBody& b = bodies[i];
    const BodyState& s = states[i];
    b.q = s.orientation.normalized();
    b.x = s.position - b.q * b.frame_offset;  // frame origin back to the centre of mass
    b.update_derived();
    b.set_velocity(s.velocity, s.angular_velocity);
  }
}

}  // namespace boxpile
