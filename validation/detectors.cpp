#include "boxpile/validation/detectors.hpp"

#include <array>
#include <string>

#include "boxpile/reference/dart/dart_contacts.hpp"
#include "boxpile/reference/reference_contacts.hpp"
#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"

namespace boxpile {
namespace {

Manifold own_box_box(const OrientedBox& a, const OrientedBox& b, const DetectOptions& options) {
  Manifold m;
  collide_box_box(a, b, options.own, m);
  return m;
}

Manifold own_box_plane(const OrientedBox& a, const HalfSpace& plane, const DetectOptions& options) {
  Manifold m;
  collide_box_plane(a, plane, options.plane_margin, m);
  return m;
}

Manifold ode_pair(const OrientedBox& a, const OrientedBox& b, const DetectOptions&) { return ode_box_box(a, b); }
Manifold ode_plane(const OrientedBox& a, const HalfSpace& p, const DetectOptions&) { return ode_box_plane(a, p); }
Manifold bullet_pair(const OrientedBox& a, const OrientedBox& b, const DetectOptions&) { return bullet_box_box(a, b); }
Manifold bullet_plane(const OrientedBox& a, const HalfSpace& p, const DetectOptions&) { return bullet_box_plane(a, p); }
Manifold dart_pair(const OrientedBox& a, const OrientedBox& b, const DetectOptions&) {
  return dart_box_box(DartDetector::Dart, a, b);
}
Manifold dart_plane(const OrientedBox& a, const HalfSpace& p, const DetectOptions&) {
  return dart_box_plane(DartDetector::Dart, a, p);
}
Manifold fcl_pair(const OrientedBox& a, const OrientedBox& b, const DetectOptions&) {
  return dart_box_box(DartDetector::FclPrimitive, a, b);
}
Manifold fcl_plane(const OrientedBox& a, const HalfSpace& p, const DetectOptions&) {
  return dart_box_plane(DartDetector::FclPrimitive, a, p);
}
Manifold multipoint_plane(const OrientedBox& a, const HalfSpace& p, const DetectOptions&) {
  return bullet_box_plane(a, p, kBulletMultipoint);
}

const std::array<DetectorInfo, 6> kDetectors = {{
    {kOwnDetector, "boxpile's separating-axis test with face clipping", false, &own_box_box, &own_box_plane},
    {"ode", "ODE's dCollide (dBoxBox, box-plane)", false, &ode_pair, &ode_plane},
    {"bullet", "Bullet's btBoxBoxDetector through a persistent manifold", false, &bullet_pair, &bullet_plane},
    {"bullet_multipoint", "Bullet with setPlaneConvexMultipointIterations(3, 3)", true, &bullet_pair,
     &multipoint_plane},
    {"dart", "DART's DARTCollisionDetector (box-box; the ground as a large box)", false, &dart_pair, &dart_plane},
    {"fcl", "FCL 0.7's box primitives through DART's FCLCollisionDetector (the ground as a large box)", false,
     &fcl_pair, &fcl_plane},
}};

}  // namespace

Manifold DetectorInfo::detect(const ContactQuery& q, const DetectOptions& options) const {
  const OrientedBox a = OrientedBox::from(q.a.pose, q.a.half_extents);
  if (q.plane) return box_plane(a, *q.plane, options);
  return box_box(a, OrientedBox::from(q.b->pose, q.b->half_extents), options);
}

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
