// Shared helpers for the contact tests: box construction, seeded random poses, and brute-force
// reference quantities (directional penetration, point-set distances) computed without the
// code under test.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "sim/collision/box.hpp"
#include "sim/collision/contact.hpp"

namespace boxpile::test {

inline Quat axis_angle(const Vec3& axis, double angle) {
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

inline OrientedBox make_box(const Vec3& half, const Vec3& center, const Quat& q = Quat::Identity()) {
  return OrientedBox::from({center, q}, half);
}

// Seeds and sample counts: fixed by default so CI is repeatable; BOXPILE_SEED and BOXPILE_SAMPLES
// override them for long runs.
inline std::uint64_t test_seed(std::uint64_t fallback) {
  const char* s = std::getenv("BOXPILE_SEED");
  return s ? std::strtoull(s, nullptr, 10) : fallback;
}
inline int test_samples(int fallback) {
  const char* s = std::getenv("BOXPILE_SAMPLES");
  return s ? std::atoi(s) : fallback;
}

// Uniformly random rotations (Shoemake's method through a normalised 4D Gaussian).
inline Quat random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Quat q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized();
}

inline Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

// A random pair of boxes that mostly touch or overlap: extents in [0.1, 1] m, random
// orientations, A's centre in a random direction from B's, at 0.4 to 1.05 times the sum of their
// radii along that direction (so about one pair in five is apart).
struct BoxPair {
  OrientedBox a, b;
};
inline BoxPair random_touching_pair(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ext(0.1, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BoxPair p;
  p.b = make_box(Vec3(ext(rng), ext(rng), ext(rng)), Vec3::Zero(), random_rotation(rng));
  const Vec3 ha(ext(rng), ext(rng), ext(rng));
  const Quat qa = random_rotation(rng);
  const Vec3 dir = random_unit(rng);
  const OrientedBox probe = make_box(ha, Vec3::Zero(), qa);
  const double reach = probe.radius_along(dir) + p.b.radius_along(dir);
  p.a = make_box(ha, dir * reach * (0.4 + 0.65 * unit(rng)), qa);
  return p;
}

// Overlap of the two boxes' projections on unit direction u when A is moved by s n:
// rA(u) + rB(u) - |(cA + s n - cB) . u|.
inline double projected_overlap(const OrientedBox& a, const OrientedBox& b, const Vec3& u) {
  return a.radius_along(u) + b.radius_along(u) - std::abs((a.center - b.center).dot(u));
}

// Candidate separating directions, found without the code under test: both boxes' axes, every
// cross product of their axes, and `extra` random directions.
inline std::vector<Vec3> candidate_axes(const OrientedBox& a, const OrientedBox& b,
                                        std::mt19937_64& rng, int extra) {
  std::vector<Vec3> axes;
  for (int i = 0; i < 3; ++i) {
    axes.push_back(a.axes.col(i));
    axes.push_back(b.axes.col(i));
    for (int j = 0; j < 3; ++j) {
      const Vec3 c = a.axes.col(i).cross(b.axes.col(j));
      if (c.norm() > 1e-9) axes.push_back(c.normalized());
    }
  }
  for (int k = 0; k < extra; ++k) axes.push_back(random_unit(rng));
  return axes;
}

// The least translation of A along unit n (from B toward A) that separates the boxes, by brute
// force over the candidate directions u: A + s n leaves B's projection on u once
// s (n . u) > rA(u) + rB(u) - (cA - cB) . u. Exact when the candidates include the faces of the
// Minkowski difference, which for boxes are the 15 axes.
inline double directional_penetration(const OrientedBox& a, const OrientedBox& b, const Vec3& n,
                                      const std::vector<Vec3>& candidates) {
  double best = std::numeric_limits<double>::infinity();
  for (Vec3 u : candidates) {
    for (int sign : {1, -1}) {
      const Vec3 us = sign * u;
      const double nu = n.dot(us);
      if (nu < 1e-9) continue;
      const double need = a.radius_along(us) + b.radius_along(us) - (a.center - b.center).dot(us);
      best = std::min(best, need / nu);
    }
  }
  return best;
}

// Least penetration over the candidate directions (the depth of the minimal translation).
inline double least_penetration(const OrientedBox& a, const OrientedBox& b,
                                const std::vector<Vec3>& candidates) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& u : candidates) best = std::min(best, projected_overlap(a, b, u));
  return best;
}

// How far p lies outside the box (0 inside), in the box's own axes: the largest excess of
// |p_local_i| over h_i.
inline double outside_distance(const OrientedBox& box, const Vec3& p) {
  const Vec3 local = box.axes.transpose() * (p - box.center);
  return (local.cwiseAbs() - box.half).maxCoeff();
}

// Symmetric Hausdorff distance between two point sets (infinity when exactly one is empty).
template <class Points>
double hausdorff(const Points& x, const Points& y) {
  auto one_way = [](const Points& from, const Points& to) {
    double worst = 0.0;
    for (const auto& p : from) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& q : to) nearest = std::min(nearest, (p.position - q.position).norm());
      worst = std::max(worst, nearest);
    }
    return worst;
  };
  return std::max(one_way(x, y), one_way(y, x));
}

// The manifold has exactly the expected points, each matched by one contact within tol. For use
// inside Catch2 tests (the file including this must include catch.hpp first).
#ifdef REQUIRE
inline void require_points(const Manifold& m, const std::vector<Vec3>& expected, double tol) {
  REQUIRE(m.size() == static_cast<int>(expected.size()));
  for (const Vec3& e : expected) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Contact& c : m) nearest = std::min(nearest, (c.position - e).norm());
    INFO("expected point " << e.transpose());
    CHECK(nearest < tol);
  }
}
#endif

inline double max_depth(const Manifold& m) {
  double d = -std::numeric_limits<double>::infinity();
  for (const Contact& c : m) d = std::max(d, c.depth);
  return d;
}

}  // namespace boxpile::test
