// Broadphase: sweep-and-prune on axis-aligned bounding boxes, so that a pile of n bodies tests
// far fewer than n^2 / 2 pairs in the narrowphase.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/step_storage.hpp"

namespace boxpile {

struct Aabb {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
  bool overlaps(const Aabb& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};

// The world bounding box of a body (all its boxes), grown by `margin` on every side.
Aabb body_aabb(const RigidBody& body, double margin);
// The same for boxes already placed in the world (PlacedBoxes::of): the same numbers, without
// composing the body's pose with each shape's again.
Aabb boxes_aabb(std::span<const OrientedBox> boxes, double margin);

// Sweep-and-prune along x. Keeps its sort order between calls, so that with small motions the
// insertion sort is nearly linear (temporal coherence), and reuses its storage: no allocation
// once the first call has sized it.
class SweepAndPrune {
 public:
  // The sweep's order compares lower x bounds rounded to the nearest multiple of this grain (m),
  // ties by body index: bodies at rest, whose bounds move by rounding alone, keep their order from
  // step to step (as do the pairs it yields and their contacts: contact_reuse.hpp), where exact
  // bounds would swap two bodies whose lower x are equal (a stack, a Jenga tower) at random.
  // (Rounded down instead, a bound on a round coordinate such as -0.75 m sat on a cell's edge and
  // its rounding jitter flipped its cell.) The sweep ends a box's scan two grains later to make up
  // for the rounding, so no overlapping pair is missed.
  static constexpr double kOrderGrain = 1e-9;

  // Sizes the storage for `storage.bodies` bodies and their expected pairs.
  void reserve(const StepStorage& storage);
  // The pairs (i < j) of bodies whose boxes overlap, each box grown by its body's margin
  // (margins[i], m), skipping pairs of two fixed bodies.
  const std::vector<std::pair<int, int>>& find_pairs(const std::vector<RigidBody>& bodies,
                                                     const std::vector<double>& margins);
  // The same from bounding boxes the caller has computed (a world that has placed its boxes
  // already), with fixed[i] != 0 for a fixed body. Stops once it holds more than `max_pairs`
  // (max_pairs + 1 returned): a caller that caps the work learns that the cap is exceeded without
  // the memory of every pair (3,000 coincident boxes make 4.5 million).
  const std::vector<std::pair<int, int>>& find_pairs(const std::vector<Aabb>& boxes, const std::vector<char>& fixed,
                                                     std::size_t max_pairs = static_cast<std::size_t>(-1));

 private:
  // Sorts order_ by the boxes' lower x bound in grains and index: insertion sort from the last
  // call's order.
  void sort_by_lower_x(const std::vector<Aabb>& boxes);

  std::vector<Aabb> boxes_;  // the bodies' boxes, for the first overload
  std::vector<char> fixed_;  // the bodies' fixed flags, for the first overload
  std::vector<int> order_;
  // A box's bounds, its body and whether it is fixed, at its place in the sweep's order.
  struct SweptBox {
    double lo_x, hi_x, lo_y, hi_y, lo_z, hi_z;
    int body;
    bool fixed;
  };
  std::vector<SweptBox> swept_;
  std::vector<double> key_;  // per body, its lower x bound in grains, rounded to the nearest
  std::vector<std::pair<int, int>> pairs_;
};

}  // namespace boxpile
