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

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

double ground_depth(std::span<const OrientedBox> boxes, const HalfSpace& ground) {
  double deepest = -kUnbounded;
  for (const OrientedBox& box : boxes) deepest = std::max(deepest, box_plane_depth(box, ground));
  return deepest;
}

// Every box placed and every body's bounding box taken once, not once per pair: the harness
// measures every step. The same numbers as placing them per pair (PlacedBoxes).
struct PlacedBodies {
  explicit PlacedBodies(const std::vector<RigidBody>& bodies) : placed(bodies) {
    placed.place(bodies);
    aabbs.reserve(bodies.size());
    fixed.reserve(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      aabbs.push_back(boxes_aabb(placed.of(static_cast<int>(i)), 0.0));
      fixed.push_back(bodies[i].fixed ? 1 : 0);
    }
  }
  PlacedBoxes placed;
  std::vector<Aabb> aabbs;
  std::vector<char> fixed;
};

// Levitation's neighbour bound. A body's bounding box has centre C and half diagonal rho. For two
// boxes a, b the separating-axis separation s (the largest gap over the 15 axes) is at least the
// gap along a's three face normals, which is at least |c_b - c_a| / sqrt(3) - |h_a| - |h_b| (the
// Minkowski sum lies inside a's frame box of half extents h_a + |h_b|, and a point outside a box
// is at least its Euclidean distance / sqrt(3) from it along one face normal). Each box of a body
// has |c - C| + |h| <= sqrt(2) rho (some corner of the box lies at least that far from C / sqrt 2
// and inside the body's box). So for bodies i, j: s_ij >= |C_j - C_i| / sqrt(3) - sqrt(2) (rho_i +
// rho_j). Grown by kGrowth rho + sqrt(3) m, two bodies' boxes that do not overlap have |C_j - C_i|
// > (kGrowth (rho_i + rho_j) + sqrt(3) (m_i + m_j)), hence s_ij > m_i + m_j.
constexpr double kSqrt2 = 1.4142135623730951;
constexpr double kSqrt3 = 1.7320508075688772;
constexpr double kGrowth = kSqrt2 * kSqrt3;
// The separation within which a body's candidates are complete, in units of its own half
// diagonal: a body floating by less than its own size above its support is resolved from the
// broadphase's pairs; one floating higher is checked against every body (with the bound above
// skipping the far ones before any separating-axis test).
constexpr double kSearchInSizes = 1.0;

double half_diagonal(const Aabb& box) { return 0.5 * (box.hi - box.lo).norm(); }
Vec3 centre(const Aabb& box) { return 0.5 * (box.hi + box.lo); }

// The lower bound on s_ij above (never above the true separation, so skipping a pair whose bound
// reaches the best gap so far changes no result).
// A millionth of slack on each side keeps rounding from making the bound exceed the separation.
constexpr double kSlack = 1e-6;
double separation_bound(const Aabb& a, const Aabb& b) {
  return (1.0 - kSlack) * (centre(b) - centre(a)).norm() / kSqrt3 -
         (1.0 + kSlack) * kSqrt2 * (half_diagonal(a) + half_diagonal(b));
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
  // Two bodies whose bounding boxes do not overlap are separated (depth < 0, never the deepest),
  // so the broadphase's pairs hold every candidate. The deepest wins; among equal depths the
  // first in the order (body, its ground contact, then its pairs by the other body's index), so
  // the result is the one the all-pairs loop gives (tests/test_metrics.cpp checks that).
  const PlacedBodies p(bodies);
  Penetration worst;
  auto before = [](const Penetration& a, const Penetration& b) {
    const int ka = a.body_b == kGround ? -1 : a.body_b, kb = b.body_b == kGround ? -1 : b.body_b;
    return a.body_a < b.body_a || (a.body_a == b.body_a && ka < kb);
  };
  auto consider = [&](const Penetration& c) {
    if (c.depth > worst.depth || (c.depth == worst.depth && worst.body_a >= 0 && before(c, worst))) worst = c;
  };
  const int n = static_cast<int>(bodies.size());
  if (ground) {
    for (int i = 0; i < n; ++i) {
      if (!bodies[static_cast<std::size_t>(i)].fixed) consider({ground_depth(p.placed.of(i), *ground), i, kGround});
    }
  }
  SweepAndPrune sweep;
  for (const auto& [i, j] : sweep.find_pairs(p.aabbs, p.fixed)) {
    consider({placed_pair_depth(p.placed.of(i), p.placed.of(j)), i, j});
  }
  return worst;
}

Vec3 down_direction(const Vec3& gravity) {
  return gravity.norm() > 0.0 ? Vec3(gravity.normalized()) : Vec3(-Vec3::UnitZ());
}

std::pair<Vec3, Vec3> across_directions(const Vec3& down) {
  const Vec3 helper = std::abs(down.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = down.cross(helper).normalized();
  return {u, down.cross(u)};
}

double measure_levitation(const std::vector<RigidBody>& bodies, const std::optional<HalfSpace>& ground,
                          const Vec3& gravity, double rest_speed) {
  const Vec3 down = down_direction(gravity);
  const PlacedBodies p(bodies);
  const std::size_t n = bodies.size();

  // Per resting body, an upper bound on its gap (the ground's; +inf without ground or when not
  // resting: then it is no candidate at all).
  std::vector<double> gap(n, -kUnbounded);  // -inf: not a resting body, contributes nothing
  std::vector<double> reach(n, 0.0);       // separation within which its candidates are complete
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& b = bodies[i];
    if (b.fixed) continue;
    const Aabb& bounds = p.aabbs[i];
    const double size = bounds.hi.maxCoeff() - bounds.lo.minCoeff();
    if (b.v.norm() > rest_speed || b.omega.norm() * size > rest_speed) continue;
    gap[i] = ground ? -ground_depth(p.placed.of(static_cast<int>(i)), *ground) : kUnbounded;
    reach[i] = kSearchInSizes * half_diagonal(bounds);
  }
  auto below = [&](std::size_t i, std::size_t j) { return down.dot(bodies[j].x - bodies[i].x) > 0.0; };
  // A body touching the ground has no gap to report whatever lies below it (the result is at least
  // 0): when every resting body does (a flat grid, a settled layer), no pair is needed.
  bool all_touch_ground = true;
  for (std::size_t i = 0; i < n; ++i) all_touch_ground = all_touch_ground && !(gap[i] > 0.0);
  if (!all_touch_ground) {
    // No fixed flags: a resting body's support may be fixed.
    std::vector<Aabb> grown(p.aabbs);
    for (std::size_t i = 0; i < n; ++i) {
      const double grow = (1.0 + kSlack) * (kGrowth * half_diagonal(p.aabbs[i]) + kSqrt3 * reach[i]);
      grown[i].lo.array() -= grow;
      grown[i].hi.array() += grow;
    }
    SweepAndPrune sweep;
    for (const auto& [a, b] : sweep.find_pairs(grown, std::vector<char>(n, 0))) {
      for (const auto& [i, j] : {std::pair<std::size_t, std::size_t>(a, b), std::pair<std::size_t, std::size_t>(b, a)}) {
        if (gap[i] == -kUnbounded || !below(i, j) || separation_bound(p.aabbs[i], p.aabbs[j]) >= gap[i]) continue;
        gap[i] = std::min(gap[i], -placed_pair_depth(p.placed.of(static_cast<int>(i)), p.placed.of(static_cast<int>(j))));
      }
    }
  }
  // Resolved: a gap within the body's reach is its gap (every body within reach was a pair).
  // The others float higher: their gap so far is an upper bound; taken from the highest down, each
  // is checked against every body until the bound falls to the largest gap found (it can no
  // longer change the result).
  double worst = 0.0;
  std::vector<std::size_t> floating;
  for (std::size_t i = 0; i < n; ++i) {
    if (gap[i] == -kUnbounded) continue;
    if (gap[i] <= reach[i]) {
      if (std::isfinite(gap[i])) worst = std::max(worst, gap[i]);
    } else {
      floating.push_back(i);
    }
  }
  std::sort(floating.begin(), floating.end(), [&](std::size_t a, std::size_t b) { return gap[a] > gap[b] || (gap[a] == gap[b] && a < b); });
  for (const std::size_t i : floating) {
    if (gap[i] <= worst) break;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || !below(i, j) || separation_bound(p.aabbs[i], p.aabbs[j]) >= gap[i]) continue;
      gap[i] = std::min(gap[i], -placed_pair_depth(p.placed.of(static_cast<int>(i)), p.placed.of(static_cast<int>(j))));
    }
    if (std::isfinite(gap[i])) worst = std::max(worst, gap[i]);
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
