// What the velocity stages of the Guendelman-Bridson-Fedkiw step ("Nonconvex rigid bodies with
// stacking", SIGGRAPH 2003, sec. 5-7, in the simplified form of the course's lab text) share:
// the bodies and contacts they work on, and the step context that carries them.
#pragma once

#include <algorithm>
#include <array>
#include <span>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/solver/impulse.hpp"
#include "boxpile/sim/solver/solver_body.hpp"
#include "boxpile/sim/solver/step_context.hpp"

namespace boxpile {

// The bodies and contacts the loops work on. `ground` is a fixed body standing for the
// half-space (index kGround in contacts).
struct SolverBodies {
  std::vector<RigidBody>& bodies;
  const RigidBody& ground;

  RigidBody& at(int i) { return bodies[i]; }
  const RigidBody& get(int i) const { return i < 0 ? ground : bodies[i]; }
  // Velocity of A's contact point relative to B's.
  // (omega x r as W omega, as in SolverBodyArray::relative_velocity: the same result, faster.)
  Vec3 relative_velocity(const SolverContact& c) const {
    return get(c.a).v + c.Wa * get(c.a).omega - get(c.b).v - c.Wb * get(c.b).omega;
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

// What the impulse method did in one step, for the convergence plots and the effect tests.
struct ImpulseStepStats {
  int collision_passes_used = 0;  // passes run before every contact separated (or the limit)
  // Largest approaching normal velocity left after each collision-loop pass, m/s.
  std::array<double, kMaxSolverPasses> collision_residual{};
  // The same after each contact-loop pass (with that pass's ramped restitution).
  std::array<double, kMaxSolverPasses> contact_residual{};
  int contact_passes_used = 0;
  int shock_levels = 0;
  int shock_passes_used = 0;  // summed over the levels' islands (a part's direct solves count as one)
  int shock_parts = 0;        // (island, level) parts solved: each island's share of a level, solved apart
  // Largest velocity change |K dj| an impulse made in each shock-propagation pass, over the
  // levels (a level stops once it is below kRestingConverged), m/s; shock_pass_count passes are
  // recorded. A level's direct solves of sticking groups count as its first pass, with their
  // largest residual as its change.
  std::array<double, kMaxSolverPasses> shock_change{};
  int shock_pass_count = 0;  // the most passes any level used
  // Parts (an island's share of a level) whose passes stopped because they no longer converged.
  int shock_stalled_levels = 0;
  double residual_after_shock = 0.0;
};

// The step context of the impulse loops: the world's step, the bodies as the loops see them
// (the resting phases through their compact array, gathered and scattered around each phase), and
// the step's solver contacts, with the settings and records every loop reads.
struct ImpulseStep {
  StepContext& world;
  SolverBodies sb;
  SolverBodyArray& resting;
  std::vector<SolverContact>& contacts;
  std::vector<ContactMatrices>& matrices;  // beside contacts, index for index
  ImpulseCounters& impulses;  // the method's own records
  ImpulseStepStats& records;

  const SolverSettings& settings() const { return world.scene.solver; }
  bool friction() const { return world.scene.effects.friction; }
  bool restitution() const { return world.scene.effects.restitution; }
  double dt() const { return world.dt; }
  ImpulseCounters& counters() { return impulses; }
  ImpulseStepStats& stats() { return records; }
};

// A level of shock propagation has converged once no impulse of a pass changes a point's
// velocity by more than this (m/s): 1e-12 m/s over the 100,000 steps of 417 s moves a box by
// 4e-10 m. (At 1e-9 m/s a stack of 10 kept a residual 2e-7 m/s and drifted 1e-4 m in 100,000
// steps: a level left unconverged starts the next step from a worse state.)
inline constexpr double kRestingConverged = 1e-12;

// Speculative contacts: a point `gap` = -depth > 0 apart may approach at up to gap / dt in this
// step without touching. Returns the lowest normal velocity the step allows, min(target, -gap/dt).
inline double allow_gap(const SolverContact& c, double target, double dt) {
  return c.depth < 0.0 ? std::min(target, c.depth / dt) : target;
}

// Largest approaching normal velocity over the contacts beyond what their gaps allow (0 when
// none approaches), m/s, read from the resting phases' compact bodies (before they are scattered
// back: the same velocities, fewer cache lines than the bodies').
double approach_residual(const SolverBodyArray& sb, std::span<const SolverContact> contacts, double dt);

}  // namespace boxpile
