// Brute-force reference quantities for a pair of boxes, computed without any contact generator:
// penetration along a direction, the least penetration over the 15 separating-axis candidates,
// and how far a point lies outside a box. The judge of a collider's answers and the tests share
// them.
#pragma once

#include <random>
#include <vector>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

// Cross products of nearly parallel axes shorter than this are no separating direction.
inline constexpr double kParallelAxisLength = 1e-9;

// Overlap of the two boxes' projections on unit direction u: rA(u) + rB(u) - |(cA - cB) . u|.
double projected_overlap(const OrientedBox& a, const OrientedBox& b, const Vec3& u);

// Candidate separating directions: both boxes' axes and every non-degenerate cross product of
// their axes (the faces of the Minkowski difference of two boxes), normalised.
std::vector<Vec3> candidate_axes(const OrientedBox& a, const OrientedBox& b);
// The same, plus `extra` random unit directions.
std::vector<Vec3> candidate_axes(const OrientedBox& a, const OrientedBox& b, std::mt19937_64& rng, int extra);

// The least translation of A along unit n (from B toward A) that separates the boxes: A + s n
// leaves B's projection on u once s (n . u) > rA(u) + rB(u) - (cA - cB) . u, minimised over the
// candidates. Exact when the candidates include the 15 axes.
double directional_penetration(const OrientedBox& a, const OrientedBox& b, const Vec3& n,
                               const std::vector<Vec3>& candidates);

// Least penetration over the candidates: the depth of the minimal translation (negative: the
// boxes are apart by at least that much along some axis).
double least_penetration(const OrientedBox& a, const OrientedBox& b, const std::vector<Vec3>& candidates);

// How far p lies outside the box (0 or less inside), in the box's own axes: the largest excess
// of |p_local_i| over h_i.
double outside_distance(const OrientedBox& box, const Vec3& p);

// Symmetric Hausdorff distance between the positions of two contact sets, m (0 when both are
// empty, infinity when only one is).
double hausdorff(const Manifold& x, const Manifold& y);

}  // namespace boxpile
