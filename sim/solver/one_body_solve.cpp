#include "boxpile/sim/solver/one_body_solve.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>

#include "boxpile/sim/solver/impulse_step.hpp"

namespace boxpile {

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// A touching point's velocity must end this close to its target (m/s): the passes leave a group
// once no impulse changes a velocity by more than kRestingConverged, so a direct solve held to the
// same bound is as converged as they are; rounding of the 6x6 solve is some 1e-15 m/s.
constexpr double kOneBodyResidual = kRestingConverged;
// Smallest pivot of the 6x6 normal matrix, relative to its largest, for the points to fix the
// body's six velocities: points on one line leave a pivot of rounding size (1e-16 relative),
// while spread points leave pivots of the order of (spread / lever)^2, far above this.
constexpr double kOneBodyPivotRatio = 1e-9;
// At most this many points in a group (a box on four others with eight points each is 32 at most
// with the ground): larger groups go to the passes, so the solve needs no heap.
constexpr int kOneBodyMaxPoints = 48;
// A group needs this many touching points for the body's velocity to be fixed by them.
constexpr int kOneBodyMinPoints = 3;

// One point of the group as the solve sees it: the moving body's offset and W = [r]x^T, the sign
// of the impulse on the moving body (+1 when it is A), the velocity its point must reach, and
// whether it touches (depth >= 0: it sticks) or has a gap (it carries no impulse).
struct Point {
  SolverContact* c = nullptr;
  const Mat3* W = nullptr;
  double side = 1.0;
  Vec3 wanted = Vec3::Zero();
  double target = 0.0;
  bool touching = true;
};

// J^T y for J = [E, W]: the force y_lin and torque W^T y_lin, here for the impulse q on the body
// at the point (W^T q = r x q).
Vec6 generalised(const Mat3& W, const Vec3& q) {
  Vec6 g;
  g.head<3>() = q;
  g.tail<3>() = W.transpose() * q;
  return g;
}

// J y = y_lin + W y_ang: the velocity of the point under the body velocity y.
Vec3 at_point(const Mat3& W, const Vec6& y) { return y.head<3>() + W * y.tail<3>(); }

// The group's points, or the reason it is not one body's group with friction at every point.
OneBodyOutcome collect_points(const SolverBodyArray& sb, std::vector<SolverContact>& contacts,
                              std::span<const ShockPropagation::LevelContact> group, bool friction,
                              std::array<Point, kOneBodyMaxPoints>& points, int& body) {
  if (!friction) return OneBodyOutcome::frictionless;
  if (group.size() > static_cast<std::size_t>(kOneBodyMaxPoints)) return OneBodyOutcome::not_one_body;
  body = -2;
  int touching = 0;
  for (std::size_t k = 0; k < group.size(); ++k) {
    const ShockPropagation::LevelContact& lc = group[k];
    SolverContact& c = contacts[static_cast<std::size_t>(lc.index)];
    if (lc.a_moves == lc.b_moves) return OneBodyOutcome::not_one_body;
    const int mover = lc.a_moves ? c.a : c.b;
    if (body != -2 && mover != body) return OneBodyOutcome::not_one_body;
    body = mover;
    if (c.friction <= 0.0) return OneBodyOutcome::frictionless;
    Point& p = points[k];
    p.c = &c;
    p.side = lc.a_moves ? 1.0 : -1.0;
    p.W = lc.a_moves ? &c.Wa : &c.Wb;
    const Vec3 frozen = lc.a_moves ? sb.point_velocity(c.b, c.Wb) : sb.point_velocity(c.a, c.Wa);
    // u = v_A - v_B = target n: the moving point's velocity is the frozen one's plus side target n.
    p.wanted = frozen + p.side * lc.target * c.n;
    p.target = lc.target;
    p.touching = c.depth >= 0.0;
    if (p.touching) ++touching;
  }
  if (touching < kOneBodyMinPoints) return OneBodyOutcome::too_few_points;
  return OneBodyOutcome::solved;
}

// Whether a total impulse on A lies in the friction cone (J_n >= 0, |J_t| <= mu J_n).
bool in_cone(const SolverContact& c, const Vec3& J) {
  const double jn = J.dot(c.n);
  return jn >= 0.0 && norm_within((J - jn * c.n).squaredNorm(), c.friction * jn);
}

}  // namespace

OneBodyOutcome solve_one_body_group(SolverBodyArray& sb, std::vector<SolverContact>& contacts,
                                    std::span<const ShockPropagation::LevelContact> group, bool friction,
                                    ImpulseCounters& counters, double& worst_residual) {
  std::array<Point, kOneBodyMaxPoints> points;
  int body = -2;
  if (const OneBodyOutcome o = collect_points(sb, contacts, group, friction, points, body); o != OneBodyOutcome::solved)
    return o;
  const int count = static_cast<int>(group.size());
  const std::span<Point> pts(points.data(), static_cast<std::size_t>(count));

  // The body's velocity y = (v, omega) that brings every touching point to its wanted velocity,
  // by least squares: G y = sum J_i^T wanted_i, G = sum J_i^T J_i.
  Mat6 G = Mat6::Zero();
  Vec6 rhs = Vec6::Zero();
  for (const Point& p : pts) {
    if (!p.touching) continue;
    const Mat3& W = *p.W;
    G.topLeftCorner<3, 3>() += Mat3::Identity();
    G.topRightCorner<3, 3>() += W;
    G.bottomRightCorner<3, 3>() += W.transpose() * W;
    rhs += generalised(W, p.wanted);
  }
  G.bottomLeftCorner<3, 3>() = G.topRightCorner<3, 3>().transpose();
  const Eigen::LDLT<Mat6> ldlt(G);
  const Vec6 pivots = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success || !(pivots.minCoeff() > kOneBodyPivotRatio * pivots.maxCoeff()))
    return OneBodyOutcome::ill_conditioned;
  const Vec6 velocity = ldlt.solve(rhs);

  // Check it against what the passes solve: touching points at their targets, points with a gap
  // approaching no faster than the gap allows.
  double worst = 0.0;
  for (const Point& p : pts) {
    const Vec3 point = at_point(*p.W, velocity);
    if (p.touching) {
      worst = std::max(worst, (point - p.wanted).norm());
    } else if (p.side * p.c->n.dot(point - p.wanted) < -kOneBodyResidual) {
      return OneBodyOutcome::gap_closes;
    }
  }
  if (!(worst <= kOneBodyResidual)) return OneBodyOutcome::off_target;

  // The smallest totals over the phase that give the body that velocity: the generalised impulse
  // the touching points must supply is b = M (y - y_now) + sum over every point of J_i^T Q_old_i
  // (a point with a gap gives back what it carried), and Q_i = J_i G^-1 b is the least-norm split
  // of b over the touching points (sum J_i^T Q_i = G G^-1 b = b). Each must lie in its cone.
  SolverBody& state = sb.state(body);
  const Mat3 inertia = state.inv_inertia.inverse();
  Vec6 b;
  b.head<3>() = velocity.head<3>() / state.inv_mass - state.P;
  b.tail<3>() = inertia * velocity.tail<3>() - state.L;
  for (const Point& p : pts) b += generalised(*p.W, p.side * p.c->accumulated);
  const Vec6 split = ldlt.solve(b);
  Vec3 P = state.P, L = state.L;
  std::array<Vec3, kOneBodyMaxPoints> totals;
  for (int k = 0; k < count; ++k) {
    const Point& p = pts[static_cast<std::size_t>(k)];
    const Vec3 on_body = p.touching ? at_point(*p.W, split) : Vec3::Zero();
    Vec3& total = totals[static_cast<std::size_t>(k)];
    total = p.side * on_body;  // on A, as accumulated is kept
    if (p.touching && !in_cone(*p.c, total)) return OneBodyOutcome::outside_cone;
    // The body's momenta change by what the point's total changed (as SolverBodyArray::apply).
    const Vec3 change = on_body - p.side * p.c->accumulated;
    P += change;
    L += p.W->transpose() * change;
  }

  // Commit.
  for (int k = 0; k < count; ++k) pts[static_cast<std::size_t>(k)].c->accumulated = totals[static_cast<std::size_t>(k)];
  state.P = P;
  state.L = L;
  // The velocities the momenta imply: the least-squares velocity to rounding (1e-16 relative).
  state.v = state.inv_mass * P;
  state.omega = state.inv_inertia * L;
  counters.normal_impulses += static_cast<std::uint64_t>(count);
  counters.friction_evaluations += static_cast<std::uint64_t>(count);
  worst_residual = worst;
  return OneBodyOutcome::solved;
}

}  // namespace boxpile

