#include "boxpile/validation/contacts/contact_diff.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace boxpile {
namespace {

// Points closer than this (relative to the hull's size) are merged, and a turn whose cross
// product is below it counts as collinear: the hull then has no slivers made of rounding noise.
constexpr double kHullRelativeTolerance = 1e-12;

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

double distance_to_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

std::vector<Eigen::Vector2d> projected(const Manifold& m, const PlaneFrame& frame) {
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(static_cast<std::size_t>(m.size()));
  for (const Contact& c : m) pts.push_back(frame.project(c.position));
  return pts;
}

// One-way Hausdorff: the farthest any point of `from` is from its nearest point of `to`.
double one_way_hausdorff(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& to) {
  double worst = 0.0;
  for (const auto& p : from) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& q : to) nearest = std::min(nearest, (p - q).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

}  // namespace

PlaneFrame::PlaneFrame(const Vec3& n) {
  // Any unit vector normal to n, then the third completing a right-handed frame.
  const Vec3 helper = std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  u = n.cross(helper).normalized();
  v = n.cross(u);
}

std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  // Andrew's monotone chain: sort by x then y, build the lower and upper chains, keeping only
  // strict left turns.
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.empty()) return points;
  double size = 0.0;
  for (const auto& p : points) size = std::max(size, (p - points.front()).norm());
  const double eps = kHullRelativeTolerance * std::max(size, 1.0);
  points.erase(std::unique(points.begin(), points.end(),
                           [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return (a - b).norm() <= eps; }),
               points.end());
  if (points.size() < 3) return points;

  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  const double turn_eps = eps * std::max(size, 1.0);
  for (const auto& p : points) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= turn_eps) --k;
    hull[k++] = p;
  }
  const std::size_t lower = k + 1;
  for (auto it = points.rbegin() + 1; it != points.rend(); ++it) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], *it) <= turn_eps) --k;
    hull[k++] = *it;
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

double distance_to_hull(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& p) {
  if (hull.empty()) return std::numeric_limits<double>::infinity();
  if (hull.size() == 1) return (hull[0] - p).norm();
  if (hull.size() == 2) return distance_to_segment(hull[0], hull[1], p);
  bool inside = true;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& a = hull[i];
    const auto& b = hull[(i + 1) % hull.size()];
    if (cross(a, b, p) < 0.0) inside = false;  // right of a counter-clockwise edge
    nearest = std::min(nearest, distance_to_segment(a, b, p));
  }
  return inside ? 0.0 : nearest;
}

double distance_to_region(const Manifold& region, const Vec3& n, const Vec3& p) {
  const PlaneFrame frame(n);
  return distance_to_hull(convex_hull(projected(region, frame)), frame.project(p));
}

Vec3 mean_normal(const Manifold& m) {
  Vec3 sum = Vec3::Zero();
  for (const Contact& c : m) sum += c.normal;
  return sum.norm() > 0.0 ? Vec3(sum.normalized()) : Vec3::Zero();
}

double deepest_depth(const Manifold& m) {
  double d = -std::numeric_limits<double>::infinity();
  for (const Contact& c : m) d = std::max(d, c.depth);
  return d;
}

ContactDiff diff_contacts(const Manifold& base, const Manifold& other, double hull_tolerance) {
  ContactDiff d;
  d.base_points = base.size();
  d.other_points = other.size();
  d.other_tested = other.size() <= base.size();
  if (base.empty() || other.empty()) return d;

  const Vec3 n_base = mean_normal(base);
  const Vec3 n_other = mean_normal(other);
  // atan2 of |sin| and cos keeps small angles accurate (acos loses them near 1).
  d.normal_angle = std::atan2(n_base.cross(n_other).norm(), n_base.dot(n_other));
  d.depth_difference = deepest_depth(other) - deepest_depth(base);

  // The contact plane is normal to the base's normal.
  const PlaneFrame frame(n_base);
  const auto p_base = projected(base, frame);
  const auto p_other = projected(other, frame);
  d.hausdorff = std::max(one_way_hausdorff(p_base, p_other), one_way_hausdorff(p_other, p_base));

  const auto& smaller = d.other_tested ? p_other : p_base;
  const auto hull = convex_hull(d.other_tested ? p_base : p_other);
  double worst = 0.0;
  for (const auto& p : smaller) worst = std::max(worst, distance_to_hull(hull, p));
  d.hull_distance = worst;
  d.inside_hull = worst <= hull_tolerance;
  return d;
}

}  // namespace boxpile
