#include "boxpile/validation/conform/known_biases.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace boxpile {
namespace {

// A normal within this of an edge pair's cross product is that pair's direction (Bullet's
// normal is the normalised cross product itself, to rounding).
constexpr double kEdgeDirectionCos = 1.0 - 1e-9;

double edge_fudge_of(const ContactQuery& q, const Manifold& m) {
  if (!q.b || m.empty()) return 0.0;
  return bullet_edge_fudge(q.a.box(), q.b->box(), m.deepest().normal.normalized());
}

// A normal along a face axis of the box (ODE's and Bullet's face normals are axes to rounding).
bool along_an_axis(const OrientedBox& box, const Vec3& n) {
  return (box.axes.transpose() * n).cwiseAbs().maxCoeff() > kEdgeDirectionCos;
}

// A swap finding on the points alone: the deepest depths of both answers agree.
bool swap_of_points(const JudgedAnswer& j) {
  return j.finding.kind == FailureKind::Swap && j.finding.unit == ErrorUnit::Metre && j.swapped && !j.answer.empty() &&
         !j.swapped->empty() && std::abs(j.answer.deepest().depth - j.swapped->deepest().depth) <= j.tol.depth;
}

// --- ODE and Bullet (Bullet's box-box is a port of ODE's) ----------------------------------------

// An edge-edge point at the closest points of the two infinite edge lines, outside the boxes
// when that edge pair does not touch (fixture ode_edge_point_outside).
bool edge_point_off_the_edges(const JudgedAnswer& j) {
  if (j.finding.kind != FailureKind::Outside || !j.query.b || j.answer.size() != 1) return false;
  const Vec3 n = j.answer[0].normal.normalized();
  return !along_an_axis(j.query.a.box(), n) && !along_an_axis(j.query.b->box(), n);
}

// --- ODE -------------------------------------------------------------------------------------

// Between parallel faces ODE's points lie on one box's surface and do not say which (the adapter
// guesses from the point, reference/convention.hpp): swapped, a point guessed the other way moves
// by twice its distance to the midway plane. Measured 1.992 to 2.008 times the deepest depth on
// the 132 largest moves of 5,000 pairs (714 parallel); this bound leaves 5% for the points'
// own depths.
constexpr double kOdeParallelMove = 2.1;  // times the deepest depth

bool ode_parallel_face_points(const JudgedAnswer& j) {
  if (!swap_of_points(j)) return false;
  const Vec3 n = j.answer.deepest().normal.normalized();
  return along_an_axis(j.query.a.box(), n) && along_an_axis(j.query.b->box(), n) &&
         j.finding.error <= kOdeParallelMove * j.answer.deepest().depth + j.tol.region;
}

// --- Bullet ----------------------------------------------------------------------------------

// Its manifold keeps 4 points of a larger face polygon, chosen by the order they come in:
// swapped, another 4 of the same polygon.
bool bullet_culled_face_points(const JudgedAnswer& j) {
  if (!swap_of_points(j)) return false;
  constexpr int kBulletManifoldPoints = 4;
  const Vec3 n = j.answer.deepest().normal.normalized();
  const bool face = along_an_axis(j.query.a.box(), n) || along_an_axis(j.query.b->box(), n);
  return face && (j.answer.size() == kBulletManifoldPoints || j.swapped->size() == kBulletManifoldPoints);
}

// Its edge-edge depth: the truth plus fudge2.
bool bullet_deeper_edge(const JudgedAnswer& j) {
  if (j.finding.kind != FailureKind::Depth) return false;
  const double fudge = edge_fudge_of(j.query, j.answer);
  return fudge > 0.0 && std::abs(j.finding.error - fudge) <= j.tol.depth;
}

// Boxes apart by less than fudge2 touch in Bullet (fixture bullet_phantom_edge).
bool bullet_phantom_edge(const JudgedAnswer& j) {
  if (j.finding.kind != FailureKind::Phantom) return false;
  const double fudge = edge_fudge_of(j.query, j.answer);
  return fudge > 0.0 && j.finding.error <= fudge + j.tol.depth;
}

// fudge2 depends on which edge pair Bullet takes, and moves its point along the normal with the
// depth: swapped, depth and points differ by up to twice the term.
bool bullet_edge_swap(const JudgedAnswer& j) {
  if (j.finding.kind != FailureKind::Swap || j.finding.unit != ErrorUnit::Metre || !j.swapped) return false;
  const double fudge = std::max(edge_fudge_of(j.query, j.answer), j.swapped->empty() ? 0.0 : [&] {
    ContactQuery back = j.query;
    std::swap(back.a, *back.b);
    return edge_fudge_of(back, *j.swapped);
  }());
  return fudge > 0.0 && j.finding.error <= 2.0 * fudge + j.tol.region;
}

const std::array<KnownBias, 7> kBiases = {{
    {"ode", "edge-edge point off the edges",
     "an edge-edge point at the closest points of the infinite edge lines, outside the boxes when that edge pair "
     "does not touch (fixture ode_edge_point_outside; 2e-4 of the conformance suite's pairs)",
     &edge_point_off_the_edges},
    {"ode", "parallel-face points on one surface",
     "between parallel faces its points lie on one box's surface without saying which: with A and B swapped they "
     "move by up to twice the depth (the parallel regime)",
     &ode_parallel_face_points},
    {"bullet", "edge-edge point off the edges", "as ODE's (its box-box is a port of dBoxBox)",
     &edge_point_off_the_edges},
    {"bullet", "4 of a face's points",
     "its manifold keeps 4 points of a larger face polygon, chosen by the order they come in: with A and B swapped, "
     "another 4 (docs/reference-engines.md)",
     &bullet_culled_face_points},
    {"bullet", "edge-edge depth + fudge2",
     "its edge-edge depth exceeds the true one by 1e-5 (sum of the four half extents) / |Ai x Bj| "
     "(docs/reference-engines.md; exactly so on every sample of the conformance suite)",
     &bullet_deeper_edge},
    {"bullet", "phantom edge contact within fudge2",
     "boxes apart by less than its fudge2 term touch along an edge axis (fixture bullet_phantom_edge)",
     &bullet_phantom_edge},
    {"bullet", "edge-edge swap within fudge2",
     "with A and B swapped its edge-edge depth and point move by up to twice the fudge2 term",
     &bullet_edge_swap},
}};

}  // namespace

double bullet_edge_fudge(const OrientedBox& a, const OrientedBox& b, const Vec3& n) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vec3 c = a.axes.col(i).cross(b.axes.col(j));
      const double len = c.norm();
      if (len < 1e-9 || std::abs(c.dot(n)) / len < kEdgeDirectionCos) continue;
      const double halves = a.half.sum() - a.half[i] + b.half.sum() - b.half[j];
      return kBulletEdgeFudge * halves / len;
    }
  }
  return 0.0;
}

std::span<const KnownBias> known_biases() { return kBiases; }

const KnownBias* explaining_bias(std::string_view detector, const JudgedAnswer& judged) {
  for (const KnownBias& b : kBiases) {
    if (b.detector == detector && b.explains(judged)) return &b;
  }
  return nullptr;
}

}  // namespace boxpile
