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
  // (1/m) E - [r]x I^-1 [r]x, written out. I^-1 is symmetric, so the share is too: only its upper
  // triangle is formed (the lower one mirrors it), from the eight entries of T = [r]x I^-1 it
  // reads. Each row and column of [r]x holds one zero, so every entry of the two products is a sum
  // of two terms: 28 multiplications where the two 3x3 products take 54.
  const Mat3& I = body.inv_inertia_world;
  const double x = r.x(), y = r.y(), z = r.z();
  // T = [r]x I^-1: rows 0 and 1 whole, row 2's first two entries.
  const double t00 = -z * I(1, 0) + y * I(2, 0), t01 = -z * I(1, 1) + y * I(2, 1), t02 = -z * I(1, 2) + y * I(2, 2);
  const double t10 = z * I(0, 0) + -x * I(2, 0), t11 = z * I(0, 1) + -x * I(2, 1), t12 = z * I(0, 2) + -x * I(2, 2);
  const double t20 = -y * I(0, 0) + x * I(1, 0), t21 = -y * I(0, 1) + x * I(1, 1);
  // (1/m) E - T [r]x, the upper triangle.
  const double m = body.inv_mass;
  const double k00 = m - (t01 * z + t02 * -y), k01 = -(t00 * -z + t02 * x), k02 = -(t00 * y + t01 * -x);
  const double k11 = m - (t10 * -z + t12 * x), k12 = -(t10 * y + t11 * -x);
  const double k22 = m - (t20 * y + t21 * -x);
  Mat3 K;
  K << k00, k01, k02,
       k01, k11, k12,
       k02, k12, k22;
  return K;
}

void set_collision_matrix(SolverContact& c, const ContactMatrices& m, bool a_moves, bool b_moves) {
  set_collision_matrix(c, (a_moves ? m.Ka : Mat3::Zero()) + (b_moves ? m.Kb : Mat3::Zero()));
  c.frozen_k = !(a_moves && b_moves);
}

void set_collision_matrix(SolverContact& c, const Mat3& K) {
  // K is symmetric positive definite whenever one moving body has finite mass, and exactly
  // symmetric as computed (each share is formed from its upper triangle). Its inverse is taken as
  // symmetric too, so n . (K^-1 x) and (K^-1 n) . x sum the same products, grouped differently:
  // they agree to rounding, where with a general inverse a normal-tangent coupling of rounding
  // size could differ in sign between the two orientations.
  // Formed in locals and stored once: read back from the contact, each entry stored alone came
  // back in a pair and waited on both stores (perf: a third of this function's time).
  const Mat3 Kinv = symmetric_inverse(K);
  const Vec3 n = c.n;
  c.K = K;
  c.Kinv = Kinv;
  c.Kinv_n = Kinv * n;
  c.Kinv_n_size = Kinv.cwiseAbs() * n.cwiseAbs();
}

Vec3 newton_coulomb_impulse(const SolverContact& c, const Vec3& u, double e, bool friction,
                            ImpulseCounters& counters) {
  const double un = c.n.dot(u);
  if (un >= 0.0) return Vec3::Zero();
  return push_impulse(c, u, -e * un, friction, counters);
}

Vec3 push_impulse(const SolverContact& c, const Vec3& u, double target_un, bool friction, ImpulseCounters& counters) {
  const Mat3& K = c.K;
  const double un = c.n.dot(u);
  if (un >= target_un) return Vec3::Zero();
  ++counters.normal_impulses;
  const double gain = target_un - un;  // the change of u_n asked for, > 0
  // Frictionless: j = j_n n with n . K j = gain.
  auto frictionless = [&] { return Vec3((gain / c.n.dot(K * c.n)) * c.n); };
  if (!friction || c.friction <= 0.0) return frictionless();

  ++counters.friction_evaluations;
  // Sticking impulse: K j = target_un n - u.
  const Vec3 j = c.Kinv * (target_un * c.n - u);
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
  return (gain / denom) * dir;
}

void begin_resting_phase(SolverContact& c, const Vec3& u) {
  c.start_un = c.n.dot(u);
  c.accumulated.setZero();
  const Vec3 ut = u - c.start_un * c.n;
  c.slide_dir = ut.norm() > kSlidingSpeed ? Vec3(ut.normalized()) : Vec3::Zero();
}

}  // namespace boxpile
