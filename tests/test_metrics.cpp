// The per-frame measurements through the broadphase give exactly what testing every pair gives:
// the deepest penetration (depth and pair, the first of equal depths) and the largest levitation
// gap, on random scenes of piles, floating bodies at rest, compounds, fixed bodies, with and
// without ground. The all-pairs loops below are the definitions of docs/metrics.md.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/sim/collision/broadphase.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/metrics.hpp"
#include "boxpile/tests/support/geometry.hpp"

using namespace boxpile;

namespace {

double all_pairs_ground_depth(const RigidBody& b, const HalfSpace& ground) {
  double deepest = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < static_cast<int>(b.shapes.size()); ++k)
    deepest = std::max(deepest, box_plane_depth(OrientedBox::from(b.shape_pose(k), b.shapes[k].half_extents), ground));
  return deepest;
}

Penetration all_pairs_penetration(const std::vector<RigidBody>& bodies, const std::optional<HalfSpace>& ground) {
  Penetration worst;
  const int n = static_cast<int>(bodies.size());
  for (int i = 0; i < n; ++i) {
    if (ground && !bodies[i].fixed) {
      const double d = all_pairs_ground_depth(bodies[i], *ground);
      if (d > worst.depth) worst = {d, i, kGround};
    }
    for (int j = i + 1; j < n; ++j) {
      if (bodies[i].fixed && bodies[j].fixed) continue;
      const double d = body_pair_depth(bodies[i], bodies[j]);
      if (d > worst.depth) worst = {d, i, j};
    }
  }
  return worst;
}

double all_pairs_levitation(const std::vector<RigidBody>& bodies, const std::optional<HalfSpace>& ground,
                            const Vec3& gravity, double rest_speed) {
  const Vec3 down = gravity.norm() > 0.0 ? Vec3(gravity.normalized()) : Vec3(-Vec3::UnitZ());
  double worst = 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const RigidBody& b = bodies[i];
    if (b.fixed) continue;
    const Aabb bounds = body_aabb(b, 0.0);
    const double size = bounds.hi.maxCoeff() - bounds.lo.minCoeff();
    if (b.v.norm() > rest_speed || b.omega.norm() * size > rest_speed) continue;
    double gap = ground ? -all_pairs_ground_depth(b, *ground) : std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < bodies.size(); ++j) {
      if (j == i || down.dot(bodies[j].x - b.x) <= 0.0) continue;
      gap = std::min(gap, -body_pair_depth(b, bodies[j]));
    }
    if (std::isfinite(gap)) worst = std::max(worst, gap);
  }
  return worst;
}

// n bodies in a box of `spread` m (a dense pile when small, floating bodies when large), sizes
// over two decades, every fourth a compound, a few fixed, about half at rest.
std::vector<RigidBody> random_scene(int n, double spread, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> pos(-spread, spread), height(0.0, 2.0 * spread), size(0.01, 0.5),
      unit(0.0, 1.0);
  Scene s;
  for (int i = 0; i < n; ++i) {
    BodyDesc b;
    b.name = std::string("b").append(std::to_string(i));
    b.boxes = {BoxShape{Vec3(size(rng), size(rng), size(rng)), Vec3::Zero(), Quat::Identity()}};
    if (i % 4 == 0) b.boxes.push_back(BoxShape{Vec3(size(rng), 0.05, 0.05), Vec3(0.3, 0, 0), Quat::UnitRandom()});
    b.frame = {Vec3(pos(rng), pos(rng), height(rng)), unit(rng) < 0.3 ? Quat::Identity() : Quat(Quat::UnitRandom())};
    b.fixed = unit(rng) < 0.05;
    if (unit(rng) < 0.5) b.velocity = Vec3(0.1, 0.0, -0.2);
    s.bodies.push_back(b);
  }
  return make_bodies(s);
}

}  // namespace

TEST_CASE("penetration and levitation through the broadphase equal the all-pairs loops", "[metrics]") {
  std::mt19937_64 rng(test::test_seed(11));
  const HalfSpace ground{Vec3::UnitZ(), 0.0};
  const Vec3 gravity(0.0, 0.0, -9.81);
  const int scenes = test::test_samples(1000) / 10;  // 100 by default, 20 under the sanitizers
  int levitating = 0, penetrating = 0;
  for (int k = 0; k < scenes; ++k) {
    const double spread = std::vector<double>{0.3, 1.0, 3.0, 30.0}[k % 4];
    const std::vector<RigidBody> bodies = random_scene(20 + k % 60, spread, rng);
    for (const std::optional<HalfSpace>& g : {std::optional<HalfSpace>(ground), std::optional<HalfSpace>()}) {
      INFO("scene " << k << ", spread " << spread << (g ? ", ground" : ", no ground"));
      const Penetration fast = measure_penetration(bodies, g), slow = all_pairs_penetration(bodies, g);
      CHECK(fast.depth == slow.depth);
      CHECK(fast.body_a == slow.body_a);
      CHECK(fast.body_b == slow.body_b);
      const double lev = measure_levitation(bodies, g, gravity, 1e-3);
      CHECK(lev == all_pairs_levitation(bodies, g, gravity, 1e-3));
      levitating += lev > 0.0;
      penetrating += fast.depth > 0.0;
    }
  }
  // The scenes exercise both measures (neither is zero everywhere).
  CHECK(levitating > scenes / 2);
  CHECK(penetrating > scenes / 2);
}
