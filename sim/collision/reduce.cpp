#include "boxpile/sim/collision/reduce.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace boxpile {
namespace {

// Index of the point, not yet chosen, that maximises score(point).
template <class Score>
int best_point(const Manifold& m, const std::array<bool, kMaxManifoldPoints>& taken, Score score) {
  int best = -1;
  double best_score = -1.0;
  for (int i = 0; i < m.size(); ++i) {
    if (taken[i]) continue;
    const double s = score(m[i].position);
    if (s > best_score) {
      best_score = s;
      best = i;
    }
  }
  return best;
}

}  // namespace

void reduce_to_four(Manifold& m) {
  if (m.size() <= 4) return;
  const Vec3 n = m[0].normal;
  std::array<bool, kMaxManifoldPoints> taken{};
  std::array<int, 4> keep{};

  // 1. The deepest point: it carries the most of the penetration.
  keep[0] = 0;
  for (int i = 1; i < m.size(); ++i)
    if (m[i].depth > m[keep[0]].depth) keep[0] = i;
  taken[keep[0]] = true;
  const Vec3 p0 = m[keep[0]].position;

  // 2. The farthest point from it, measured in the contact plane.
  auto in_plane = [&](const Vec3& d) { return d - n.dot(d) * n; };
  keep[1] = best_point(m, taken, [&](const Vec3& p) { return in_plane(p - p0).squaredNorm(); });
  taken[keep[1]] = true;
  const Vec3 p1 = m[keep[1]].position;

  // 3. The point spanning the largest triangle with the first two (twice its area: |e x f|).
  keep[2] = best_point(m, taken, [&](const Vec3& p) { return std::abs(n.dot((p1 - p0).cross(p - p0))); });
  taken[keep[2]] = true;
  const Vec3 p2 = m[keep[2]].position;

  // 4. The point adding the most area: outside the triangle, the largest signed triangle it forms
  //    with one of the three edges, taken on the side opposite the third vertex.
  const double orient = n.dot((p1 - p0).cross(p2 - p0)) >= 0.0 ? 1.0 : -1.0;
  keep[3] = best_point(m, taken, [&](const Vec3& p) {
    const double s01 = -orient * n.dot((p1 - p0).cross(p - p0));
    const double s12 = -orient * n.dot((p2 - p1).cross(p - p1));
    const double s20 = -orient * n.dot((p0 - p2).cross(p - p2));
    return std::max({s01, s12, s20, 0.0});
  });

  Manifold reduced;
  for (int k : keep) reduced.push_back(m[k]);
  m = reduced;
}

}  // namespace boxpile
