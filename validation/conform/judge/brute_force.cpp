#include "boxpile/validation/conform/judge/brute_force.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace boxpile {
namespace {

// Directions almost normal to n cannot bound the translation along n.
constexpr double kGrazingDirection = 1e-9;

std::mt19937_64& unused_rng() {
  thread_local std::mt19937_64 rng;
  return rng;
}

Vec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

// Largest distance from a point of `from` to the nearest point of `to`.
double one_way_distance(const Manifold& from, const Manifold& to) {
  double worst = 0.0;
  for (const Contact& p : from) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Contact& q : to) nearest = std::min(nearest, (p.position - q.position).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

}  // namespace

double hausdorff(const Manifold& x, const Manifold& y) {
  return std::max(one_way_distance(x, y), one_way_distance(y, x));
}

double projected_overlap(const OrientedBox& a, const OrientedBox& b, const Vec3& u) {
  return a.radius_along(u) + b.radius_along(u) - std::abs((a.center - b.center).dot(u));
}

std::vector<Vec3> candidate_axes(const OrientedBox& a, const OrientedBox& b) {
  return candidate_axes(a, b, unused_rng(), 0);
}

std::vector<Vec3> candidate_axes(const OrientedBox& a, const OrientedBox& b, std::mt19937_64& rng, int extra) {
  std::vector<Vec3> axes;
  for (int i = 0; i < 3; ++i) {
    axes.push_back(a.axes.col(i));
    axes.push_back(b.axes.col(i));
    for (int j = 0; j < 3; ++j) {
      const Vec3 c = a.axes.col(i).cross(b.axes.col(j));
      if (c.norm() > kParallelAxisLength) axes.push_back(c.normalized());
    }
  }
  for (int k = 0; k < extra; ++k) axes.push_back(random_direction(rng));
  return axes;
}

double directional_penetration(const OrientedBox& a, const OrientedBox& b, const Vec3& n,
                               const std::vector<Vec3>& candidates) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& u : candidates) {
    for (const double sign : {1.0, -1.0}) {
      const Vec3 us = sign * u;
      const double nu = n.dot(us);
      if (nu < kGrazingDirection) continue;
      const double need = a.radius_along(us) + b.radius_along(us) - (a.center - b.center).dot(us);
      best = std::min(best, need / nu);
    }
  }
  return best;
}

double least_penetration(const OrientedBox& a, const OrientedBox& b, const std::vector<Vec3>& candidates) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& u : candidates) best = std::min(best, projected_overlap(a, b, u));
  return best;
}

double outside_distance(const OrientedBox& box, const Vec3& p) {
  const Vec3 local = box.axes.transpose() * (p - box.center);
  return (local.cwiseAbs() - box.half).maxCoeff();
}

}  // namespace boxpile
