// Conversions between Bullet's types and ours, and the reading of a persistent manifold in our
// convention. Internal to boxpile::reference (it includes Bullet's headers; Bullet is built with
// BT_USE_DOUBLE_PRECISION, so btScalar is double and nothing is rounded).
#pragma once

#include <btBulletCollisionCommon.h>

#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile::reference_detail {

inline btVector3 to_bt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 from_bt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
// btQuaternion takes (x, y, z, w).
inline btQuaternion to_bt(const Quat& q) { return {q.x(), q.y(), q.z(), q.w()}; }
inline Quat from_bt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()).normalized(); }
inline btTransform to_bt(const Pose& p) { return btTransform(to_bt(p.orientation), to_bt(p.position)); }
inline btMatrix3x3 to_bt(const Mat3& m) {
  return {m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2)};
}

// One persistent-manifold point in our convention. Bullet's m_normalWorldOnB points from the
// manifold's body 1 toward its body 0 and getDistance() < 0 when penetrating, with
// onA = onB + n * distance; our A may be either body, so `a_is_body0` says which. The position
// is the midpoint of Bullet's two surface points; the feature id holds `kind` only.
inline Contact contact_from_bullet(const btManifoldPoint& p, bool a_is_body0, FeatureKind kind) {
  const Vec3 n = from_bt(p.m_normalWorldOnB);
  const Vec3 mid = 0.5 * (from_bt(p.m_positionWorldOnA) + from_bt(p.m_positionWorldOnB));
  return {mid, a_is_body0 ? n : Vec3(-n), -p.getDistance(), FeatureId::make(kind, 0, 0, 0)};
}

}  // namespace boxpile::reference_detail
