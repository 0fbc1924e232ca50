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
