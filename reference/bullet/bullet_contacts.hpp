// Bullet's contact set for one query (box-box or box-plane), normalised to our convention:
// position midway between the surfaces, normal from B toward A, depth > 0 when penetrating. The
// feature id of a reference contact holds only its kind (FaceA, FaceB or EdgeEdge judged from the
// normal, Plane for box-plane): Bullet numbers no features.
#pragma once

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// The points Bullet's solver would use: btBoxBoxDetector run through the dispatcher's collision
// algorithm into a fresh persistent manifold (at most 4 points; points closer than the contact
// breaking threshold merge).
Manifold bullet_box_box(const OrientedBox& a, const OrientedBox& b);

// Bullet's convex-plane algorithm adds one point (the deepest vertex) per call unless
// perturbation iterations are set (btDefaultCollisionConfiguration::
// setPlaneConvexMultipointIterations), which add the deepest vertex of slightly rotated copies.
struct BulletPlaneOptions {
  int perturbation_iterations = 0;  // 0: Bullet's default (no perturbation)
  int minimum_points = 3;           // perturb only while the manifold has fewer points
};
// The values setPlaneConvexMultipointIterations() uses when called without arguments.
inline constexpr BulletPlaneOptions kBulletMultipoint{3, 3};

Manifold bullet_box_plane(const OrientedBox& a, const HalfSpace& plane,
                          const BulletPlaneOptions& options = {});

}  // namespace boxpile
