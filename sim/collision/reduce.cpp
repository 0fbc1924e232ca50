#include "boxpile/sim/collision/reduce.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace boxpile {
namespace {

// Every score (a squared length or an area) is >= 0; a point already kept scores below them all.
constexpr double kKeptScore = -1.0;

using Scores = std::array<double, kMaxManifoldPoints>;

// Index of the point not yet kept (the first `n_kept` of `keep`) with the largest score, the
// first on a tie. Chosen without a branch (an index select and a maximum): which point wins is
// data, and a mispredicted branch per comparison cost more than the scores themselves.
int best_point(Scores s, int n_points, const std::array<int, 4>& keep, int n_kept) {
  for (int k = 0; k < n_kept; ++k) s[keep[k]] = kKeptScore;
  int best = -1;
  double best_score = kKeptScore;
  for (int i = 0; i < n_points; ++i) {
    best = s[i] > best_score ? i : best;
    best_score = std::max(best_score, s[i]);
  }
  return best;
}

// Twice the signed area of the triangle (a, b, p) seen along n: n . ((b - a) x (p - a)).
inline double twice_signed_area(const Vec3& n, const Vec3& a, const Vec3& b, const Vec3& p) {
  return n.dot((b - a).cross(p - a));
}

}  // namespace

void reduce_to_four(Manifold& m) {
  if (m.size() <= 4) return;
  // The normal and the kept points are read in place (m is not written before the end): copied
  // into locals they went through the stack in pieces and were read back across them, a stalled
  // store-to-load forward each.
  const Vec3& n = m[0].normal;
  const int count = m.size();
  std::array<int, 4> keep{};
  Scores score;

  // 1. The deepest point: it carries the most of the penetration.
  keep[0] = 0;
  double deepest = m[0].depth;
  for (int i = 1; i < count; ++i) {
    keep[0] = m[i].depth > deepest ? i : keep[0];
    deepest = std::max(deepest, m[i].depth);
  }
  const Vec3& p0 = m[keep[0]].position;

  // 2. The farthest point from it, measured in the contact plane.
  auto in_plane = [&](const Vec3& d) { return d - n.dot(d) * n; };
  for (int i = 0; i < count; ++i) score[i] = in_plane(m[i].position - p0).squaredNorm();
  keep[1] = best_point(score, count, keep, 1);
  const Vec3& p1 = m[keep[1]].position;

  // 3. The point spanning the largest triangle with the first two (twice its area: |e x f|).
  //    The signed areas are kept: they are step 4's areas along the edge p0 p1.
  Scores area01;
  for (int i = 0; i < count; ++i) area01[i] = twice_signed_area(n, p0, p1, m[i].position);
  for (int i = 0; i < count; ++i) score[i] = std::abs(area01[i]);
  keep[2] = best_point(score, count, keep, 2);
  const Vec3& p2 = m[keep[2]].position;

  // 4. The point adding the most area: outside the triangle, the largest signed triangle it forms
  //    with one of the three edges, taken on the side opposite the third vertex.
  const double orient = area01[keep[2]] >= 0.0 ? 1.0 : -1.0;
  for (int i = 0; i < count; ++i) {
    const Vec3& p = m[i].position;
    const double s01 = -orient * area01[i];
    const double s12 = -orient * twice_signed_area(n, p1, p2, p);
    const double s20 = -orient * twice_signed_area(n, p2, p0, p);
    score[i] = std::max(std::max(std::max(s01, s12), s20), 0.0);  // std::max({...}) took a branch
  }
  keep[3] = best_point(score, count, keep, 3);

  // In place: a second Manifold would be built (eight default contacts) and copied back whole.
  std::array<Contact, 4> kept;
  for (int k = 0; k < 4; ++k) kept[k] = m[keep[k]];
  for (int k = 0; k < 4; ++k) m[k] = kept[k];
  m.truncate(4);
}

}  // namespace boxpile
