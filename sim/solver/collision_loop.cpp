#include "boxpile/sim/solver/collision_loop.hpp"

#include <algorithm>
#include <cassert>

namespace boxpile {

void collision_loop(ImpulseStep& step) {
  SolverBodies& sb = step.sb;
  std::vector<SolverContact>& contacts = step.contacts;
  const Scene& scene = step.world.scene;
  const int passes = scene.solver.collision_passes;
  const bool restitution = scene.effects.restitution;
  const bool friction = scene.effects.friction;
  const double time = step.world.time;
  const double dt = step.world.dt;
  const double event_speed = collision_event_speed(scene, dt);
  ImpulseCounters& counters = step.world.counters.impulses;
  StepStats& stats = step.world.stats;
  std::vector<CollisionEvent>& events = step.world.events;
  assert(passes <= kMaxSolverPasses);
  const std::size_t first_event = events.size();
  // A point still apart collides in this step only if it would close its gap within the step;
  // decided once, before any impulse, so that the points of one face landing together all take
  // part even after the first of them has slowed the body.
  for (SolverContact& c : contacts) {
    c.start_un = c.n.dot(sb.relative_velocity(c));
    c.active = c.start_un < allow_gap(c, 0.0, dt);
  }
  for (int pass = 0; pass < passes; ++pass) {
    bool any_active = false;
    for (SolverContact& c : contacts) {
      if (!c.active) continue;
      any_active = true;
      const Vec3 u = sb.relative_velocity(c);
      if (c.n.dot(u) >= 0.0) continue;
      const double e = restitution ? c.restitution : 0.0;
      const Vec3 j = newton_coulomb_impulse(c, u, e, friction, counters);
      sb.apply(c, j, true, true);
      // Events are judged by the approach before the loop's first impulse: later passes see a
      // body already turned by its other points' impulses.
      const double approach = -c.start_un;
      if (approach > event_speed) {
        // One event per pair and step: contacts of a pair are consecutive, so the pair's event,
        // if any, is among those recorded since the loop began.
        auto same_pair = [&](const CollisionEvent& ev) { return ev.body_a == c.a && ev.body_b == c.b; };
        auto it = std::find_if(events.begin() + static_cast<std::ptrdiff_t>(first_event), events.end(), same_pair);
        if (it == events.end()) {
          events.push_back({time, c.a, c.b, 0.0, 0.0});
          it = events.end() - 1;
        }
        it->impulse += j.norm();
        it->approach_speed = std::max(it->approach_speed, approach);
      }
    }
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
    stats.collision_residual[pass] = residual;
    stats.collision_passes_used = pass + 1;
  }
}

}  // namespace boxpile
