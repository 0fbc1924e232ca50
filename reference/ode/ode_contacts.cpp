#include "boxpile/reference/ode/ode_contacts.hpp"

#include "boxpile/reference/convention.hpp"
#include "boxpile/reference/ode/ode_support.hpp"

namespace boxpile {

using namespace reference_detail;

namespace {

// Geoms outside any space, created once and placed per query.
struct OdeQueryGeoms {
  OdeQueryGeoms() {
    ensure_ode_initialised();
    box_a = dCreateBox(nullptr, 1, 1, 1);
    box_b = dCreateBox(nullptr, 1, 1, 1);
    plane = dCreatePlane(nullptr, 0, 0, 1, 0);
  }
  ~OdeQueryGeoms() {
    dGeomDestroy(box_a);
    dGeomDestroy(box_b);
    dGeomDestroy(plane);
  }
  OdeQueryGeoms(const OdeQueryGeoms&) = delete;
  OdeQueryGeoms& operator=(const OdeQueryGeoms&) = delete;

  dGeomID box_a, box_b, plane;
};

OdeQueryGeoms& ode_geoms() {
  thread_local OdeQueryGeoms geoms;
  return geoms;
}

void place(dGeomID geom, const OrientedBox& box) {
  const Vec3 size = 2.0 * box.half;
  dGeomBoxSetLengths(geom, size.x(), size.y(), size.z());
  dGeomSetPosition(geom, box.center.x(), box.center.y(), box.center.z());
  dMatrix3 R;
  matrix_to_ode(box.axes, R);
  dGeomSetRotation(geom, R);
}

}  // namespace

Manifold ode_box_box(const OrientedBox& a, const OrientedBox& b) {
  OdeQueryGeoms& g = ode_geoms();
  place(g.box_a, a);
  place(g.box_b, b);
  dContactGeom raw[kMaxManifoldPoints];
  const int n = dCollide(g.box_a, g.box_b, kMaxManifoldPoints, raw, sizeof(dContactGeom));
  Manifold out;
  for (int i = 0; i < n; ++i) out.push_back(ode_box_box_contact(a, b, raw[i]));
  return out;
}

Manifold ode_box_plane(const OrientedBox& a, const HalfSpace& plane) {
  OdeQueryGeoms& g = ode_geoms();
  place(g.box_a, a);
  dGeomPlaneSetParams(g.plane, plane.normal.x(), plane.normal.y(), plane.normal.z(), plane.offset);
  dContactGeom raw[kMaxManifoldPoints];
  const int n = dCollide(g.box_a, g.plane, kMaxManifoldPoints, raw, sizeof(dContactGeom));
  Manifold out;
  for (int i = 0; i < n; ++i) out.push_back(ode_box_plane_contact(raw[i]));
  return out;
}

}  // namespace boxpile
