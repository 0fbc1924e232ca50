#include "boxpile/sim/collision/broadphase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace boxpile {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The grid's cells are this many times a box's mean extent along y and z: a box of mean size then
// overlaps 1.5 cells each way on average.
constexpr double kCellPerExtent = 2.0;
// At most this many entries per box in all the cells (a few large boxes can span many cells):
// above it the cells are made twice as wide.
constexpr std::size_t kMaxEntriesPerBox = 4;

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
  // The grid has at most a cell per body and holds at most kMaxEntriesPerBox entries per body
  // (choose_grid), so these never grow.
  cell_start_.reserve(storage.bodies + 1);
  cell_boxes_.reserve(kMaxEntriesPerBox * storage.bodies);
  first_start_.reserve(storage.bodies + 1);
  found_.reserve(storage.pairs());
  seconds_.reserve(storage.pairs());
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

int SweepAndPrune::Grid::cell_y(double y) const {
  return static_cast<int>(std::clamp(std::floor((y - origin_y) * inverse_width_y), 0.0, ny - 1.0));
}

int SweepAndPrune::Grid::cell_z(double z) const {
  return static_cast<int>(std::clamp(std::floor((z - origin_z) * inverse_width_z), 0.0, nz - 1.0));
}

const std::vector<std::pair<int, int>>& SweepAndPrune::find_pairs(const std::vector<Aabb>& boxes,
                                                                  const std::vector<char>& fixed,
                                                                  std::size_t max_pairs) {
  sort_by_lower_x(boxes);
  // The bounds in the sweep's order, one after another: a box's scan reads the boxes after it as
  // one run of memory rather than each at its body's place.
  const int n = static_cast<int>(boxes.size());
  swept_.resize(boxes.size());
  for (int s = 0; s < n; ++s) {
    const int i = order_[s];
    const Aabb& b = boxes[i];
    swept_[s] = {b.lo.x(), b.hi.x(), b.lo.y(), b.hi.y(), b.lo.z(), b.hi.z(), i, s, fixed[i] != 0};
  }
  pairs_.clear();
  const bool by_cells = search_ == Search::cells || (search_ == Search::automatic && n >= kCellsFrom);
  cells_ = 1;
  if (by_cells && choose_grid()) {
    cells_ = grid_.ny * grid_.nz;
    sweep_cells(max_pairs);
  } else {
    sweep_all(max_pairs);
  }
  return pairs_;
}

void SweepAndPrune::sweep_all(std::size_t max_pairs) {
  // Each box meets the boxes that start before it ends along x.
  const int n = static_cast<int>(swept_.size());
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
      if (pairs_.size() > max_pairs) return;
    }
  }
}

bool SweepAndPrune::choose_grid() {
  const std::size_t n = swept_.size();
  if (n == 0) return false;
  double lo_y = kInfinity, hi_y = -kInfinity, lo_z = kInfinity, hi_z = -kInfinity;
  double sum_y = 0.0, sum_z = 0.0;
  for (const SweptBox& b : swept_) {
    lo_y = std::min(lo_y, b.lo_y);
    hi_y = std::max(hi_y, b.hi_y);
    lo_z = std::min(lo_z, b.lo_z);
    hi_z = std::max(hi_z, b.hi_z);
    sum_y += b.hi_y - b.lo_y;
    sum_z += b.hi_z - b.lo_z;
  }
  if (!std::isfinite(hi_y - lo_y) || !std::isfinite(hi_z - lo_z) || !std::isfinite(sum_y + sum_z)) return false;
  const double span_y = hi_y - lo_y, span_z = hi_z - lo_z;
  // Cells of some twice a box's mean size (never narrower than a millionth of the scene), and at
  // most one cell per box.
  double width_y = std::max(kCellPerExtent * sum_y / static_cast<double>(n), 1e-6 * span_y);
  double width_z = std::max(kCellPerExtent * sum_z / static_cast<double>(n), 1e-6 * span_z);
  if (!(width_y > 0.0) || !(width_z > 0.0)) return false;
  auto cells_along = [](double span, double width) { return std::max(1.0, std::ceil(span / width)); };
  while (cells_along(span_y, width_y) * cells_along(span_z, width_z) > static_cast<double>(n)) {
    width_y *= 2.0;
    width_z *= 2.0;
  }
  for (;;) {
    grid_ = {lo_y, lo_z, 1.0 / width_y, 1.0 / width_z, static_cast<int>(cells_along(span_y, width_y)),
             static_cast<int>(cells_along(span_z, width_z))};
    if (grid_.ny * grid_.nz == 1) return false;  // one cell: the plain sweep
    std::size_t entries = 0;
    for (const SweptBox& b : swept_)
      entries += static_cast<std::size_t>(grid_.cell_y(b.hi_y) - grid_.cell_y(b.lo_y) + 1) *
                 static_cast<std::size_t>(grid_.cell_z(b.hi_z) - grid_.cell_z(b.lo_z) + 1);
    if (entries <= kMaxEntriesPerBox * n) return true;
    width_y *= 2.0;
    width_z *= 2.0;
  }
}

bool SweepAndPrune::sweep_cells(std::size_t max_pairs) {
  const Grid& g = grid_;
  const int cells = g.ny * g.nz;
  // Each cell's boxes in the sweep's order: counted, then placed (a counting sort by cell, stable).
  cell_start_.assign(static_cast<std::size_t>(cells) + 1, 0);
  auto for_each_cell = [&](const SweptBox& b, auto&& visit) {
    const int y0 = g.cell_y(b.lo_y), y1 = g.cell_y(b.hi_y), z0 = g.cell_z(b.lo_z), z1 = g.cell_z(b.hi_z);
    for (int z = z0; z <= z1; ++z)
      for (int y = y0; y <= y1; ++y) visit(z * g.ny + y);
  };
  for (const SweptBox& b : swept_) for_each_cell(b, [&](int c) { ++cell_start_[c + 1]; });
  for (int c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_boxes_.resize(static_cast<std::size_t>(cell_start_[cells]));
  for (const SweptBox& b : swept_) for_each_cell(b, [&](int c) { cell_boxes_[cell_start_[c]++] = b; });
  for (int c = cells; c > 0; --c) cell_start_[c] = cell_start_[c - 1];  // back to each cell's start
  cell_start_[0] = 0;

  // Each cell swept as the whole scene is, keeping a pair only in the cell where its overlap
  // begins: the larger of the two lower bounds lies in both boxes, along y and along z, so both
  // are in that cell, and in no other cell is the pair kept.
  found_.clear();
  for (int c = 0; c < cells; ++c) {
    const int cy = c % g.ny, cz = c / g.ny;
    const int end = cell_start_[c + 1];
    for (int a = cell_start_[c]; a < end; ++a) {
      const SweptBox& bi = cell_boxes_[a];
      const double end_x = bi.hi_x + 2.0 * kOrderGrain;  // as the plain sweep's
      for (int b = a + 1; b < end; ++b) {
        const SweptBox& bj = cell_boxes_[b];
        if (bj.lo_x > end_x) break;
        if (!(bi.lo_y <= bj.hi_y && bj.lo_y <= bi.hi_y && bi.lo_z <= bj.hi_z && bj.lo_z <= bi.hi_z &&
              bi.lo_x <= bj.hi_x && bj.lo_x <= bi.hi_x))
          continue;
        if (bi.fixed && bj.fixed) continue;
        if (g.cell_y(std::max(bi.lo_y, bj.lo_y)) != cy || g.cell_z(std::max(bi.lo_z, bj.lo_z)) != cz) continue;
        found_.emplace_back(bi.at, bj.at);
        if (found_.size() > max_pairs) {
          for (const auto& [s, t] : found_)
            pairs_.emplace_back(std::min(swept_[s].body, swept_[t].body), std::max(swept_[s].body, swept_[t].body));
          return false;
        }
      }
    }
  }

  // Back to the plain sweep's order: by the first box's place, then the second's (a counting sort
  // by the first, then each box's few partners sorted).
  const int n = static_cast<int>(swept_.size());
  first_start_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& pair : found_) ++first_start_[pair.first + 1];
  for (int s = 0; s < n; ++s) first_start_[s + 1] += first_start_[s];
  seconds_.resize(found_.size());
  for (const auto& [s, t] : found_) seconds_[first_start_[s]++] = t;
  for (int s = n; s > 0; --s) first_start_[s] = first_start_[s - 1];
  first_start_[0] = 0;
  for (int s = 0; s < n; ++s) {
    const auto begin = seconds_.begin() + first_start_[s], end = seconds_.begin() + first_start_[s + 1];
    std::sort(begin, end);
    const int i = swept_[s].body;
    for (auto t = begin; t != end; ++t) {
      const int j = swept_[*t].body;
      pairs_.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  return true;
}

}  // namespace boxpile
