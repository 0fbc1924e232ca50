// The normal matrix of a rigid body's contact points, as the direct sticking solve forms it
// (sticking_solve.cpp): with J_i = [E, W_i] the velocity of point i under the body velocity
// y = (v, omega) (W_i = [r_i]x^T), G = sum J_i^T J_i = [p E, S; S^T, T], p the number of points,
// S = sum W_i, T = sum W_i^T W_i. Its linear block is a multiple of the identity, so G is factored
// through the 3x3 Schur complement C = T - S^T S / p (the second moment of the points about their
// centroid) instead of as a general 6x6 matrix: G y = r is
//   C omega = r_ang - S^T r_lin / p,   v = (r_lin - S omega) / p.
// C is factored as L D L^T without pivoting (it is symmetric positive semi-definite). The pivots of
// the whole elimination are p (three times) and D's; their smallest against their largest says
// whether the points fix all six velocities (points on one line leave a pivot of rounding size).
#pragma once

#include <algorithm>
#include <array>

#include "boxpile/sim/math.hpp"

namespace boxpile {

class PointNormalMatrix {
 public:
  using Vec6 = Eigen::Matrix<double, 6, 1>;

  // Adds a point at offset r from the centre of mass: S gains [r]x^T and T gains
  // [r]x [r]x^T = |r|^2 E - r r^T, kept as the sums of r, |r|^2 and r r^T.
  void add(const Vec3& r) {
    p_ += 1.0;
    sum_r_ += r;
    sum_r2_ += r.squaredNorm();
    sum_rr_ += r * r.transpose();
  }

  // Factors G; false when a pivot is not above `pivot_ratio` times the largest (or is not a
  // number), i.e. when the points do not fix the body's six velocities.
  bool factor(double pivot_ratio) {
    // C = T - S^T S / p = (sum |r|^2 - |R|^2 / p) E - (sum r r^T - R R^T / p), R = sum r (the
    // second moment of the points about their centroid), read from its lower triangle.
    const Vec3 centroid = sum_r_ / p_;
    const Mat3 C = (sum_r2_ - sum_r_.dot(centroid)) * Mat3::Identity() - (sum_rr_ - sum_r_ * centroid.transpose());
    d_[0] = C(0, 0);
    l10_ = C(1, 0) / d_[0];
    l20_ = C(2, 0) / d_[0];
    d_[1] = C(1, 1) - l10_ * l10_ * d_[0];
    l21_ = (C(2, 1) - l20_ * l10_ * d_[0]) / d_[1];
    d_[2] = C(2, 2) - l20_ * l20_ * d_[0] - l21_ * l21_ * d_[1];
    const double largest = std::max({p_, d_[0], d_[1], d_[2]});
    const double smallest_allowed = pivot_ratio * largest;
    // Comparisons with a NaN are false: a zero pivot's NaN successors decline too.
    return d_[0] > smallest_allowed && d_[1] > smallest_allowed && d_[2] > smallest_allowed;
  }

  // The pivots of the elimination: p, p, p and the three of C.
  Vec6 pivots() const {
    Vec6 d;
    d << p_, p_, p_, d_[0], d_[1], d_[2];
    return d;
  }

  // G^-1 r, after factor() has returned true.
  Vec6 solve(const Vec6& r) const {
    const Vec3 r_lin = r.head<3>();
    // C omega = r_ang - S^T r_lin / p: forward (L), diagonal (D), backward (L^T).
    // S^T x = [R]x x = R x x, and S omega = omega x R.
    const Vec3 b = r.tail<3>() - sum_r_.cross(r_lin) / p_;
    const double z0 = b.x();
    const double z1 = b.y() - l10_ * z0;
    const double z2 = b.z() - l20_ * z0 - l21_ * z1;
    const double w2 = z2 / d_[2];
    const double w1 = z1 / d_[1] - l21_ * w2;
    const double w0 = z0 / d_[0] - l10_ * w1 - l20_ * w2;
    const Vec3 omega(w0, w1, w2);
    Vec6 y;
    y.head<3>() = (r_lin - omega.cross(sum_r_)) / p_;
    y.tail<3>() = omega;
    return y;
  }

 private:
  double p_ = 0.0;
  Vec3 sum_r_ = Vec3::Zero();
  double sum_r2_ = 0.0;
  Mat3 sum_rr_ = Mat3::Zero();
  // C = L D L^T, L unit lower triangular.
  std::array<double, 3> d_{};
  double l10_ = 0.0, l20_ = 0.0, l21_ = 0.0;
};

}  // namespace boxpile
