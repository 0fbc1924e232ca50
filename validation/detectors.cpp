#include "boxpile/validation/detectors.hpp"

#include <array>
#include <string>

#include "boxpile/reference/reference_contacts.hpp"
#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"

namespace boxpile {
namespace {

OrientedBox box_a(const ContactQuery& q) { return OrientedBox::from(q.a.pose, q.a.half_extents); }
OrientedBox box_b(const ContactQuery& q) { return OrientedBox::from(q.b->pose, q.b->half_extents); }

Manifold own(const ContactQuery& q, const DetectOptions& options) {
  Manifold m;
  if (q.b) {
    CollisionSettings settings;
    settings.reduce_to_four = options.reduce;
    collide_box_box(box_a(q), box_b(q), settings, m);
  } else {
    collide_box_plane(box_a(q), *q.plane, 0.0, m);
  }
  return m;
}

Manifold ode(const ContactQuery& q, const DetectOptions&) {
  return q.b ? ode_box_box(box_a(q), box_b(q)) : ode_box_plane(box_a(q), *q.plane);
}

Manifold bullet(const ContactQuery& q, const DetectOptions&) {
  return q.b ? bullet_box_box(box_a(q), box_b(q)) : bullet_box_plane(box_a(q), *q.plane);
}

Manifold bullet_multipoint(const ContactQuery& q, const DetectOptions&) {
  return q.b ? bullet_box_box(box_a(q), box_b(q)) : bullet_box_plane(box_a(q), *q.plane, kBulletMultipoint);
}

const std::array<DetectorInfo, 4> kDetectors = {{
    {"own", "boxpile's separating-axis test with face clipping", false, &own},
    {"ode", "ODE's dCollide (dBoxBox, box-plane)", false, &ode},
    {"bullet", "Bullet's btBoxBoxDetector through a persistent manifold", false, &bullet},
    {"bullet_multipoint", "Bullet with setPlaneConvexMultipointIterations(3, 3)", true, &bullet_multipoint},
}};

}  // namespace

std::span<const DetectorInfo> detectors() { return kDetectors; }

const DetectorInfo& find_detector(std::string_view name) {
  for (const DetectorInfo& d : kDetectors) {
    if (d.name == name) return d;
  }
  std::string known;
  for (const DetectorInfo& d : kDetectors) known += (known.empty() ? "" : ", ") + std::string(d.name);
  throw UnknownDetector("unknown detector \"" + std::string(name) + "\" (known: " + known + ")");
}

Collider detector_collider(std::string_view name, const DetectOptions& options) {
  const DetectorInfo& d = find_detector(name);
  return [&d, options](const ContactQuery& q) { return d.detect(q, options); };
}

}  // namespace boxpile
