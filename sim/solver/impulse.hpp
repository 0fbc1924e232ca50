// The Newton-Coulomb impulse at one contact point, and the contact data it needs.
//
// With u the velocity of A's contact point relative to B's, n the unit normal from B toward A,
// and r_A, r_B the contact point relative to the centres of mass, an impulse j on A (and -j on B)
// changes u by K j, where K is the collision matrix (Eberly, "Game Physics", 2nd ed., sec. 5.2;
// Mirtich's thesis, sec. 2.3):
//   K = (1/mA + 1/mB) E - [rA]x IA^-1 [rA]x - [rB]x IB^-1 [rB]x.
// Sticking: the impulse that leaves the point with normal velocity -e u_n and no sliding is
//   j = K^-1 (-e u_n n - u).
// If it leaves the friction cone (|j_t| > mu j_n), the point slides along t, the direction of
// the tangential part of u, and the impulse lies on the cone's edge:
//   j = j_n (n - mu t),  j_n = -(1 + e) u_n / (n . K (n - mu t)).
// This is Eberly's eq. 5.27 with Coulomb friction as in the course notes (the pseudo-code on
// Eberly's p. 248 has a typo: in fNumer the last kA should be kB).
#pragma once

#include <cstdint>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

// One contact point as the solver sees it during a step (positions do not change in a step, so
// r_A, r_B and each body's share of K are computed once).
struct SolverContact {
  int a = 0;
  int b = 0;  // kGround (-1) for the ground
  Vec3 n = Vec3::UnitZ();
  Vec3 ra = Vec3::Zero();
  Vec3 rb = Vec3::Zero();
  double depth = 0.0;
  double friction = 0.0;     // mu
  double restitution = 0.0;  // e
  Mat3 Ka = Mat3::Zero();    // 1/mA E - [rA]x IA^-1 [rA]x (zero for a fixed body)
  Mat3 Kb = Mat3::Zero();
  // The collision matrix the current phase uses and its inverse: Ka + Kb, or in shock
  // propagation the share of the bodies that still move. Set once per phase, not per impulse.
  Mat3 K = Mat3::Zero();
  Mat3 Kinv = Mat3::Zero();
  bool active = true;        // the collision loop drops contacts that separate
  // The normal velocity when the current loop began (the collision loop's events and the
  // contact loop's restitution ramp read it), and, in the resting phase (contact loop and
  // shock propagation), the impulse accumulated over the phase so far.
  double start_un = 0.0;
  Vec3 accumulated = Vec3::Zero();
  Vec3 slide_dir = Vec3::Zero();  // unit tangential direction if sliding at the start, else 0
};

// Body A's share of K at offset r: (1/m) E - [r]x I^-1 [r]x.
Mat3 collision_matrix_share(const RigidBody& body, const Vec3& r);

// Counts of the work the solver did: the tests check that a scene without an effect never pays
// for it.
struct ImpulseCounters {
  std::uint64_t normal_impulses = 0;       // impulses computed (any kind)
  std::uint64_t friction_evaluations = 0;  // impulses that solved for a tangential part
  std::uint64_t sliding = 0;               // impulses clamped to the friction cone
};

// Sets c.K and c.Kinv from the shares of the bodies that move (a fixed body has a zero share).
void set_collision_matrix(SolverContact& c, bool a_moves, bool b_moves);

// The impulse on A for relative velocity u, restitution e, friction on or off, with c.K.
// Returns zero when the point does not approach (u_n >= 0).
Vec3 newton_coulomb_impulse(const SolverContact& c, const Vec3& u, double e, bool friction,
                            ImpulseCounters& counters);

// Starts a resting phase at a contact whose relative velocity is u: records u_n, clears the
// accumulated impulse, and fixes the sliding direction (zero when the point barely slides).
void begin_resting_phase(SolverContact& c, const Vec3& u);

// Resting contacts: one projected Gauss-Seidel update of the impulse accumulated over the
// resting phase. It asks for normal velocity `target_un` and (with friction) no sliding,
// Delta j = K^-1 (target_un n - u), then projects the accumulated impulse J + Delta j on the
// friction cone (J_n >= 0, |J_t| <= mu J_n); outside it, the point slides and the total is
// J_n (n - mu t) against the sliding direction t. Unlike a lone push-only impulse it may take
// back part of what it gave earlier in the phase, so the sequential passes converge to the
// impulses that hold every point of a resting face together (the push-only form leaves a box
// lifting and drifting: docs/solver.md). Updates c.accumulated; returns the impulse on A now.
Vec3 resting_impulse(SolverContact& c, const Vec3& u, double target_un, bool friction,
                     ImpulseCounters& counters);

}  // namespace boxpile
