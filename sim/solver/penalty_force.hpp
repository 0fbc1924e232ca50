// The penalty method's force at one contact point (the lab text, "Penalty based simulation
// method"): a damped spring along the normal and a friction spring to an anchor.
//
// With d > 0 the penetration, u the velocity of A's point relative to B's and n from B toward A:
//   normal      f_n = max(0, k d - c u_n)   (zero at zero penetration, never pulling);
//   friction    the spring from the anchor q (on B) to p (on A), tangential part
//               s = (p - q) - ((p - q) . n) n, force F_t = -k_f s - c u_t while it sticks.
// Static and dynamic Coulomb friction: while |k_f s| <= mu_s f_n the anchor stays put (F_t is
// then bounded by mu_s f_n); once it leaves that cone the point slides, and each step the anchor
// is dragged to where the spring's force is mu_d f_n along the slip direction, F_t = -mu_d f_n s^.
// A sliding point sticks again when it stops moving away from its anchor, or when the spring,
// dragged no farther, pulls less than mu_d f_n.
#pragma once

#include "boxpile/sim/math.hpp"

namespace boxpile {

struct PenaltyPoint {
  Vec3 n = Vec3::UnitZ();  // unit, from B toward A
  // The friction spring's end on A: the material point of A where the contact began (world).
  Vec3 p = Vec3::Zero();
  double depth = 0.0;      // m, > 0 penetrating
  Vec3 u = Vec3::Zero();   // m/s, A's point relative to B's
  double stiffness = 0.0;           // k, N/m
  double damping = 0.0;             // c, N s/m (normal and tangential)
  double friction_stiffness = 0.0;  // k_f, N/m
  double static_mu = 0.0;           // mu_s
  double dynamic_mu = 0.0;          // mu_d <= mu_s
};

struct PenaltyForce {
  Vec3 force = Vec3::Zero();  // on A (B gets -force), N
  double normal = 0.0;        // f_n, N
  bool slipped = false;       // the spring left the static cone in this step
};

// The force on A at `pt`; moves the anchor `anchor` (world) and its sliding state as friction
// demands.
PenaltyForce penalty_force(const PenaltyPoint& pt, Vec3& anchor, bool& sliding);

}  // namespace boxpile
