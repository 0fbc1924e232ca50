// The velocity stages of the Guendelman-Bridson-Fedkiw step ("Nonconvex rigid bodies with
// stacking", SIGGRAPH 2003, sec. 5-7, in the simplified form of the course's lab text): the
// collision loop, the contact loop with its restitution ramp, and shock propagation.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "sim/body.hpp"
#include "sim/solver/impulse.hpp"

namespace boxpile {

// The largest number of passes a loop may be given (keeps per-pass statistics fixed-size).
inline constexpr int kMaxSolverPasses = 64;

// What the solver did in one step, for the convergence plots and the effect tests.
struct StepStats {
  int collision_passes_used = 0;  // passes run before every contact separated (or the limit)
  // Speculative contacts: a point `gap` = -depth > 0 apart may approach at up to gap / dt in this
// step without touching. Returns the lowest normal velocity the step allows, min(target, -gap/dt).
inline double allow_gap(const SolverContact& c, double target, double dt) {
  return c.depth < 0.0 ? std::min(target, c.depth / dt) : target;
}

// Largest approaching normal velocity left after each collision-loop pass, m/s.
  std::array<double, kMaxSolverPasses> collision_residual{};
  // The same after each contact-loop pass (with that pass's ramped restitution).
  std::array<double, kMaxSolverPasses> contact_residual{};
  int contact_passes_used = 0;
  int shock_levels = 0;
  int shock_passes_used = 0;  // summed over the levels
  double residual_after_shock = 0.0;
};

// The bodies and contacts the loops work on. `ground` is a fixed body standing for the
// half-space (index kGround in contacts).
struct SolverBodies {
  std::vector<RigidBody>& bodies;
  const RigidBody& ground;

  RigidBody& at(int i) { return bodies[i]; }
  const RigidBody& get(int i) const { return i < 0 ? ground : bodies[i]; }
  // Velocity of A's contact point relative to B's.
  Vec3 relative_velocity(const SolverContact& c) const {
    return get(c.a).v + get(c.a).omega.cross(c.ra) - get(c.b).v - get(c.b).omega.cross(c.rb);
  }
  // Applies j to A and -j to B at the contact offsets; frozen or fixed bodies do not move.
  void apply(const SolverContact& c, const Vec3& j, bool a_moves, bool b_moves) {
    if (a_moves && !get(c.a).fixed) push(at(c.a), j, c.ra);
    if (b_moves && c.b >= 0 && !get(c.b).fixed) push(at(c.b), -j, c.rb);
  }

 private:
  static void push(RigidBody& body, const Vec3& impulse, const Vec3& r) {
    body.P += impulse;
    body.L += r.cross(impulse);
    body.v = body.inv_mass * body.P;
    body.omega = body.inv_inertia_world * body.L;
  }
};

// A collision event: an impulse at an approach faster than resting contact explains.
struct CollisionEvent {
  double time = 0.0;
  int body_a = 0;
  int body_b = 0;
  double impulse = 0.0;  // N s, summed over the pair's points in that step
  double approach_speed = 0.0;  // m/s, the fastest approaching point
};

// Collision loop: `passes` sequential passes of Newton-Coulomb impulses with restitution e over
// the active contacts; after each pass, contacts that no longer approach are deactivated.
// Impulses at approach speeds above `event_speed` are reported as events.
void collision_loop(SolverBodies& sb, std::vector<SolverContact>& contacts, int passes,
                    bool restitution, bool friction, double time, double dt, double event_speed,
                    ImpulseCounters& counters, StepStats& stats, std::vector<CollisionEvent>& events);

// Contact loop: `passes` passes over every contact of the step's set, restitution ramped
// e_k = -1 + (k + 1) / passes (from -1 + 1/n up to 0), nothing removed.
void contact_loop(SolverBodies& sb, std::vector<SolverContact>& contacts, int passes, bool friction,
                  double dt, ImpulseCounters& counters, StepStats& stats);

// Shock propagation: bodies sorted into levels by contact-graph distance from the ground and
// fixed bodies; level by level from the bottom, up to `passes` passes with e = 0 over the
// contacts that reach down from the level (fewer once the level has converged), with every
// lower level frozen (infinite mass).
class ShockPropagation {
 public:
  void run(SolverBodies& sb, std::vector<SolverContact>& contacts, int passes, bool friction,
           double dt, ImpulseCounters& counters, StepStats& stats);
  // Level of each body in the last run (-1: fixed; kUnsupported: not connected to the ground).
  const std::vector<int>& levels() const { return level_; }
  static constexpr int kUnsupported = 1 << 30;

 private:
  std::vector<int> level_;
  std::vector<int> queue_;
  std::vector<int> adjacency_start_, adjacency_;  // contact graph, compressed rows
  std::vector<int> by_level_;                      // contact indices sorted by level
  std::vector<int> level_start_;
};

// Speculative contacts: a point `gap` = -depth > 0 apart may approach at up to gap / dt in this
// step without touching. Returns the lowest normal velocity the step allows, min(target, -gap/dt).
inline double allow_gap(const SolverContact& c, double target, double dt) {
  return c.depth < 0.0 ? std::min(target, c.depth / dt) : target;
}

// Largest approaching normal velocity over the contacts beyond what their gaps allow (0 when
// none approaches), m/s.
double approach_residual(const SolverBodies& sb, const std::vector<SolverContact>& contacts, double dt);

}  // namespace boxpile
