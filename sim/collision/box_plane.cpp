#include "boxpile/sim/collision/box_plane.hpp"

#include <cmath>

namespace boxpile {
namespace {

// The quick rejection below compares the box's lowest point, found through its radius along the
// normal, with the margin; the vertex loop finds the same depths with different rounding. This
// relative slack (many times double rounding over a dozen operations) keeps the rejection from
// ever dropping a vertex that the loop would keep.
constexpr double kRejectSlack = 1e-12;  // times the magnitudes involved

}  // namespace

void collide_box_plane(const OrientedBox& a, const HalfSpace& plane, double margin, Manifold& out) {
  out.clear();
  // A box wholly above the margin has no vertex to test: most boxes of a pile, every step.
  const double gap = -box_plane_depth(a, plane);
  const double magnitude = std::abs(plane.offset) + a.center.cwiseAbs().sum() + a.half.sum() + margin;
  if (gap > margin + kRejectSlack * magnitude) return;
  // Vertex v lies below the plane by depth = offset - n . v. The plane's surface point under v is
  // v + depth n, so the midpoint between the surfaces is v + (depth / 2) n.
  for (int k = 0; k < 8; ++k) {
    const Vec3 v = a.vertex(k);
    const double depth = plane.offset - plane.normal.dot(v);
    if (depth < -margin) continue;
    out.push_back({v + 0.5 * depth * plane.normal, plane.normal, depth,
                   FeatureId::make(FeatureKind::Plane, k, 0, 0)});
  }
}

double box_plane_depth(const OrientedBox& a, const HalfSpace& plane) {
  // The lowest vertex along n sits at n . c - r(n), with r the box radius along n.
  return plane.offset - (plane.normal.dot(a.center) - a.radius_along(plane.normal));
}

}  // namespace boxpile
