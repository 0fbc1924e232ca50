#include "boxpile/sim/solver/pair_impulse.hpp"

#include <algorithm>
#include <array>

#include <Eigen/Cholesky>

namespace boxpile {
namespace {

using BlockMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlockPoints, kMaxBlockPoints>;
using BlockVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxBlockPoints, 1>;

// The redundant points of a face make the block matrix singular. A ridge of this much of its
// mean diagonal makes it definite and, being tiny, picks the minimum-norm solution among the
// exact ones (the Tikhonov limit), which is the symmetric one.
constexpr double kRidge = 1e-10;

// One point's part of the block for one body: n_i . K_ij n_j = (1/m) n_i . n_j + c_i . I^-1 c_j with
// c = r x n. Computed once per point, so that an entry of the block costs two dot products.
struct PointShare {
  Vec3 c = Vec3::Zero();   // r x n
  Vec3 Ic = Vec3::Zero();  // I^-1 (r x n)
};

PointShare share_of(const RigidBody& b, const Vec3& r, const Vec3& n) {
  if (b.fixed) return {};
  const Vec3 c = r.cross(n);
  return {c, b.inv_inertia_world * c};
}

// The normal impulses of the points in `set` that change each u_n by `change`: the minimum-norm
// solution, then, while one is negative, the most negative point leaves the set.
void solve_normal(const SolverBodies& sb, std::span<SolverContact> points, std::array<int, kMaxBlockPoints>& set,
                  int& count, const BlockVector& change, BlockVector& lambda) {
  const RigidBody& a = sb.get(points[0].a);
  const RigidBody& b = sb.get(points[0].b);
  const double inv_mass = (a.fixed ? 0.0 : a.inv_mass) + (b.fixed ? 0.0 : b.inv_mass);
  std::array<PointShare, kMaxBlockPoints> sa, sbb;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    sa[i] = share_of(a, points[i].ra, points[i].n);
    sbb[i] = share_of(b, points[i].rb, points[i].n);
  }
  while (count > 0) {
    BlockMatrix A(count, count);
    BlockVector rhs(count);
    for (int p = 0; p < count; ++p) {
      const int i = set[p];
      rhs[p] = change[i];
      for (int q = p; q < count; ++q) {
        const int j = set[q];
        A(p, q) = A(q, p) = inv_mass * points[i].n.dot(points[j].n) + sa[i].c.dot(sa[j].Ic) + sbb[i].c.dot(sbb[j].Ic);
      }
    }
    A.diagonal().array() += kRidge * A.diagonal().mean();
    lambda = A.ldlt().solve(rhs);
    int worst = -1;
    for (int p = 0; p < count; ++p)
      if (lambda[p] < 0.0 && (worst < 0 || lambda[p] < lambda[worst])) worst = p;
    if (worst < 0) return;
    set[worst] = set[--count];
  }
}

// The tangential impulse that stops point c's sliding, clamped to the disc of radius limit.
Vec3 friction_impulse(const SolverContact& c, const Vec3& u, double limit) {
  const Vec3 ut = u - c.n.dot(u) * c.n;
  if (!(ut.squaredNorm() > 0.0) || !(limit > 0.0)) return Vec3::Zero();
  const Vec3 t1 = c.n.unitOrthogonal();
  const Vec3 t2 = c.n.cross(t1);
  Eigen::Matrix<double, 3, 2> T;
  T << t1, t2;
  const Eigen::Vector2d lambda = (T.transpose() * c.K * T).ldlt().solve(-T.transpose() * u);
  Vec3 j = T * lambda;
  if (j.norm() > limit) j *= limit / j.norm();
  return j;
}

void solve_block(SolverBodies& sb, std::span<SolverContact> points, bool restitution, bool friction,
                 ImpulseCounters& counters) {
  const int n = static_cast<int>(points.size());
  std::array<int, kMaxBlockPoints> set{};
  int count = 0;
  BlockVector target(n);  // the change of u_n each approaching point needs
  for (int i = 0; i < n; ++i) {
    const double un = points[i].n.dot(sb.relative_velocity(points[i]));
    target[i] = 0.0;
    if (!points[i].active || un >= 0.0) continue;
    const double e = restitution ? points[i].restitution : 0.0;
    target[i] = -(1.0 + e) * un;
    set[count++] = i;
  }
  if (count == 0) return;
  BlockVector lambda;
  if (count == 1) {  // one point: the scalar impulse, no system to build
    const SolverContact& c = points[set[0]];
    lambda.resize(1);
    lambda[0] = target[set[0]] / c.n.dot(c.K * c.n);
  } else {
    solve_normal(sb, points, set, count, target, lambda);
  }
  for (int p = 0; p < count; ++p) {
    SolverContact& c = points[set[p]];
    ++counters.normal_impulses;
    sb.apply(c, lambda[p] * c.n, true, true);
    c.collision_impulse += lambda[p];
  }
  if (!friction) return;
  for (int p = 0; p < count; ++p) {
    SolverContact& c = points[set[p]];
    if (c.friction <= 0.0) continue;
    ++counters.friction_evaluations;
    const Vec3 j = friction_impulse(c, sb.relative_velocity(c), c.friction * lambda[p]);
    sb.apply(c, j, true, true);
  }
}

}  // namespace

void pair_collision_impulses(SolverBodies& sb, std::span<SolverContact> points, bool restitution, bool friction,
                             ImpulseCounters& counters) {
  for (std::size_t first = 0; first < points.size(); first += kMaxBlockPoints) {
    const std::size_t size = std::min<std::size_t>(kMaxBlockPoints, points.size() - first);
    solve_block(sb, points.subspan(first, size), restitution, friction, counters);
  }
}

}  // namespace boxpile
