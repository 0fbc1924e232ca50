#include "boxpile/sim/solver/shock_propagation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace boxpile {

namespace {
// A pass makes progress when its largest change falls below this fraction of the smallest change
// of the level's earlier passes. A converging level gains a factor of 3 to 30 per pass (the
// Jenga tower, a stack of 10); a cycling one repeats the same change (a Jenga level stuck at
// 4.765e-12 m/s for 55 passes; a falling pile's levels swinging between 2e-2 and 2e-1 m/s).
constexpr double kShockProgress = 0.9;
// A level stops after this many passes in a row without progress: a pass that overshoots
// before converging does not end it.
constexpr int kShockStallPasses = 3;
}  // namespace

double approach_residual(const SolverBodies& sb, const std::vector<SolverContact>& contacts, double dt) {
  double worst = 0.0;
  for (const SolverContact& c : contacts)
    worst = std::max(worst, allow_gap(c, 0.0, dt) - c.n.dot(sb.relative_velocity(c)));
  return worst;
}

void ShockPropagation::reserve(const StepStorage& storage) {
  // Per body (levels and the queue hold at most one entry per body, plus the level ends), and
  // per contact (each contact between two bodies is two adjacency entries).
  level_.reserve(storage.bodies);
  queue_.reserve(storage.bodies + 1);
  adjacency_start_.reserve(storage.bodies + 1);
  level_start_.reserve(storage.bodies + 2);
  adjacency_.reserve(2 * storage.contacts());
  by_level_.reserve(storage.contacts());
  level_contacts_.reserve(storage.contacts());
}

void ShockPropagation::run(ImpulseStep& step) {
  build_graph(step);
  assign_levels(step);
  group_contacts_by_level(step);
  // Solve level by level with e = 0; bodies below the level are frozen (infinite mass), so
  // nothing pushes back down the pile and the stack's weight is carried by the ground.
  for (int l = 0; l <= top_; ++l) solve_level(step, l);
  step.stats().shock_levels = top_ + 1;
  step.stats().residual_after_shock = approach_residual(step.sb, step.contacts, step.dt());
}

void ShockPropagation::build_graph(const ImpulseStep& step) {
  // Contact graph between movable bodies, as compressed adjacency rows.
  const int n = static_cast<int>(step.sb.bodies.size());
  adjacency_start_.assign((n + 1), 0);
  for (const SolverContact& c : step.contacts)
    if (c.b >= 0) {
      ++adjacency_start_[c.a + 1];
      ++adjacency_start_[c.b + 1];
    }
  for (int i = 0; i < n; ++i) adjacency_start_[i + 1] += adjacency_start_[i];
  adjacency_.resize(adjacency_start_.back());
  queue_.assign(adjacency_start_.begin(), adjacency_start_.end() - 1);  // fill cursors
  for (const SolverContact& c : step.contacts)
    if (c.b >= 0) {
      adjacency_[queue_[c.a]++] = c.b;
      adjacency_[queue_[c.b]++] = c.a;
    }
}

void ShockPropagation::assign_levels(const ImpulseStep& step) {
  // Levels by breadth-first search: fixed bodies are -1, bodies touching the ground or a fixed
  // body are level 0, their neighbours 1, and so on up the pile.
  const int n = static_cast<int>(step.sb.bodies.size());
  level_.assign(n, kUnsupported);
  queue_.clear();
  for (int i = 0; i < n; ++i)
    if (step.sb.get(i).fixed) level_[i] = -1;
  for (const SolverContact& c : step.contacts) {
    for (const auto& [body, support] : {std::pair{c.a, c.b}, std::pair{c.b, c.a}}) {
      if (body < 0 || level_of(body) != kUnsupported) continue;
      if (support < 0 || step.sb.get(support).fixed) {
        level_[body] = 0;
        queue_.push_back(body);
      }
    }
  }
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const int body = queue_[head];
    for (int k = adjacency_start_[body]; k < adjacency_start_[body + 1]; ++k) {
      const int next = adjacency_[k];
      if (level_of(next) != kUnsupported) continue;
      level_[next] = level_of(body) + 1;
      queue_.push_back(next);
    }
  }
  top_ = -1;
  for (int i = 0; i < n; ++i)
    if (level_[i] != kUnsupported) top_ = std::max(top_, level_[i]);
}

void ShockPropagation::group_contacts_by_level(const ImpulseStep& step) {
  // A contact belongs to the higher of its two bodies' levels.
  auto solved = [](int l) { return l >= 0 && l != kUnsupported; };
  level_start_.assign((top_ + 2), 0);
  for (const SolverContact& c : step.contacts)
    if (const int l = contact_level(c); solved(l)) ++level_start_[l + 1];
  for (int l = 0; l <= top_; ++l) level_start_[l + 1] += level_start_[l];
  by_level_.resize(level_start_.back());
  queue_.assign(level_start_.begin(), level_start_.end() - 1);
  for (int k = 0; k < static_cast<int>(step.contacts.size()); ++k)
    if (const int l = contact_level(step.contacts[k]); solved(l)) by_level_[queue_[l]++] = k;
}

// A frozen body is immovable, not at rest: if it still moves toward the level's body, asking
// for u_n >= 0 would launch that body at the frozen one's speed, with energy nothing paid for
// (a ram at 15 m/s carried the bricks it touched along at 15 m/s). The level's body is only
// stopped: its own normal velocity must not fall below min(0, the frozen point's), so the
// target for the relative u_n is min(0, -w) with w the frozen point's velocity along the
// direction from it to the moving body.
double ShockPropagation::frozen_target(const SolverBodies& sb, const SolverContact& c, int level) const {
  if (moves(c.a, level) && !moves(c.b, level)) {
    const RigidBody& b = sb.get(c.b);
    return std::min(0.0, -c.n.dot(b.v + b.omega.cross(c.rb)));
  }
  if (moves(c.b, level) && !moves(c.a, level)) {
    const RigidBody& a = sb.get(c.a);
    return std::min(0.0, c.n.dot(a.v + a.omega.cross(c.ra)));
  }
  return 0.0;
}

void ShockPropagation::solve_level(ImpulseStep& step, int l) {
  SolverBodies& sb = step.sb;
  StepStats& stats = step.stats();
  // Contacts that reach down to a frozen body see only the moving body's share of K. A frozen
  // body keeps its velocity through the level, so each contact's target is set once.
  level_contacts_.clear();
  for (int k = level_start_[l]; k < level_start_[l + 1]; ++k) {
    SolverContact& c = step.contacts[by_level_[k]];
    const bool a_moves = moves(c.a, l), b_moves = moves(c.b, l);
    if (!(a_moves && b_moves)) set_collision_matrix(c, a_moves, b_moves);
    level_contacts_.push_back({by_level_[k], a_moves, b_moves, allow_gap(c, frozen_target(sb, c, l), step.dt())});
  }
  const int passes = step.settings().shock_passes;
  // The smallest change a pass of this level has made so far, and the passes since it fell.
  double lowest_change = std::numeric_limits<double>::infinity();
  int passes_without_progress = 0;
  for (int pass = 0; pass < passes; ++pass) {
    // The largest velocity change an impulse of this pass made, |K dj|: once it is below
    // kRestingConverged the level is solved and later passes would change nothing that matters.
    double largest_change_sq = 0.0;
    for (const LevelContact& lc : level_contacts_) {
      SolverContact& c = step.contacts[lc.index];
      const Vec3 j = resting_impulse(c, sb.relative_velocity(c), lc.target, step.friction(), step.counters());
      sb.apply(c, j, lc.a_moves, lc.b_moves);
      largest_change_sq = std::max(largest_change_sq, (c.K * j).squaredNorm());
    }
    const double largest_change = std::sqrt(largest_change_sq);
    ++stats.shock_passes_used;
    stats.shock_change[pass] = std::max(stats.shock_change[pass], largest_change);
    stats.shock_pass_count = std::max(stats.shock_pass_count, pass + 1);
    if (largest_change < kRestingConverged) break;
    // A level that has stopped converging is cycling: more passes would repeat the same changes.
    if (largest_change < kShockProgress * lowest_change) {
      lowest_change = largest_change;
      passes_without_progress = 0;
    } else if (++passes_without_progress >= kShockStallPasses) {
      ++stats.shock_stalled_levels;
      break;
    }
  }
}

}  // namespace boxpile
