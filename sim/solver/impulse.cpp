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
  // (1/m) E - [r]x I^-1 [r]x, written out: each row and column of [r]x holds one zero, so every
  // entry of the two products is a sum of two terms, not three. Adding the third, a zero, changes
  // no nonzero sum, so the entries are those of the two 3x3 products Eigen would form (bit for
  // bit but for the sign of an exact zero), with 36 multiplications instead of 54.
  const Mat3& I = body.inv_inertia_world;
  const double x = r.x(), y = r.y(), z = r.z();
  Mat3 T;  // [r]x I^-1
  for (int j = 0; j < 3; ++j) {
    T(0, j) = -z * I(1, j) + y * I(2, j);
    T(1, j) = z * I(0, j) + -x * I(2, j);
    T(2, j) = -y * I(0, j) + x * I(1, j);
  }
  Mat3 K;  // (1/m) E - T [r]x
  for (int i = 0; i < 3; ++i) {
    K(i, 0) = (i == 0 ? body.inv_mass : 0.0) - (T(i, 1) * z + T(i, 2) * -y);
    K(i, 1) = (i == 1 ? body.inv_mass : 0.0) - (T(i, 0) * -z + T(i, 2) * x);
    K(i, 2) = (i == 2 ? body.inv_mass : 0.0) - (T(i, 0) * y + T(i, 1) * -x);
  }
  return K;
}

void set_collision_matrix(SolverContact& c, bool a_moves, bool b_moves) {
  c.K = (a_moves ? c.Ka : Mat3::Zero()) + (b_moves ? c.Kb : Mat3::Zero());
  // K is symmetric positive definite whenever one moving body has finite mass. Its inverse is
  // taken as symmetric (from K's upper triangle; the lower one differs by rounding), so
  // n . (K^-1 x) and (K^-1 n) . x sum the same products, grouped differently: they agree to
  // rounding, where with a general inverse a normal-tangent coupling of rounding size could
  // differ in sign between the two orientations.
  c.Kinv = symmetric_inverse(c.K);
  c.Kinv_n = c.Kinv * c.n;
  c.Kinv_n_size = c.Kinv.cwiseAbs() * c.n.cwiseAbs();
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

}  // namespace boxpile
