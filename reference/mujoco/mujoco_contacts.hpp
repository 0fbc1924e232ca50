// MuJoCo 2.2.2's contact sets for one query (box-box or box-plane), in our convention: position
// midway between the surfaces, normal from B toward A, depth > 0 when penetrating; the feature id
// holds the kind only (FaceA, FaceB or EdgeEdge judged from the normal, Plane for box-plane).
#pragma once

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// MuJoCo's collision function table (mjCOLLISIONFUNC) for two box geoms (mjc_BoxBox) and for a
// plane and a box (mjc_PlaneBox), called with margin 0 as mj_collision calls them for the
// engine's geoms. At most kMaxManifoldPoints points are kept, the deepest first.
Manifold mujoco_box_box(const OrientedBox& a, const OrientedBox& b);
Manifold mujoco_box_plane(const OrientedBox& a, const HalfSpace& plane);

}  // namespace boxpile
