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

}  // namespace boxpile
