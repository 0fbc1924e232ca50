#include "boxpile/sim/solver/shock_propagation.hpp"

#include <algorithm>

namespace boxpile {

namespace {
// Shock propagation stops iterating a level once no impulse changes a point's velocity by more
// than this (m/s): 1e-9 m/s over the 1,200 steps of 5 s moves a box by 5e-9 m.
constexpr double kShockConverged = 1e-9;
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
}

void ShockPropagation::run(ImpulseStep& step) {
  SolverBodies& sb = step.sb;
  std::vector<SolverContact>& contacts = step.contacts;
  const int passes = step.world.scene.solver.shock_passes;
  const bool friction = step.world.scene.effects.friction;
  const double dt = step.world.dt;
  ImpulseCounters& counters = step.world.counters.impulses;
  StepStats& stats = step.world.stats;
  const int n = static_cast<int>(sb.bodies.size());
  auto level_of = [&](int body) { return body < 0 ? -1 : level_[body]; };

  // Contact graph between movable bodies, as compressed adjacency rows.
  adjacency_start_.assign((n + 1), 0);
  for (const SolverContact& c : contacts)
    if (c.b >= 0) {
      ++adjacency_start_[c.a + 1];
      ++adjacency_start_[c.b + 1];
    }
  for (int i = 0; i < n; ++i) adjacency_start_[i + 1] += adjacency_start_[i];
  adjacency_.resize(adjacency_start_.back());
  queue_.assign(adjacency_start_.begin(), adjacency_start_.end() - 1);  // fill cursors
  for (const SolverContact& c : contacts)
    if (c.b >= 0) {
      adjacency_[queue_[c.a]++] = c.b;
      adjacency_[queue_[c.b]++] = c.a;
    }

  // Levels by breadth-first search: fixed bodies are -1, bodies touching the ground or a fixed
  // body are level 0, their neighbours 1, and so on up the pile.
  level_.assign(n, kUnsupported);
  queue_.clear();
  for (int i = 0; i < n; ++i)
    if (sb.get(i).fixed) level_[i] = -1;
  for (const SolverContact& c : contacts) {
    for (const auto& [body, support] : {std::pair{c.a, c.b}, std::pair{c.b, c.a}}) {
      if (body < 0 || level_of(body) != kUnsupported) continue;
      if (support < 0 || sb.get(support).fixed) {
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

  // Contacts by level: a contact belongs to the higher of its two bodies' levels.
  int top = -1;
  for (int i = 0; i < n; ++i)
    if (level_[i] != kUnsupported) top = std::max(top, level_[i]);
  level_start_.assign((top + 2), 0);
  auto contact_level = [&](const SolverContact& c) { return std::max(level_of(c.a), level_of(c.b)); };
  for (const SolverContact& c : contacts) {
    const int l = contact_level(c);
    if (l >= 0 && l != kUnsupported) ++level_start_[l + 1];
  }
  for (int l = 0; l <= top; ++l) level_start_[l + 1] += level_start_[l];
  by_level_.resize(level_start_.back());
  queue_.assign(level_start_.begin(), level_start_.end() - 1);
  for (int k = 0; k < static_cast<int>(contacts.size()); ++k) {
    const int l = contact_level(contacts[k]);
    if (l >= 0 && l != kUnsupported) by_level_[queue_[l]++] = k;
  }

  // Solve level by level with e = 0; bodies below the level are frozen (infinite mass), so
  // nothing pushes back down the pile and the stack's weight is carried by the ground.
  auto moves = [&](int body, int l) { return body >= 0 && level_of(body) == l; };
  for (int l = 0; l <= top; ++l) {
    for (int k = level_start_[l]; k < level_start_[l + 1]; ++k) {
      SolverContact& c = contacts[by_level_[k]];
      if (!(moves(c.a, l) && moves(c.b, l))) set_collision_matrix(c, moves(c.a, l), moves(c.b, l));
    }
    for (int pass = 0; pass < passes; ++pass) {
      // The largest velocity change an impulse of this pass made, |K dj|: once it is below
      // kShockConverged the level is solved and later passes would change nothing that matters.
      double largest_change = 0.0;
      for (int k = level_start_[l]; k < level_start_[l + 1]; ++k) {
        SolverContact& c = contacts[by_level_[k]];
        const Vec3 j = resting_impulse(c, sb.relative_velocity(c), allow_gap(c, 0.0, dt), friction, counters);
        sb.apply(c, j, moves(c.a, l), moves(c.b, l));
        largest_change = std::max(largest_change, (c.K * j).norm());
      }
      ++stats.shock_passes_used;
      if (largest_change < kShockConverged) break;
    }
  }
  stats.shock_levels = top + 1;
  stats.residual_after_shock = approach_residual(sb, contacts, dt);
}

}  // namespace boxpile
