#include "boxpile/sim/solver/shock_propagation.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>

#include "boxpile/sim/solver/sticking_solve.hpp"

namespace boxpile {

namespace {
// A pass makes progress when its largest change falls below this fraction of the smallest change
// of the level's earlier passes. A converging level gains a factor of 3 to 30 per pass (the
// Jenga tower, a stack of 10); a cycling one repeats the same change (a Jenga level stuck at
// 4.765e-12 m/s for 55 passes; a falling pile's levels swinging between 2e-2 and 2e-1 m/s).
constexpr double kShockProgress = 0.9;
// A level stops after this many passes in a row without progress: a pass that
// overshoots before converging does not end it.
constexpr int kShockStallPasses = 3;


// What a pass's impulses read besides their contact: the bodies, the contacts, the settings.
struct PassContext {
  SolverBodyArray& sb;
  SolverContact* contacts;
  bool friction;
  bool accumulated;  // projected Gauss-Seidel (ours), or the lab text's push-only impulses
  ImpulseCounters& counters;
  explicit PassContext(ImpulseStep& step)
      : sb(step.resting),
        contacts(step.contacts.data()),
        friction(step.friction()),
        accumulated(step.settings().accumulated_impulses),
        counters(step.counters()) {}
};

// The impulse of one contact of a pass toward `target` (its u_n at e = 0).
[[gnu::always_inline]] inline Vec3 level_impulse(const PassContext& p, SolverContact& c, const Vec3& u, double target) {
  return p.accumulated ? resting_impulse(c, u, target, p.friction, p.counters)
                       : push_impulse(c, u, target, p.friction, p.counters);
}

// One resting impulse of a pass; returns the squared velocity change |K dj|^2 it made.
[[gnu::always_inline]] inline double solve_contact(const PassContext& p, const ShockPropagation::LevelContact& lc) {
  SolverContact& c = p.contacts[lc.index];
  const Vec3 j = level_impulse(p, c, p.sb.relative_velocity(c), lc.target);
  p.sb.apply(c, j, lc.a_moves, lc.b_moves);
  return (c.K * j).squaredNorm();
}

// One pass over a group's contacts; returns the largest velocity change |K dj| an impulse of it
// made: once it is below kRestingConverged the group is solved and later passes would change
// nothing that matters. Always inlined into the passes' loop: a group may be a single box's four
// points.
[[gnu::always_inline]] inline double solve_group_pass(const PassContext& p,
                                                      std::span<const ShockPropagation::LevelContact> group) {
  double largest_change_sq = 0.0;
  for (const ShockPropagation::LevelContact& lc : group) largest_change_sq = std::max(largest_change_sq, solve_contact(p, lc));
  return std::sqrt(largest_change_sq);
}

// The impulses of two contacts that share no moving body: both points' velocities are read before
// either impulse is applied, so that the two computations, each a chain of operations waiting on
// the one before, overlap in the processor. Neither reads what the other writes (a frozen body is
// never written), so the results are those of the two impulses in turn, to the bit. Returns the
// squared changes |K dj|^2.
[[gnu::always_inline]] inline std::pair<double, double> solve_independent_pair(const PassContext& p,
                                                                               const ShockPropagation::LevelContact& first,
                                                                               const ShockPropagation::LevelContact& second) {
  SolverContact& c1 = p.contacts[first.index];
  SolverContact& c2 = p.contacts[second.index];
  const Vec3 u1 = p.sb.relative_velocity(c1);
  const Vec3 u2 = p.sb.relative_velocity(c2);
  const Vec3 j1 = level_impulse(p, c1, u1, first.target);
  const Vec3 j2 = level_impulse(p, c2, u2, second.target);
  p.sb.apply(c1, j1, first.a_moves, first.b_moves);
  p.sb.apply(c2, j2, second.a_moves, second.b_moves);
  return {(c1.K * j1).squaredNorm(), (c2.K * j2).squaredNorm()};
}

// One pass over two groups at once, the k-th contact of one with the k-th of the other. Groups
// share no moving body, so the pairs are independent. Returns each group's largest change.
// Flattened: as calls, the body's velocity and impulse routines cost more than the pairing gained.
[[gnu::flatten]] std::pair<double, double> solve_group_pair_pass(const PassContext& p,
                                                                 std::span<const ShockPropagation::LevelContact> first,
                                                                 std::span<const ShockPropagation::LevelContact> second) {
  const std::size_t common = std::min(first.size(), second.size());
  double first_sq = 0.0, second_sq = 0.0;
  for (std::size_t k = 0; k < common; ++k) {
    const auto [first_change, second_change] = solve_independent_pair(p, first[k], second[k]);
    first_sq = std::max(first_sq, first_change);
    second_sq = std::max(second_sq, second_change);
  }
  for (std::size_t k = common; k < first.size(); ++k) first_sq = std::max(first_sq, solve_contact(p, first[k]));
  for (std::size_t k = common; k < second.size(); ++k) second_sq = std::max(second_sq, solve_contact(p, second[k]));
  return {std::sqrt(first_sq), std::sqrt(second_sq)};
}

}  // namespace

double approach_residual(const SolverBodyArray& sb, std::span<const SolverContact> contacts, double dt) {
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
  group_contacts_.reserve(storage.contacts());
  groups_.reserve(storage.bodies, storage.contacts());
  grouped_.reserve(storage.contacts());
  group_start_.reserve(storage.contacts() + 1);
  level_group_.reserve(storage.bodies + 2);
  own_.active.reserve(storage.bodies);
}

void ShockPropagation::run(ImpulseStep& step, bool same_contacts) {
  prepare(step, same_contacts);
  step.resting.gather(step.sb.bodies);
  solve_island(step, 0, static_cast<int>(step.contacts.size()), own_);
  step.stats().residual_after_shock = approach_residual(step.resting, step.contacts, step.dt());
  step.resting.scatter(step.sb.bodies);
}

void ShockPropagation::prepare(ImpulseStep& step, bool same_contacts) {
  if (!same_contacts) {
    build_graph(step);
    assign_levels(step);
    group_contacts_by_level(step);
    // Every level's groups, from which bodies belong to it alone: its targets, which read the
    // frozen bodies' velocities, are set when the level is solved.
    grouped_.clear();
    group_start_.assign(1, 0);
    level_group_.assign(1, 0);
    for (int l = 0; l <= top_; ++l) group_level(step, l);
  }
  step.stats().shock_levels = top_ + 1;
}

void ShockPropagation::solve_island(ImpulseStep& step, int begin, int end, Worker& worker) {
  // Solve level by level with e = 0; bodies below the level are frozen (infinite mass), so
  // nothing pushes back down the pile and the stack's weight is carried by the ground. A level's
  // groups are ordered by their first contact and lie within one island each, so the island's are
  // one run of them.
  auto first_group_from = [&](int l, int contact) {
    int lo = level_group_[l], hi = level_group_[l + 1];
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (grouped_[group_start_[mid]].index < contact) lo = mid + 1; else hi = mid;
    }
    return lo;
  };
  for (int l = 0; l <= top_; ++l) {
    const int first = first_group_from(l, begin), last = first_group_from(l, end);
    if (first < last) solve_level(step, l, first, last, worker);
  }
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
double ShockPropagation::frozen_target(const SolverBodyArray& sb, const SolverContact& c, int level) const {
  if (moves(c.a, level) && !moves(c.b, level)) return std::min(0.0, -c.n.dot(sb.point_velocity(c.b, c.Wb)));
  if (moves(c.b, level) && !moves(c.a, level)) return std::min(0.0, c.n.dot(sb.point_velocity(c.a, c.Wa)));
  return 0.0;
}

void ShockPropagation::solve_level(ImpulseStep& step, int l, int first, int last, Worker& worker) {
  // A frozen body keeps its velocity through the level, so each contact's target is set once.
  for (int k = group_start_[first]; k < group_start_[last]; ++k) {
    LevelContact& lc = grouped_[k];
    lc.target = allow_gap(step.contacts[lc.index], frozen_target(step.resting, step.contacts[lc.index], l), step.dt());
  }
  solve_groups(step, first, last, worker);
}

void ShockPropagation::solve_groups(ImpulseStep& step, int group_begin, int group_end, Worker& worker) {
  // First the groups whose touching points can all stick, each solved directly; then the passes
  // over the rest. Each pass runs over the groups that have not converged yet: a group leaves
  // once no impulse of a pass changes a point's velocity by more than kRestingConverged (its later
  // passes would change nothing that matters). The island's part of the level ends as a whole
  // level did before it was split: when every group has converged, or when the largest change of a
  // pass stalls (one island's stall does not end another's: islands are solved apart). (Letting a
  // stalled group leave on its own took some 10% more off pyramid_10, but let a tumbling pile's
  // slowly converging groups run on, and the brick wall's penetration went from 0.57 to 4.6 mm.)
  ImpulseStepStats& stats = step.stats();
  const int passes = step.settings().shock_passes;
  const PassContext context(step);
  std::vector<int>& active_ = worker.active;
  const double direct_residual = solve_sticking_groups(step, group_begin, group_end, active_);
  PassProgress level(kShockProgress, kShockStallPasses);
  bool stalled = false;
  int pass = 0;
  while (pass < passes && !active_.empty()) {
    double largest_change = 0.0;
    if (active_.size() == 1) {
      // One group (a sliding box of a stack, a Jenga layer the direct solve declined): without the
      // bookkeeping, which cost 8% of a stack_10 step.
      largest_change = solve_group_pass(context, group(active_[0]));
      if (largest_change < kRestingConverged) active_.clear();
    } else {
      // The active groups two at a time (see solve_group_pair_pass), the last one alone.
      std::size_t kept = 0;
      auto keep = [&](int g, double change) {
        largest_change = std::max(largest_change, change);
        if (change >= kRestingConverged) active_[kept++] = g;
      };
      std::size_t k = 0;
      for (; k + 1 < active_.size(); k += 2) {
        const int first = active_[k], second = active_[k + 1];
        const auto [first_change, second_change] = solve_group_pair_pass(context, group(first), group(second));
        keep(first, first_change);
        keep(second, second_change);
      }
      if (k < active_.size()) keep(active_[k], solve_group_pass(context, group(active_[k])));
      active_.resize(kept);
    }
    stats.shock_change[pass] = std::max(stats.shock_change[pass], largest_change);
    ++pass;
    if (active_.empty()) break;
    if (!level.made(largest_change)) {
      stalled = true;
      break;
    }
  }
  if (direct_residual >= 0.0) {
    // The direct solves count as the level's first pass, their residual as its change.
    stats.shock_change[0] = std::max(stats.shock_change[0], direct_residual);
    pass = std::max(pass, 1);
  }
  stats.shock_pass_count = std::max(stats.shock_pass_count, pass);
  stats.shock_passes_used += pass;
  ++stats.shock_parts;
  if (stalled) ++stats.shock_stalled_levels;
}

double ShockPropagation::solve_sticking_groups(ImpulseStep& step, int group_begin, int group_end,
                                               std::vector<int>& active_) {
  // Each group of bodies on frozen supports solved directly when every touching point can stick
  // (sticking_solve.hpp); the groups it declines stay active for the passes.
  const bool direct = step.settings().sticking_solves;
  double worst = -1.0;
  active_.clear();
  for (int g = group_begin; g < group_end; ++g) {
    if (!direct) {  // every group by passes
      set_frozen_collision_matrices(step, group(g));
      active_.push_back(g);
      continue;
    }
    double residual = 0.0;
    const StickingOutcome outcome =
        solve_sticking_group(step.resting, step.contacts, group(g), step.friction(), step.counters(), residual);
    if (outcome == StickingOutcome::solved) {
      worst = std::max(worst, residual);
    } else {
      set_frozen_collision_matrices(step, group(g));
      active_.push_back(g);
    }
  }
  return worst;
}

void ShockPropagation::set_frozen_collision_matrices(ImpulseStep& step, std::span<const LevelContact> contacts) {
  // Contacts that reach down to a frozen body see only the moving body's share of K. Only the
  // passes read K (the direct solve does not), so they are set only for the groups it declines.
  for (const LevelContact& lc : contacts)
    if (!(lc.a_moves && lc.b_moves)) set_collision_matrix(step.contacts[lc.index], step.matrices[lc.index], lc.a_moves, lc.b_moves);
}

void ShockPropagation::group_level(const ImpulseStep& step, int l) {
  // A contact moves the level's body it touches; one between two of them links their groups.
  level_contacts_.clear();
  for (int k = level_start_[l]; k < level_start_[l + 1]; ++k) {
    const SolverContact& c = step.contacts[by_level_[k]];
    level_contacts_.push_back({by_level_[k], moves(c.a, l), moves(c.b, l), 0.0});
  }
  auto moving = [&](const LevelContact& lc) {
    const SolverContact& c = step.contacts[lc.index];
    return MovingBodies::of(c.a, c.b, lc.a_moves, lc.b_moves);
  };
  groups_.sort(std::span<const LevelContact>(level_contacts_), step.sb.bodies.size(), moving, group_contacts_);
  grouped_.insert(grouped_.end(), group_contacts_.begin(), group_contacts_.end());
  for (int g = 0; g < groups_.count(); ++g)
    group_start_.push_back(group_start_.back() + static_cast<int>(groups_.group(group_contacts_, g).size()));
  level_group_.push_back(static_cast<int>(group_start_.size()) - 1);
}

}  // namespace boxpile
