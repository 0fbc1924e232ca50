#include "boxpile/sim/collision/box_plane.hpp"

namespace boxpile {

void collide_box_plane(const OrientedBox& a, const HalfSpace& plane, double margin, Manifold& out) {
  out.clear();
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
