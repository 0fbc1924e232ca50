// Box-box contact generation by the separating-axis test (Eberly, "Game Physics", ch. 5;
// Erleben's thesis pp. 178-183), written for boxpile from the math.
#pragma once

#include <limits>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// The axis of least penetration found by the separating-axis test.
struct SatResult {
  double separation = 0.0;      // > 0: separated by at least this much; <= 0: -depth
  Vec3 normal = Vec3::UnitZ();  // unit, from B toward A
  FeatureKind kind = FeatureKind::FaceA;
  int axis_a = 0;  // face axis of A (FaceA), or A's edge axis (EdgeEdge)
  int axis_b = 0;  // face axis of B (FaceB), or B's edge axis (EdgeEdge)
};

// Separating-axis test over the 15 axes: A's 3 face normals, B's 3, and the 9 edge cross products
// (near-parallel edge pairs skipped). On near-ties faces win over edges (see box_box.cpp).
// The test stops once an axis separates by more than `stop_above`: after the face axes (the
// largest of the six) or at the first such edge axis; the separation returned is then a lower
// bound of the largest one (the default tests every axis).
SatResult box_box_sat(const OrientedBox& a, const OrientedBox& b,
                      double stop_above = std::numeric_limits<double>::infinity());

// An edge-edge axis within this angle's cosine of the best face normal means two nearly aligned
// boxes (a brick 0.02 rad off the one under it): their edge-edge point alone lets them turn about
// it, and the corners it does not hold sank 2.2 mm (1% of the brick) within one step. The face's
// clipped points join the edge point then, in its normal (docs/contacts.md).
inline constexpr double kEdgeNearFaceCos = 0.995;  // 0.1 rad

// The contact set of two boxes: a clipped face polygon (up to 8 points), or an edge-edge point,
// followed by the best face's clipped points when that face is within kEdgeNearFaceCos of it.
// `out` is cleared first and left empty when the boxes are separated by more than settings.margin.
void collide_box_box(const OrientedBox& a, const OrientedBox& b, const CollisionSettings& settings,
                     Manifold& out);

}  // namespace boxpile
