// Properties of box-box contact generation over many random pose pairs (fixed seeds; override
// with BOXPILE_SEED and BOXPILE_SAMPLES for long runs). Each property is checked against values
// computed here without the code under test.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/tests/support/geometry.hpp"

using namespace boxpile;
using namespace boxpile::test;

namespace {

constexpr int kDefaultSamples = 10000;
// Geometric tolerance for boxes of 0.1-1 m: far above rounding (1e-15) and far below any
// physically meaningful distance.
constexpr double kTol = 1e-9;

Manifold collide(const OrientedBox& a, const OrientedBox& b) {
  Manifold m;
  collide_box_box(a, b, CollisionSettings{}, m);
  return m;
}

}  // namespace

TEST_CASE("swapping A and B flips the normal and keeps the points", "[box_box][property]") {
  std::mt19937_64 rng(test_seed(1));
  const int n = test_samples(kDefaultSamples);
  int touching = 0;
  for (int k = 0; k < n; ++k) {
    const BoxPair p = random_touching_pair(rng);
    const Manifold ab = collide(p.a, p.b);
    const Manifold ba = collide(p.b, p.a);
    INFO("sample " << k);
    REQUIRE(ab.size() == ba.size());
    if (ab.empty()) continue;
    ++touching;
    CHECK((ab[0].normal + ba[0].normal).norm() < kTol);
    CHECK(hausdorff(ab, ba) < kTol);
    CHECK(std::abs(max_depth(ab) - max_depth(ba)) < kTol);
  }
  CHECK(touching > n / 2);  // the generator mostly makes touching pairs
}

TEST_CASE("a rigid motion of both boxes moves the contacts with it", "[box_box][property]") {
  std::mt19937_64 rng(test_seed(2));
  std::uniform_real_distribution<double> shift(-100.0, 100.0);
  const int n = test_samples(kDefaultSamples);
  for (int k = 0; k < n; ++k) {
    const BoxPair p = random_touching_pair(rng);
    const Quat q = random_rotation(rng);
    const Vec3 t(shift(rng), shift(rng), shift(rng));
    auto moved = [&](const OrientedBox& b) {
      return OrientedBox{q * b.center + t, q.toRotationMatrix() * b.axes, b.half};
    };
    const Manifold m0 = collide(p.a, p.b);
    const Manifold m1 = collide(moved(p.a), moved(p.b));
    INFO("sample " << k);
    REQUIRE(m0.size() == m1.size());
    for (int i = 0; i < m0.size(); ++i) {
      // Positions are compared after the motion, so the tolerance scales with |t| ~ 100 m.
      CHECK((q * m0[i].position + t - m1[i].position).norm() < 100 * kTol);
      CHECK((q * m0[i].normal - m1[i].normal).norm() < kTol);
      CHECK(std::abs(m0[i].depth - m1[i].depth) < 100 * kTol);
      CHECK(m0[i].feature == m1[i].feature);
    }
  }
}

TEST_CASE("contact points lie in both boxes and depths match the brute-force penetration",
          "[box_box][property]") {
  std::mt19937_64 rng(test_seed(3));
  const int n = test_samples(kDefaultSamples);
  constexpr int kRandomDirections = 200;
  // The face bias (box_box.cpp) keeps a face axis unless an edge axis is shallower by 5% of the
  // face depth plus 1e-6 of the box size, so a face depth may exceed the least penetration by a
  // factor up to 1/0.95 (plus that absolute part); nothing else may exceed it.
  constexpr double kFaceBias = 0.05;
  auto biased = [&](double d, double scale) { return (d + 1e-6 * scale) / (1 - kFaceBias) + kTol; };
  int face_chosen_over_edge = 0;
  for (int k = 0; k < n; ++k) {
    const BoxPair p = random_touching_pair(rng);
    const Manifold m = collide(p.a, p.b);
    INFO("sample " << k);
    // Overlapping by the SAT means at least one contact point, and only then.
    CHECK(m.empty() == (box_box_sat(p.a, p.b).separation > 0.0));
    if (m.empty()) continue;
    const std::vector<Vec3> dirs = candidate_axes(p.a, p.b, rng, kRandomDirections);
    const Vec3 normal = m[0].normal;
    const double least = least_penetration(p.a, p.b, dirs);
    const double sat_depth = -box_box_sat(p.a, p.b).separation;
    const double scale = std::max(p.a.half.maxCoeff(), p.b.half.maxCoeff());

    // The SAT depth is the least penetration, or (faces over edges) at most the bias above it.
    CHECK(sat_depth >= least - kTol);
    CHECK(sat_depth <= biased(least, scale));
    if (sat_depth > least + kTol) ++face_chosen_over_edge;

    // No point is deeper than the least translation along the normal that separates the boxes
    // (plus the same bias when a face was preferred to an edge).
    const double along_normal = directional_penetration(p.a, p.b, normal, dirs);
    CHECK(max_depth(m) <= biased(along_normal, scale));

    for (const Contact& c : m) {
      CHECK(std::abs(c.normal.norm() - 1.0) < kTol);
      CHECK(c.depth >= -kTol);
      // The midpoint between the surfaces is inside each box, or outside by at most half the
      // depth (it lies depth/2 from each surface).
      CHECK(outside_distance(p.a, c.position) <= 0.5 * c.depth + kTol);
      CHECK(outside_distance(p.b, c.position) <= 0.5 * c.depth + kTol);
    }
  }
  WARN("face preferred to a shallower edge axis in " << face_chosen_over_edge << " of " << n);
}
