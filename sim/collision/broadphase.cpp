#include "boxpile/sim/collision/broadphase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace boxpile {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Grows `box` to hold `b`. For a box of axes R and half extents h the world half extents are |R| h.
void include(Aabb& box, const OrientedBox& b) {
  const Vec3 extent = b.axes.cwiseAbs() * b.half;
  box.lo = box.lo.cwiseMin(b.center - extent);
  box.hi = box.hi.cwiseMax(b.center + extent);
}

void grow(Aabb& box, double margin) {
  box.lo.array() -= margin;
  box.hi.array() += margin;
}

}  // namespace

Aabb body_aabb(const RigidBody& body, double margin) {
  Aabb box{Vec3::Constant(kInfinity), Vec3::Constant(-kInfinity)};
  for (int k = 0; k < static_cast<int>(body.shapes.size()); ++k)
    include(box, OrientedBox::from(body.shape_pose(k), body.shapes[k].half_extents));
  grow(box, margin);
  return box;
}

Aabb boxes_aabb(std::span<const OrientedBox> boxes, double margin) {
  Aabb box{Vec3::Constant(kInfinity), Vec3::Constant(-kInfinity)};
  for (const OrientedBox& b : boxes) include(box, b);
  grow(box, margin);
  return box;
}

void SweepAndPrune::reserve(const StepStorage& storage) {
  order_.reserve(storage.bodies);
  swept_.reserve(storage.bodies);
  key_.reserve(storage.bodies);
  pairs_.reserve(storage.pairs());
}

const std::vector<std::pair<int, int>>& SweepAndPrune::find_pairs(const std::vector<RigidBody>& bodies,
                                                                  const std::vector<double>& margins) {
  boxes_.resize(bodies.size());
  fixed_.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    boxes_[i] = body_aabb(bodies[i], margins[i]);
    fixed_[i] = bodies[i].fixed;
  }
  return find_pairs(boxes_, fixed_);
}

void SweepAndPrune::sort_by_lower_x(const std::vector<Aabb>& boxes) {
  const int n = static_cast<int>(boxes.size());
  key_.resize(boxes.size());
  for (int i = 0; i < n; ++i) key_[i] = std::round(boxes[i].lo.x() / kOrderGrain);
  // A strict order: the same keys give the same order whatever the last call's was.
  auto before = [&](int a, int b) { return key_[a] < key_[b] || (key_[a] == key_[b] && a < b); };
  if (static_cast<int>(order_.size()) != n) {
    // First call (or the body count changed): a full sort, O(n log n) whatever the scene order.
    order_.resize(boxes.size());
    std::iota(order_.begin(), order_.end(), 0);
    std::sort(order_.begin(), order_.end(), before);
  }
  // Nearly sorted from the last call: each body moves a few places at most.
  for (int i = 1; i < n; ++i) {
    const int moving = order_[i];
    int j = i - 1;
    while (j >= 0 && before(moving, order_[j])) {
      order_[j + 1] = order_[j];
      --j;
    }
    order_[j + 1] = moving;
  }
}

const std::vector<std::pair<int, int>>& SweepAndPrune::find_pairs(const std::vector<Aabb>& boxes,
                                                                  const std::vector<char>& fixed,
                                                                  std::size_t max_pairs) {
  sort_by_lower_x(boxes);
  // The bounds in the sweep's order, one after another: a box's scan reads the boxes after it as
  // one run of memory rather than each at its body's place. In a pile the scan is long (a box of
  // the 9,455-box pyramid meets some 900 boxes that overlap it along x, nearly all of them
  // rejected by y or z), and read through the order it missed the cache at every box.
  const int n = static_cast<int>(boxes.size());
  swept_.resize(boxes.size());
  for (int s = 0; s < n; ++s) {
    const int i = order_[s];
    const Aabb& b = boxes[i];
    swept_[s] = {b.lo.x(), b.hi.x(), b.lo.y(), b.hi.y(), b.lo.z(), b.hi.z(), i, fixed[i] != 0};
  }
  // Sweep: each box meets the boxes that start before it ends along x.
  pairs_.clear();
  for (int s = 0; s < n; ++s) {
    const SweptBox& bi = swept_[s];
    // Sorted by rounded bounds, a later box's lower x is at most a grain below this one's (two,
    // for the rounding of the division).
    const double end_x = bi.hi_x + 2.0 * kOrderGrain;
    for (int t = s + 1; t < n; ++t) {
      const SweptBox& bj = swept_[t];
      if (bj.lo_x > end_x) break;
      // Aabb::overlaps, y and z first: they reject nearly every box the scan meets.
      if (!(bi.lo_y <= bj.hi_y && bj.lo_y <= bi.hi_y && bi.lo_z <= bj.hi_z && bj.lo_z <= bi.hi_z &&
            bi.lo_x <= bj.hi_x && bj.lo_x <= bi.hi_x))
        continue;
      if (bi.fixed && bj.fixed) continue;
      pairs_.emplace_back(std::min(bi.body, bj.body), std::max(bi.body, bj.body));
      if (pairs_.size() > max_pairs) return pairs_;
    }
  }
  return pairs_;
}

}  // namespace boxpile
