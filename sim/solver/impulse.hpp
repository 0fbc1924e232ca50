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

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

// One contact point as the solver sees it during a step (positions do not change in a step, so
// r_A, r_B and each body's share of K are computed once).
// The fields the resting passes read at every impulse come first, one after another, and the
// collision loop's own last. Each body's share of K, read once per step or per phase, is kept
// apart (ContactMatrices): every pass streams through the step's contacts, and on a pyramid of
// thousands of boxes they no longer fit in the caches (docs/performance.md).
struct SolverContact {
  int a = 0;
  int b = 0;  // kGround (-1) for the ground
  Vec3 n = Vec3::UnitZ();
  Vec3 ra = Vec3::Zero();
  Vec3 rb = Vec3::Zero();
  double depth = 0.0;
  double slop = 0.0;         // m, penetration left alone by recovery (relative to the pair's boxes)
  double friction = 0.0;     // mu
  // The normal velocity when the current loop began (the collision loop's events and the
  // contact loop's restitution ramp read it), and, in the resting phase (contact loop and
  // shock propagation), the impulse accumulated over the phase so far.
  double start_un = 0.0;
  Mat3 Wa = Mat3::Zero();    // [rA]x^T, so omega_A x rA = Wa omega_A (likewise Wb): solver_body.hpp
  Mat3 Wb = Mat3::Zero();
  Vec3 accumulated = Vec3::Zero();
  Vec3 slide_dir = Vec3::Zero();  // unit tangential direction if sliding at the start, else 0
  // K^-1 n and |K^-1| |n| (Kinv is exactly symmetric), set with K: the normal part of a sticking
  // impulse is Kinv_n . (target n - u), and Kinv_n_size . |target n - u| bounds the terms it sums
  // (stays_unloaded).
  Vec3 Kinv_n = Vec3::Zero();
  Vec3 Kinv_n_size = Vec3::Zero();
  // The collision matrix the current phase uses and its inverse: Ka + Kb, or in shock
  // propagation the share of the bodies that still move. Set once per phase, not per impulse.
  Mat3 Kinv = Mat3::Zero();
  Mat3 K = Mat3::Zero();
  double restitution = 0.0;  // e
  double collision_impulse = 0.0;  // N s, the normal impulse the collision loop gave this step
  bool active = true;        // the collision loop drops contacts that separate
  // K and its inverse are shock propagation's share of the bodies that move (a frozen body's left
  // out), not the prepared Ka + Kb: a contact kept for the next step takes back its K from the
  // shares, and only then (ImpulseMethod::prepare_solver_contacts).
  bool frozen_k = false;
};

// A contact's collision matrices apart from the SolverContact, in an array beside the solver's
// contacts (ImpulseStep::matrices): each body's share of K, which shock propagation and recovery
// read once per phase, and from which a contact kept from the last step whose K shock propagation
// changed (frozen_k) forms it again, as it was prepared.
struct ContactMatrices {
  Mat3 Ka = Mat3::Zero();  // 1/mA E - [rA]x IA^-1 [rA]x (zero for a fixed body)
  Mat3 Kb = Mat3::Zero();
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

// Sets c.K and c.Kinv from the shares (m) of the bodies that move (a fixed body has a zero share),
// and c.frozen_k when one of them is left out.
void set_collision_matrix(SolverContact& c, const ContactMatrices& m, bool a_moves, bool b_moves);
// Sets c.K to K (Ka + Kb, or the moving body's share alone) and c.Kinv from it.
void set_collision_matrix(SolverContact& c, const Mat3& K);

// The impulse on A for relative velocity u, restitution e, friction on or off, with c.K.
// Returns zero when the point does not approach (u_n >= 0). The lab text's impulse: its
// collision loop (without pair_impulses) and, with the ramped e, its contact loop (without
// accumulated_impulses).
Vec3 newton_coulomb_impulse(const SolverContact& c, const Vec3& u, double e, bool friction,
                            ImpulseCounters& counters);
// The push-only impulse that brings the point's normal velocity up to `target_un` (sticking, or on
// the cone's edge when sticking would leave it); zero when u_n >= target_un already. Newton-Coulomb
// with restitution e is target_un = -e u_n.
Vec3 push_impulse(const SolverContact& c, const Vec3& u, double target_un, bool friction, ImpulseCounters& counters);

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
// Defined below and always inlined: the contact loop and shock propagation call it for every
// contact of every pass (as a call it cost 6-8% of a step).
Vec3 resting_impulse(SolverContact& c, const Vec3& u, double target_un, bool friction,
                     ImpulseCounters& counters);

// Whether sqrt(squared) <= limit, decided exactly as the rounded square root would decide it. The
// root (the slowest instruction of a resting impulse) is taken only where squared and limit^2
// agree to within kNormMargin, i.e. within a few ulps of the cone's edge; elsewhere the squares
// decide. Tiny limits, whose squares lose precision to underflow, always take the root.
inline bool norm_within(double squared, double limit) {
  // Rounding of limit^2 and of the rounded root are each below one ulp (2.2e-16 relative).
  constexpr double kNormMargin = 8.0 * std::numeric_limits<double>::epsilon();
  constexpr double kSmallestExactSquare = 1e-150;  // limit^2 above it is a normal double
  if (limit > kSmallestExactSquare) {
    const double limit_sq = limit * limit;
    if (squared < limit_sq * (1.0 - kNormMargin)) return true;
    if (squared > limit_sq * (1.0 + kNormMargin)) return false;
  }
  return std::sqrt(squared) <= limit;
}

// Whether an impulse with normal part jn and tangential part jt lies in the friction cone of
// coefficient mu (jn >= 0, |jt| <= mu jn), decided as norm_within decides it.
inline bool within_cone(double jn, const Vec3& jt, double mu) { return jn >= 0.0 && norm_within(jt.squaredNorm(), mu * jn); }

// Whether every component is zero (+0 or -0), exactly: Eigen's isZero() allows 1e-12.
inline bool is_exact_zero(const Vec3& v) { return v.x() == 0.0 && v.y() == 0.0 && v.z() == 0.0; }

// Whether a point that carries no impulse yet would still carry none after a resting update, told
// from the normal part of its sticking impulse alone (one dot product instead of the update): a
// sticking impulse that would pull (j_n < 0) ends on the cone's apex, and so does a sliding one
// while the point already meets its target. A third of the contact loop's updates in the Jenga
// tower are such points: separating, or kept apart by their neighbours. The normal part is
// estimated with a different rounding than the update computes it, so only a clear pull is
// decided here (below kUnloadedMargin of the terms' size); the update decides the rest itself.
inline bool stays_unloaded(const SolverContact& c, const Vec3& u, double un, double target_un) {
  // Far above the rounding of either form (a few ulps, 1e-15 relative).
  constexpr double kUnloadedMargin = 1e-12;
  const Vec3 rhs = target_un * c.n - u;
  const double jn = c.Kinv_n.dot(rhs);
  const double size = c.Kinv_n_size.dot(rhs.cwiseAbs());
  if (!(jn < -kUnloadedMargin * size)) return false;
  return c.slide_dir.isZero() || un >= target_un;
}

[[gnu::always_inline]] inline Vec3 resting_impulse(SolverContact& c, const Vec3& u, double target_un, bool friction,
                                                   ImpulseCounters& counters) {
  ++counters.normal_impulses;
  const Vec3& n = c.n;
  const double un = n.dot(u);
  const Vec3 J_old = c.accumulated;
  if (!friction || c.friction <= 0.0) {
    const double jn_old = J_old.dot(n);
    const double jn_new = std::max(0.0, jn_old + (target_un - un) / n.dot(c.K * n));
    c.accumulated = jn_new * n;
    return (jn_new - jn_old) * n;
  }
  ++counters.friction_evaluations;
  if (is_exact_zero(J_old) && stays_unloaded(c, u, un, target_un)) {
    ++counters.sliding;  // the full update below would end on the cone's apex, as sliding
    return Vec3::Zero();
  }
  // Sticking: the total impulse that brings the point to u_n = target with no sliding.
  Vec3 J = J_old + c.Kinv * (target_un * n - u);
  const double jn = J.dot(n);
  const Vec3 jt = J - jn * n;
  if (within_cone(jn, jt, c.friction)) {
    c.accumulated = J;
    return J - J_old;
  }
  // Sliding: Coulomb friction opposes the sliding velocity with the full mu J_n, so the total is
  // J = J_n (n - mu t), t the sliding direction at the phase's start, with J_n set by the target:
  //   n . (u + K (J - J_old)) = target  =>  J_n = (target - u_n + n . K J_old) / (n . K (n - mu t)).
  // (Eberly's sliding impulse, eq. 5.27 with friction, for the impulse accumulated over the
  // phase.) Clamping the sticking impulse radially instead would tilt each corner's friction
  // off the sliding direction and lose up to 6% of it on a sliding box.
  ++counters.sliding;
  if (c.slide_dir.isZero()) {
    // The point was not sliding when the phase began: its sliding direction would be noise, so
    // keep the sticking impulse's own direction and clamp it radially onto the cone.
    // A point pulled apart (J_n <= 0) keeps no impulse: its scale is +0, known without the root
    // and the division (friction * 0 / |j_t| is +0 too), which would wait in its chain.
    const double jn_clamped = std::max(0.0, jn);
    const double scale =
        jn_clamped > 0.0 && jt.norm() > 0.0 ? std::min(1.0, c.friction * jn_clamped / jt.norm()) : 0.0;
    J = jn_clamped * n + scale * jt;
    c.accumulated = J;
    return J - J_old;
  }
  const Vec3& t = c.slide_dir;
  const Vec3 dir = n - c.friction * t;
  const double denom = n.dot(c.K * dir);
  double jn_slide = 0.0;
  if (denom > 0.0) jn_slide = std::max(0.0, (target_un - un + n.dot(c.K * J_old)) / denom);
  J = jn_slide * dir;
  c.accumulated = J;
  return J - J_old;
}

}  // namespace boxpile
