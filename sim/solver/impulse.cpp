#include "boxpile/sim/solver/impulse.hpp"

#include <algorithm>
#include <cmath>

namespace boxpile {

namespace {
// A point sliding slower than this (m/s) when a resting phase begins is treated as sticking:
// resting stacks show 1e-9 m/s of rounding noise, while a box starting to slide moves at
// g sin(theta) dt, about 1e-2 m/s at 240 Hz.
constexpr double kSlidingSpeed = 1e-5;
// Below this tangential speed (m/s) the sliding direction is taken from the sticking impulse
// instead of from u_t, whose direction is then rounding noise.
constexpr double kSlideDirectionSpeed = 1e-12;

}  // namespace

Mat3 collision_matrix_share(const RigidBody& body, const Vec3& r) {
  const Mat3 rx = cross_matrix(r);
  return body.inv_mass * Mat3::Identity() - rx * body.inv_inertia_world * rx;
}

void set_collision_matrix(SolverContact& c, bool a_moves, bool b_moves) {
  c.K = (a_moves ? c.Ka : Mat3::Zero()) + (b_moves ? c.Kb : Mat3::Zero());
  // K is symmetric positive definite whenever one moving body has finite mass.
  c.Kinv = c.K.inverse();
}

Vec3 newton_coulomb_impulse(const SolverContact& c, const Vec3& u, double e, bool friction,
                            ImpulseCounters& counters) {
  const Mat3& K = c.K;
  const double un = c.n.dot(u);
  if (un >= 0.0) return Vec3::Zero();
  ++counters.normal_impulses;
  // Frictionless: j = j_n n with n . K j = -(1 + e) u_n.
  auto frictionless = [&] { return Vec3((-(1.0 + e) * un / c.n.dot(K * c.n)) * c.n); };
  if (!friction || c.friction <= 0.0) return frictionless();

  ++counters.friction_evaluations;
  // Sticking impulse: K j = -e u_n n - u.
  const Vec3 j = c.Kinv * (-e * un * c.n - u);
  const double jn = j.dot(c.n);
  const Vec3 jt = j - jn * c.n;
  if (jn >= 0.0 && jt.norm() <= c.friction * jn) return j;

  // Sliding along t (the tangential direction of u): the impulse on the cone's edge.
  ++counters.sliding;
  const Vec3 ut = u - un * c.n;
  Vec3 t;
  if (ut.norm() > kSlideDirectionSpeed) {
    t = ut.normalized();
  } else if (jt.norm() > 0.0) {
    t = -jt.normalized();  // friction opposes sliding: the sticking impulse points along -t
  } else {
    return frictionless();
  }
  const Vec3 dir = c.n - c.friction * t;
  const double denom = c.n.dot(K * dir);
  if (denom <= 0.0) return frictionless();
  return (-(1.0 + e) * un / denom) * dir;
}

void begin_resting_phase(SolverContact& c, const Vec3& u) {
  c.start_un = c.n.dot(u);
  c.accumulated.setZero();
  const Vec3 ut = u - c.start_un * c.n;
  c.slide_dir = ut.norm() > kSlidingSpeed ? Vec3(ut.normalized()) : Vec3::Zero();
}

Vec3 resting_impulse(SolverContact& c, const Vec3& u, double target_un, bool friction,
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
  // Sticking: the total impulse that brings the point to u_n = target with no sliding.
  Vec3 J = J_old + c.Kinv * (target_un * n - u);
  const double jn = J.dot(n);
  const Vec3 jt = J - jn * n;
  if (jn >= 0.0 && jt.norm() <= c.friction * jn) {
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
    const double jn_clamped = std::max(0.0, jn);
    const double scale = jt.norm() > 0.0 ? std::min(1.0, c.friction * jn_clamped / jt.norm()) : 0.0;
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
