#include "boxpile/sim/collision/broadphase.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace boxpile {

Aabb body_aabb(const RigidBody& body, double margin) {
  Aabb box{Vec3::Constant(std::numeric_limits<double>::infinity()),
           Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (int k = 0; k < static_cast<int>(body.shapes.size()); ++k) {
    const Pose pose = body.shape_pose(k);
    const Vec3 extent = pose.orientation.toRotationMatrix().cwiseAbs() *
                        body.shapes[k].half_extents;
    box.lo = box.lo.cwiseMin(pose.position - extent);
    box.hi = box.hi.cwiseMax(pose.position + extent);
  }
  box.lo.array() -= margin;
  box.hi.array() += margin;
  return box;
}

void SweepAndPrune::reserve(const StepStorage& storage) {
  boxes_.reserve(storage.bodies);
  order_.reserve(storage.bodies);
  pairs_.reserve(storage.pairs());
}

const std::vector<std::pair<int, int>>& SweepAndPrune::find_pairs(const std::vector<RigidBody>& bodies,
                                                                  const std::vector<double>& margins) {
  const int n = static_cast<int>(bodies.size());
  boxes_.resize(bodies.size());
  for (int i = 0; i < n; ++i) boxes_[i] = body_aabb(bodies[i], margins[i]);
  auto lo_x = [&](int i) { return boxes_[i].lo.x(); };
  if (static_cast<int>(order_.size()) != n) {
    // First call (or the body count changed): a full sort, O(n log n) whatever the scene order.
    order_.resize(bodies.size());
    std::iota(order_.begin(), order_.end(), 0);
    std::sort(order_.begin(), order_.end(), [&](int a, int b) { return lo_x(a) < lo_x(b); });
  }

  // Insertion sort by the lower x bound: nearly sorted from the last step.
  for (int i = 1; i < n; ++i) {
    const int moving = order_[i];
    int j = i - 1;
    while (j >= 0 && lo_x(order_[j]) > lo_x(moving)) {
      order_[j + 1] = order_[j];
      --j;
    }
    order_[j + 1] = moving;
  }

  // Sweep: each box meets the boxes that start before it ends along x.
  pairs_.clear();
  for (int s = 0; s < n; ++s) {
    const int i = order_[s];
    const Aabb& bi = boxes_[i];
    for (int t = s + 1; t < n; ++t) {
      const int j = order_[t];
      const Aabb& bj = boxes_[j];
      if (bj.lo.x() > bi.hi.x()) break;
      if (bodies[i].fixed && bodies[j].fixed) continue;
      if (bi.overlaps(bj)) pairs_.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  return pairs_;
}

}  // namespace boxpile
