#include "sim/solver/impulse.hpp"

#include <algorithm>
#include <cmath>

namespace boxpile {

namespace {
// Below this tangential speed (m/s) the sliding direction is taken from the sticking impulse
// instead of from u_t, whose direction is then rounding noise.
constexpr double kSlideDirectionSpeed = 1e-12;
}  // namespace

Mat3 collision_matrix_share(const RigidBody& body, const Vec3& r) {
  const Mat3 rx = cross_matrix(r);
  return body.inv_mass * Mat3::Identity() - rx * body.inv_inertia_world * rx;
}

Vec3 newton_coulomb_impulse(const SolverContact& c, const Mat3& K, const Vec3& u, double e,
                            bool friction, ImpulseCounters& counters) {
  const double un = c.n.dot(u);
  if (un >= 0.0) return Vec3::Zero();
  ++counters.normal_impulses;

  if (!friction || c.friction <= 0.0) {
    // Frictionless: j = j_n n with n . K j = -(1 + e) u_n.
    return (-(1.0 + e) * un / c.n.dot(K * c.n)) * c.n;
  }

  ++counters.friction_evaluations;
  // Sticking impulse: K j = -e u_n n - u.
  const Vec3 j = K.ldlt().solve(-e * un * c.n - u);
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
    return (-(1.0 + e) * un / c.n.dot(K * c.n)) * c.n;
  }
  const Vec3 dir = c.n - c.friction * t;
  const double denom = c.n.dot(K * dir);
  if (denom <= 0.0) return (-(1.0 + e) * un / c.n.dot(K * c.n)) * c.n;
  return (-(1.0 + e) * un / denom) * dir;
}

Vec3 resting_impulse(SolverContact& c, const Mat3& K, const Vec3& u, double target_un, bool friction,
                     ImpulseCounters& counters) {
  ++counters.normal_impulses;
  const double un = c.n.dot(u);
  if (!friction || c.friction <= 0.0) {
    const double jn_old = c.accumulated.dot(c.n);
    const double jn_new = std::max(0.0, jn_old + (target_un - un) / c.n.dot(K * c.n));
    c.accumulated = jn_new * c.n;
    return (jn_new - jn_old) * c.n;
  }
  ++counters.friction_evaluations;
  Vec3 J = c.accumulated + K.ldlt().solve(target_un * c.n - u);
  const double jn = std::max(0.0, J.dot(c.n));
  Vec3 jt = J - J.dot(c.n) * c.n;
  const double limit = c.friction * jn;
  if (jt.norm() > limit) {
    ++counters.sliding;
    jt *= limit / jt.norm();
  }
  J = jn * c.n + jt;
  const Vec3 delta = J - c.accumulated;
  c.accumulated = J;
  return delta;
}

}  // namespace boxpile
