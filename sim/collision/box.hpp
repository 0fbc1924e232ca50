// A box placed in the world, as the narrowphase sees it.
#pragma once

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

struct OrientedBox {
  Vec3 center = Vec3::Zero();
  Mat3 axes = Mat3::Identity();  // columns: the box's unit axes in world coordinates
  Vec3 half = Vec3::Constant(0.5);

  static OrientedBox from(const Pose& pose, const Vec3& half_extents) {
    return {pose.position, pose.orientation.toRotationMatrix(), half_extents};
  }
  // Vertex k (0..7): bit i set means the positive side along axis i.
  Vec3 vertex(int k) const {
    Vec3 local;
    for (int i = 0; i < 3; ++i) local[i] = (k >> i & 1) ? half[i] : -half[i];
    return center + axes * local;
  }
  // Half the box's extent along a unit direction d: sum_i h_i |a_i . d|.
  double radius_along(const Vec3& d) const {
    return half.dot((axes.transpose() * d).cwiseAbs());
  }
};

}  // namespace boxpile
