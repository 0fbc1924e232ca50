// Box against a half-space of any normal: every vertex below the plane is a contact.
#pragma once

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// Box A against the half-space B (solid where n . x < offset). Normals are the plane normal
// (from B toward A); up to 8 points; vertices within `margin` above the plane count too.
// `out` is cleared first.
void collide_box_plane(const OrientedBox& a, const HalfSpace& plane, double margin, Manifold& out);

// Depth of the deepest vertex below the plane (negative: the box's gap above it).
double box_plane_depth(const OrientedBox& a, const HalfSpace& plane);

}  // namespace boxpile
