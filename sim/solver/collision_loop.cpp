#include "boxpile/sim/solver/collision_loop.hpp"

#include <algorithm>
#include <cassert>
#include <span>

#include "boxpile/sim/solver/pair_impulse.hpp"

namespace boxpile {

namespace {
// A touching point approaching slower than this (m/s) is not a collision but rounding left by the
// previous step's resting phases (they converge to 1e-9 m/s); the contact loop takes it. Far
// below the g dt = 0.04 m/s a resting contact gains per step, so no impact is missed.
constexpr double kCollisionSpeedMin = 1e-6;

// One event per pair and step with an approach faster than `event_speed` before the loop's first
// impulse (later passes see a body already turned by other points' impulses), with the pair's
// summed impulse. Contacts of a pair are consecutive.
void record_events(std::span<const SolverContact> contacts, double time, double event_speed,
                   std::vector<CollisionEvent>& events) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const SolverContact& c = contacts[k];
    const double approach = -c.start_un;
    if (c.collision_impulse <= 0.0 || approach <= event_speed) continue;
    const bool same_pair = k > 0 && !events.empty() && contacts[k - 1].a == c.a && contacts[k - 1].b == c.b &&
                           events.back().body_a == c.a && events.back().body_b == c.b && events.back().time == time;
    if (!same_pair) events.push_back({time, c.a, c.b, 0.0, 0.0});
    events.back().impulse += c.collision_impulse;
    events.back().approach_speed = std::max(events.back().approach_speed, approach);
  }
}

// The lab text's pass: each active point in turn takes the Newton-Coulomb impulse of its present
// approach (push-only), the bodies' velocities updated at once. Returns whether a point was active.
bool sequential_pass(SolverBodies& sb, std::span<SolverContact> contacts, bool restitution, bool friction,
                     double dt, ImpulseCounters& counters) {
  bool any_active = false;
  for (SolverContact& c : contacts) {
    if (!c.active) continue;
    any_active = true;
    const Vec3 u = sb.relative_velocity(c);
    if (c.n.dot(u) >= allow_gap(c, 0.0, dt)) continue;  // not approaching (or closing no gap in the step)
    const Vec3 j = newton_coulomb_impulse(c, u, restitution ? c.restitution : 0.0, friction, counters);
    sb.apply(c, j, true, true);
    c.collision_impulse += j.dot(c.n);
  }
  return any_active;
}

// Our pass: each pair's points solved together (pair_impulse.hpp), so that a face landing flat
// stays flat. The points of one pair are consecutive in the contact set.
bool pair_pass(SolverBodies& sb, std::span<SolverContact> contacts, bool restitution, bool friction,
               ImpulseCounters& counters) {
  bool any_active = false;
  for (std::size_t first = 0; first < contacts.size();) {
    std::size_t last = first + 1;
    while (last < contacts.size() && contacts[last].a == contacts[first].a && contacts[last].b == contacts[first].b)
      ++last;
    const std::span<SolverContact> pair(contacts.data() + first, last - first);
    if (std::any_of(pair.begin(), pair.end(), [](const SolverContact& c) { return c.active; })) {
      any_active = true;
      pair_collision_impulses(sb, pair, restitution, friction, counters);
    }
    first = last;
  }
  return any_active;
}

}  // namespace

void collision_loop(ImpulseStep& step, std::span<SolverContact> contacts) {
  SolverBodies& sb = step.sb;
  const Scene& scene = step.world.scene;
  const int passes = scene.solver.collision_passes;
  const bool restitution = scene.effects.restitution;
  const bool friction = scene.effects.friction;
  const double dt = step.world.dt;
  ImpulseCounters& counters = step.counters();
  ImpulseStepStats& stats = step.stats();
  assert(passes <= kMaxSolverPasses);
  const bool together = scene.solver.pair_impulses;
  // A point still apart collides in this step only if it would close its gap within the step;
  // decided once, before any impulse, so that the points of one face landing together all take
  // part even after the first of them has slowed the body. The lab text's loop starts from every
  // point and lets each pass's impulses decide (a point that does not approach takes none).
  bool any_starts_active = false;
  for (SolverContact& c : contacts) {
    c.start_un = c.n.dot(sb.relative_velocity(c));
    c.active = together ? c.start_un < std::min(allow_gap(c, 0.0, dt), -kCollisionSpeedMin)
                        : c.start_un < allow_gap(c, 0.0, dt) || c.depth >= 0.0;
    c.collision_impulse = 0.0;
    any_starts_active = any_starts_active || c.active;
  }
  // An island at rest has no active point: its passes would only scan for one. (Nor are its
  // events looked for: record_collision_events is skipped when no island ran a pass.)
  if (!any_starts_active) return;
  for (int pass = 0; pass < passes; ++pass) {
    const bool any_active = together ? pair_pass(sb, contacts, restitution, friction, counters)
                                     : sequential_pass(sb, contacts, restitution, friction, dt, counters);
    if (!any_active) break;
    // Drop the contacts that now separate: they take no part in the coming passes. The largest
    // approach among those kept is the pass's residual.
    double residual = 0.0;
    for (SolverContact& c : contacts) {
      if (!c.active) continue;
      const double approach = -c.n.dot(sb.relative_velocity(c));
      if (approach <= 0.0) c.active = false;
      residual = std::max(residual, approach);
    }
    // Islands run apart: the step's residual after a pass is the largest of theirs.
    stats.collision_residual[pass] = std::max(stats.collision_residual[pass], residual);
    stats.collision_passes_used = std::max(stats.collision_passes_used, pass + 1);
  }
}

void record_collision_events(ImpulseStep& step) {
  const double dt = step.world.dt;
  record_events(step.contacts, step.world.time, collision_event_speed(step.world.scene, dt), step.world.events);
}

}  // namespace boxpile
