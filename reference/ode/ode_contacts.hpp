// ODE's contact set for one query (box-box or box-plane), normalised to our convention: position
// midway between the surfaces, normal from B toward A, depth > 0 when penetrating. The feature id
// of a reference contact holds only its kind (FaceA, FaceB or EdgeEdge judged from the normal,
// Plane for box-plane): ODE numbers no features.
#pragma once

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// ODE's dCollide with room for 8 points: dBoxBox clips the incident face to the reference face
// (up to 8 points), or gives one edge-edge point.
Manifold ode_box_box(const OrientedBox& a, const OrientedBox& b);
// ODE's dCollide of a box and a plane geom: at most 4 vertices, the deepest first.
Manifold ode_box_plane(const OrientedBox& a, const HalfSpace& plane);

}  // namespace boxpile
