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
//
// A large scene is swept cell by cell: a grid over y and z (cells some twice a box's mean size)
// holds each box in every cell it overlaps, and each cell is swept along x on its own, so that a
// box meets the boxes of its own cells along x rather than every box of its slice of the scene
// (in the 9,455-box pyramid some 900, nearly all rejected by y or z). A pair is kept in one cell
// only, the one holding the corner where the two boxes' overlap begins (the larger lower y, the
// larger lower z), and the pairs are then put back in the order of the plain sweep: sorted by
// the first box's place in the sweep's order, then the second's. Both searches give the same
// pairs in the same order, and with them the same contacts and the same solver results.
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
  // From this many bodies on, `Search::automatic` sweeps cell by cell (below it the plain sweep
  // meets few boxes, and the grid would cost more than it saves).
  static constexpr int kCellsFrom = 256;

  // How the pairs are searched: the same pairs, in the same order, whichever is chosen.
  enum class Search {
    automatic,  // by cells from kCellsFrom bodies on, else the plain sweep
    sweep,      // one sweep along x over every box
    cells,      // one sweep along x per cell of the y-z grid (one cell when the boxes fit one)
  };

  explicit SweepAndPrune(Search search = Search::automatic) : search_(search) {}

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
  // The cells the last call swept (1: the plain sweep).
  int cells() const { return cells_; }

 private:
  // A box's bounds and its place in the sweep's order (`at`), with its body and whether it is
  // fixed.
  struct SweptBox {
    double lo_x, hi_x, lo_y, hi_y, lo_z, hi_z;
    int body;
    int at;
    bool fixed;
  };
  // The y-z grid: cells of `width` (y, z) from `origin`, `ny` by `nz` of them.
  struct Grid {
    double origin_y = 0, origin_z = 0, inverse_width_y = 0, inverse_width_z = 0;
    int ny = 1, nz = 1;
    int cell_y(double y) const;
    int cell_z(double z) const;
  };

  // Sorts order_ by the boxes' lower x bound in grains and index: insertion sort from the last
  // call's order.
  void sort_by_lower_x(const std::vector<Aabb>& boxes);
  // The plain sweep over swept_, its pairs straight into pairs_.
  void sweep_all(std::size_t max_pairs);
  // Chooses the grid for swept_: false if one cell would hold nearly everything (then the plain
  // sweep is as good) or the bounds are not finite.
  bool choose_grid();
  // The sweep cell by cell; false if it stopped at more than `max_pairs` (pairs_ then holds
  // max_pairs + 1 of them, in no particular order).
  bool sweep_cells(std::size_t max_pairs);

  Search search_;
  std::vector<Aabb> boxes_;  // the bodies' boxes, for the first overload
  std::vector<char> fixed_;  // the bodies' fixed flags, for the first overload
  std::vector<int> order_;
  std::vector<SweptBox> swept_;  // the boxes in the sweep's order
  std::vector<double> key_;      // per body, its lower x bound in grains, rounded to the nearest
  Grid grid_;
  int cells_ = 1;
  std::vector<int> cell_start_;        // per cell, where its boxes begin in cell_boxes_ (one more at the end)
  std::vector<SweptBox> cell_boxes_;   // each cell's boxes in the sweep's order, cell after cell
  std::vector<std::pair<int, int>> found_;  // the cells' pairs as places in the sweep's order
  std::vector<int> first_start_;       // per place in the sweep's order, where its pairs begin in seconds_
  std::vector<int> seconds_;           // the second places of the pairs, grouped by the first
  std::vector<std::pair<int, int>> pairs_;
};

}  // namespace boxpile
