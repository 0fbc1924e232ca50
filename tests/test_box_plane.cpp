// Box against the ground half-space: flat, on an edge, on a vertex, and on a tilted plane.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/tests/support/geometry.hpp"

using namespace boxpile;
using namespace boxpile::test;
using Catch::Matchers::WithinAbs;

namespace {

const Vec3 kUnitHalf = Vec3::Constant(0.5);

Manifold collide(const OrientedBox& a, const HalfSpace& plane, double margin = 0.0) {
  Manifold m;
  collide_box_plane(a, plane, margin, m);
  return m;
}

}  // namespace

TEST_CASE("a box flat on the ground touches at its four bottom corners", "[box_plane]") {
  const HalfSpace ground;
  const Manifold m = collide(make_box(kUnitHalf, Vec3(1, 2, 0.49)), ground);
  require_points(m, {Vec3(0.5, 1.5, -0.005), Vec3(1.5, 1.5, -0.005), Vec3(0.5, 2.5, -0.005),
                     Vec3(1.5, 2.5, -0.005)}, 1e-12);
  for (const Contact& c : m) {
    CHECK(c.normal == Vec3::UnitZ());
    CHECK_THAT(c.depth, WithinAbs(0.01, 1e-12));
    CHECK(c.feature.kind() == FeatureKind::Plane);
  }
  CHECK_THAT(box_plane_depth(make_box(kUnitHalf, Vec3(1, 2, 0.49)), ground), WithinAbs(0.01, 1e-12));
}

TEST_CASE("resting exactly on the ground gives depth zero; lifted, nothing", "[box_plane]") {
  const HalfSpace ground;
  const Manifold resting = collide(make_box(kUnitHalf, Vec3(0, 0, 0.5)), ground);
  REQUIRE(resting.size() == 4);
  for (const Contact& c : resting) CHECK(c.depth == 0.0);
  CHECK(collide(make_box(kUnitHalf, Vec3(0, 0, 0.501)), ground).empty());
  // Within a margin the lifted box still reports its (negative-depth) points.
  const Manifold speculative = collide(make_box(kUnitHalf, Vec3(0, 0, 0.501)), ground, 0.002);
  REQUIRE(speculative.size() == 4);
  for (const Contact& c : speculative) CHECK_THAT(c.depth, WithinAbs(-0.001, 1e-12));
}

TEST_CASE("a box on an edge touches at the edge's two ends", "[box_plane]") {
  const double h = std::sqrt(2.0) / 2;
  const Manifold m = collide(make_box(kUnitHalf, Vec3(0, 0, h - 0.02), axis_angle(Vec3::UnitY(), M_PI / 4)),
                             HalfSpace{});
  require_points(m, {Vec3(0, -0.5, -0.01), Vec3(0, 0.5, -0.01)}, 1e-12);
  for (const Contact& c : m) CHECK_THAT(c.depth, WithinAbs(0.02, 1e-12));
}

TEST_CASE("a box on a vertex touches at that vertex", "[box_plane]") {
  const Quat q = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), -Vec3::UnitZ());
  const double h = std::sqrt(3.0) / 2;
  const Manifold m = collide(make_box(kUnitHalf, Vec3(-3, 4, h - 0.02), q), HalfSpace{});
  require_points(m, {Vec3(-3, 4, -0.01)}, 1e-12);
  CHECK_THAT(m[0].depth, WithinAbs(0.02, 1e-12));
}

TEST_CASE("a box lying flat on a tilted plane of any normal", "[box_plane]") {
  // Plane through the point o with normal n tilted 30 degrees about x; the box is rotated the
  // same way and sunk 5 mm into it.
  const Quat tilt = axis_angle(Vec3::UnitX(), M_PI / 6);
  const Vec3 n = tilt * Vec3::UnitZ();
  const Vec3 o(0.2, -0.3, 1.0);
  const HalfSpace plane{n, n.dot(o)};
  const OrientedBox box = make_box(Vec3(0.4, 0.3, 0.2), o + (0.2 - 0.005) * n, tilt);
  const Manifold m = collide(box, plane);
  std::vector<Vec3> expected;
  for (double x : {-0.4, 0.4})
    for (double y : {-0.3, 0.3}) expected.push_back(o + tilt * Vec3(x, y, 0) - 0.0025 * n);
  require_points(m, expected, 1e-12);
  for (const Contact& c : m) {
    CHECK((c.normal - n).norm() < 1e-15);
    CHECK_THAT(c.depth, WithinAbs(0.005, 1e-12));
  }
}

TEST_CASE("the quick rejection of a box above the margin keeps every vertex the full test keeps",
          "[box_plane]") {
  // Boxes of any size, pose and plane whose lowest vertex lies within 1e-9 of the margin's edge,
  // on both sides: the reported points are exactly those of testing all eight vertices.
  std::mt19937_64 rng(test_seed(11));
  std::uniform_real_distribution<double> unit(-1.0, 1.0), size(0.001, 10.0), far(-100.0, 100.0);
  std::uniform_real_distribution<double> near_edge(-1e-9, 1e-9);
  int kept = 0, rejected = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 normal = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    const HalfSpace plane{normal, far(rng)};
    const double margin = k % 2 ? 0.0 : 0.01 * size(rng);
    OrientedBox box = make_box(Vec3(size(rng), size(rng), size(rng)), Vec3(far(rng), far(rng), far(rng)),
                               Quat::UnitRandom());
    // Move the box along the normal so that its deepest vertex is near depth -margin.
    box.center += (box_plane_depth(box, plane) + margin + near_edge(rng)) * normal;
    Manifold expected;
    for (int v = 0; v < 8; ++v) {
      const double depth = plane.offset - plane.normal.dot(box.vertex(v));
      if (depth >= -margin) expected.push_back({box.vertex(v) + 0.5 * depth * plane.normal, plane.normal, depth,
                                                FeatureId::make(FeatureKind::Plane, v, 0, 0)});
    }
    const Manifold m = collide(box, plane, margin);
    REQUIRE(m.size() == expected.size());
    for (int i = 0; i < m.size(); ++i) {
      CHECK(m[i].position == expected[i].position);
      CHECK(m[i].depth == expected[i].depth);
      CHECK(m[i].feature == expected[i].feature);
    }
    (m.empty() ? rejected : kept) += 1;
  }
  // Both sides of the edge were exercised.
  CHECK(kept > 1000);
  CHECK(rejected > 1000);
}
