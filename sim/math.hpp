// Fixed-size Eigen types used throughout boxpile. Double precision everywhere, SI units, z up.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace boxpile {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// A rigid placement: x_world = position + orientation * x_local.
struct Pose {
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();

  Vec3 apply(const Vec3& local) const { return position + orientation * local; }
  Pose operator*(const Pose& inner) const {
    return {apply(inner.position), (orientation * inner.orientation).normalized()};
  }
};

// [v]x, the matrix with [v]x w = v x w.
inline Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(),
       v.z(), 0, -v.x(),
       -v.y(), v.x(), 0;
  return m;
}

// The inverse of a symmetric 3x3 matrix from its upper triangle: six cofactors where a general
// inverse forms nine, and an exactly symmetric result (m^-T x = m^-1 x to the bit). The matrix must
// be nonsingular; its lower triangle is not read.
inline Mat3 symmetric_inverse(const Mat3& m) {
  const double a = m(0, 0), b = m(0, 1), c = m(0, 2), d = m(1, 1), e = m(1, 2), f = m(2, 2);
  const double c00 = d * f - e * e, c01 = c * e - b * f, c02 = b * e - c * d;
  const double inv_det = 1.0 / (a * c00 + b * c01 + c * c02);
  const double i00 = c00 * inv_det, i01 = c01 * inv_det, i02 = c02 * inv_det;
  const double i11 = (a * f - c * c) * inv_det, i12 = (b * c - a * e) * inv_det, i22 = (a * d - b * b) * inv_det;
  Mat3 inv;
  inv << i00, i01, i02,
         i01, i11, i12,
         i02, i12, i22;
  return inv;
}

}  // namespace boxpile
