// What every use of ODE in boxpile shares: one-time initialisation, the message handler that
// counts ODE's messages instead of printing them, and conversions between ODE's arrays and ours.
// Internal to boxpile::reference (it includes ODE's headers).
#pragma once

#include <ode/ode.h>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile::reference_detail {

// Calls dInitODE2 once per process and installs the counting message handler. Every function
// that touches ODE calls this first: ODE aborts if used before initialisation.
void ensure_ode_initialised();

inline Vec3 from_ode(const dReal* v) { return {v[0], v[1], v[2]}; }

// ODE's dMatrix3 is 3 rows of 4 (the fourth unused): element (i, j) is R[4 i + j].
inline Mat3 matrix_from_ode(const dReal* R) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = R[4 * i + j];
  return m;
}
inline void matrix_to_ode(const Mat3& m, dMatrix3 R) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R[4 * i + j] = m(i, j);
    R[4 * i + 3] = 0.0;
  }
}
// ODE quaternions are (w, x, y, z), as in our JSON.
inline void quat_to_ode(const Quat& q, dQuaternion out) {
  out[0] = q.w();
  out[1] = q.x();
  out[2] = q.y();
  out[3] = q.z();
}
inline Quat quat_from_ode(const dReal* q) { return Quat(q[0], q[1], q[2], q[3]).normalized(); }

// The placed box of a box geom, read back from ODE.
OrientedBox box_of_geom(dGeomID geom);

// dCollide(A, B) results for two boxes, in our convention: ODE's normal already points toward
// o1 = A; face points move from the incident face to the midpoint, edge-edge points are
// midpoints already. The kind comes from the normal (see box_box_kind).
Contact ode_box_box_contact(const OrientedBox& a, const OrientedBox& b, const dContactGeom& g);

// dCollide(box, plane) results: ODE reports the box vertex below the plane; the midpoint lies
// depth/2 above it along the plane normal.
Contact ode_box_plane_contact(const dContactGeom& g);

}  // namespace boxpile::reference_detail
