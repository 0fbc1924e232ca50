// Reducing a manifold to at most four points that keep its support area.
#pragma once

#include "boxpile/sim/collision/contact.hpp"

namespace boxpile {

// Keeps the deepest point, then the point farthest from it, then the point that spans the
// largest triangle with those two, then the point that adds the most area (measured in the plane
// normal to the manifold's normal). Leaves manifolds of four or fewer points unchanged.
void reduce_to_four(Manifold& m);

}  // namespace boxpile
