#include "boxpile/sim/collision/reduce.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace boxpile {
namespace {

// Every score (a squared length or an area) is >= 0; a point already kept scores below them all.
constexpr double kKeptScore = -1.0;

// Index of the point not yet kept (the first `n_kept` of `keep`) that maximises score(point), the
// first on a tie. Chosen without a branch (an index select and a maximum): which point wins is
// data, and a mispredicted branch per comparison cost more than the scores themselves.
template <class Score>
int best_point(const Manifold& m, const std::array<int, 4>& keep, int n_kept, Score score) {
  std::array<double, kMaxManifoldPoints> s;
  for (int i = 0; i < m.size(); ++i) s[i] = score(m[i].position);
  for (int k = 0; k < n_kept; ++k) s[keep[k]] = kKeptScore;
  int best = -1;
  double best_score = kKeptScore;
  for (int i = 0; i < m.size(); ++i) {
    best = s[i] > best_score ? i : best;
    best_score = std::max(best_score, s[i]);
  }
  return best;
}

}  // namespace

void reduce_to_four(Manifold& m) {
  if (m.size() <= 4) return;
  // The normal and the kept points are read in place (m is not written before the end): copied
  // into locals they went through the stack in pieces and were read back across them, a stalled
  // store-to-load forward each.
  const Vec3& n = m[0].normal;
  std::array<int, 4> keep{};

  // 1. The deepest point: it carries the most of the penetration.
  keep[0] = 0;
  double deepest = m[0].depth;
  for (int i = 1; i < m.size(); ++i) {
    keep[0] = m[i].depth > deepest ? i : keep[0];
    deepest = std::max(deepest, m[i].depth);
  }
  const Vec3& p0 = m[keep[0]].position;

  // 2. The farthest point from it, measured in the contact plane.
  auto in_plane = [&](const Vec3& d) { return d - n.dot(d) * n; };
  keep[1] = best_point(m, keep, 1, [&](const Vec3& p) { return in_plane(p - p0).squaredNorm(); });
  const Vec3& p1 = m[keep[1]].position;

  // 3. The point spanning the largest triangle with the first two (twice its area: |e x f|).
  keep[2] = best_point(m, keep, 2, [&](const Vec3& p) { return std::abs(n.dot((p1 - p0).cross(p - p0))); });
  const Vec3& p2 = m[keep[2]].position;

  // 4. The point adding the most area: outside the triangle, the largest signed triangle it forms
  //    with one of the three edges, taken on the side opposite the third vertex.
  const double orient = n.dot((p1 - p0).cross(p2 - p0)) >= 0.0 ? 1.0 : -1.0;
  keep[3] = best_point(m, keep, 3, [&](const Vec3& p) {
    const double s01 = -orient * n.dot((p1 - p0).cross(p - p0));
    const double s12 = -orient * n.dot((p2 - p1).cross(p - p1));
    const double s20 = -orient * n.dot((p0 - p2).cross(p - p2));
    return std::max(std::max(std::max(s01, s12), s20), 0.0);  // std::max({...}) took a branch
  });

  // In place: a second Manifold would be built (eight default contacts) and copied back whole.
  std::array<Contact, 4> kept;
  for (int k = 0; k < 4; ++k) kept[k] = m[keep[k]];
  for (int k = 0; k < 4; ++k) m[k] = kept[k];
  m.truncate(4);
}

}  // namespace boxpile
