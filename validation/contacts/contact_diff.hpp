// Comparing two contact sets of the same query from two detectors, another detector's set against
// a base set (every tool takes ours as the base, and each other registered detector in turn,
// validation/contacts/detectors.hpp): point counts, the angle between the normals, the difference of the
// deepest depths, and how the point sets sit in the contact plane (Hausdorff distance, and whether
// the smaller set lies inside the larger set's convex hull).
#pragma once

#include <optional>
#include <vector>

#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

// Distances in the contact plane below this count as zero when testing hull containment: far
// above the rounding of coordinates of a few metres (1e-15) and far below any contact feature.
inline constexpr double kHullTolerance = 1e-9;  // m

struct ContactDiff {
  int base_points = 0;
  int other_points = 0;
  // The remaining fields need points on both sides; they are empty otherwise.
  std::optional<double> normal_angle;      // rad, between the two sets' mean normals
  std::optional<double> depth_difference;  // m, the other's deepest depth - the base's deepest
  std::optional<double> hausdorff;         // m, symmetric Hausdorff distance in the contact plane
  // How far the smaller set's farthest point lies outside the larger set's convex hull in the
  // contact plane (normal to the base's normal), m (0 inside). On equal counts the other set's
  // points are tested.
  std::optional<double> hull_distance;
  bool other_tested = true;  // the other set's points were tested against the base's hull
  bool inside_hull = true;   // hull_distance <= tolerance (true when either set is empty)
};

ContactDiff diff_contacts(const Manifold& base, const Manifold& other, double hull_tolerance = kHullTolerance);

// The mean normal of a contact set, normalised (zero for an empty set).
Vec3 mean_normal(const Manifold& m);
// Deepest depth of a non-empty set.
double deepest_depth(const Manifold& m);

// Points of a plane through the origin with unit normal n, in 2D coordinates of that plane.
struct PlaneFrame {
  explicit PlaneFrame(const Vec3& n);
  Eigen::Vector2d project(const Vec3& p) const { return {u.dot(p), v.dot(p)}; }
  Vec3 u, v;
};

// The convex hull of 2D points, counter-clockwise, without repeated or collinear points: one
// point or a segment's two ends when the points are (nearly) collinear.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points);

// Distance from p to a convex hull as convex_hull() returns it (0 inside or on it).
double distance_to_hull(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& p);

// Distance in the plane normal to n from p to the convex hull of the region's points (the
// contact region a manifold spans).
double distance_to_region(const Manifold& region, const Vec3& n, const Vec3& p);

}  // namespace boxpile
