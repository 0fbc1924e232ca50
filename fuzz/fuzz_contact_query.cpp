// libFuzzer target: the contact query (`boxpile contacts`): the query loader, then our box-box or
// box-plane detector and ODE's and Bullet's on what it accepts. What must hold: parse_query throws
// InputError or returns a query every detector answers without crashing, and our contacts have
// finite positions and depths and unit normals.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "boxpile/reference/ode_engine.hpp"
#include "boxpile/reference/reference_contacts.hpp"
#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/sim/io/query_loader.hpp"

namespace {

using namespace boxpile;

// A normal is unit to rounding: far looser than the 1e-15 of a normalised double vector.
constexpr double kUnitTolerance = 1e-9;

void check(const Manifold& m) {
  for (const Contact& c : m) {
    const bool ok = c.position.allFinite() && std::isfinite(c.depth) &&
                    std::abs(c.normal.norm() - 1.0) < kUnitTolerance;
    if (!ok) {
      std::fprintf(stderr, "bad contact: position (%g %g %g) normal (%g %g %g) depth %g\n", c.position.x(),
                   c.position.y(), c.position.z(), c.normal.x(), c.normal.y(), c.normal.z(), c.depth);
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ContactQuery query;
  try {
    query = parse_query(text, "fuzz.json");
  } catch (const InputError&) {
    return 0;
  }
  const OrientedBox a = OrientedBox::from(query.a.pose, query.a.half_extents);
  Manifold own;
  try {
    if (query.b) {
      const OrientedBox b = OrientedBox::from(query.b->pose, query.b->half_extents);
      collide_box_box(a, b, CollisionSettings{}, own);
      static_cast<void>(ode_box_box(a, b));
      static_cast<void>(bullet_box_box(a, b));
    } else {
      collide_box_plane(a, *query.plane, 0.0, own);
      static_cast<void>(ode_box_plane(a, *query.plane));
      static_cast<void>(bullet_box_plane(a, *query.plane));
    }
  } catch (const OdeError& e) {
    std::fprintf(stderr, "accepted query reached an ODE error: %s\n", e.what());
    std::abort();
  }
  check(own);
  return 0;
}
