// DART's contact sets for one query (box-box or box-plane) through each of its detectors,
// normalised to our convention (midpoint position, normal from B toward A, depth > 0 when
// penetrating; the feature id holds the kind only, judged from the normal).
#pragma once

#include "boxpile/reference/dart/dart_settings.hpp"
#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// The detector's box-box points, up to kMaxManifoldPoints (the deepest kept when it gives more).
Manifold dart_box_box(DartDetector detector, const OrientedBox& a, const OrientedBox& b);

// The detector's box-plane points as the engine sees the ground: ODE's against a plane shape, the
// others against the ground box (dart_ground_box, reference/dart/dart_convention.hpp).
Manifold dart_box_plane(DartDetector detector, const OrientedBox& a, const HalfSpace& plane);

}  // namespace boxpile
