#include "boxpile/sim/solver/sticking_solve.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>

#include "boxpile/sim/solver/impulse_step.hpp"

namespace boxpile {

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// A touching point's velocity must end this close to its target, and a free point may approach at
// most this much faster than its target allows (m/s): the passes leave a group once no impulse
// changes a velocity by more than kRestingConverged, so a direct solve held to the same bound is as
// converged as they are; the rounding of the 6x6 solve is some 1e-16 m/s per m/s of velocity.
constexpr double kStickingResidual = kRestingConverged;
// Smallest pivot of a body's 6x6 normal matrix, relative to its largest, for its points to fix its
// six velocities: points on one line leave a pivot of rounding size (1e-16 relative), while points
// spread over a face leave pivots of the order of (spread / lever)^2, far above this.
constexpr double kStickingPivotRatio = 1e-9;
// At most this many bodies and points in a group (a Jenga layer is three blocks and some 48
// points): larger groups go to the passes, so the solve needs no heap.
constexpr int kStickingMaxBodies = 4;
constexpr int kStickingMaxPoints = 64;
// A body needs this many touching points for its velocity to be fixed by them.
constexpr int kStickingMinPoints = 3;
// A point with a gap this small (m) counts as touching when the group cannot stick otherwise:
// faces resting on each other end a step 1e-16 to 1e-13 m apart or into each other by rounding,
// so a Jenga block's points on the blocks below fall on either side of depth 0 at random, and
// those with a gap of rounding size left the block too few points, or points on one line, or a
// split outside a cone (13% of the Jenga tower's groups). Asked to stick, such a point closes its
// gap within the step (it moves 1e-9 m at most).
constexpr double kNearTouchingGap = 1e-9;

// One point of a body as the solve sees it: its place in the group, the body's W = [r]x^T there,
// the sign of the impulse on the body (+1 when it is A), the velocity the point must reach, and
// whether it touches a body that does not move (touches_support: it sticks), has a gap to one (it
// carries no impulse), or links two moving bodies (it carries no impulse either). Left
// uninitialised until filled: a group's array of them is set up for every group of every level.
struct Point {
  int k;
  SolverContact* c;
  const Mat3* W;
  const Vec3* r;  // the point's offset from the body's centre of mass (W = [r]x^T)
  double side;
  Vec3 wanted;
  bool touching;
  bool link;
};

// A moving body's solve: its new momenta and the velocities they imply.
struct BodyPlan {
  int body = 0;
  Vec3 P = Vec3::Zero(), L = Vec3::Zero();
  Vec3 v = Vec3::Zero(), omega = Vec3::Zero();
};

// J y = y_lin + W y_ang: the velocity of the point under the body velocity y.
Vec3 at_point(const Mat3& W, const Vec6& y) { return y.head<3>() + W * y.tail<3>(); }

// Whether a total impulse on A lies in the contact's friction cone, as resting_impulse decides it.
bool in_cone(const SolverContact& c, const Vec3& J) {
  const double jn = J.dot(c.n);
  return within_cone(jn, J - jn * c.n, c.friction);
}

// Whether a point of the group sticks under the hypothesis: it joins a moving body to one that
// does not move (frozen, fixed or the ground) and touches it (depth >= -gap: 0 as the passes see
// it, kNearTouchingGap on the second try). A point with a larger gap, or between two moving bodies,
// carries no impulse instead.
bool touches_support(const ShockPropagation::LevelContact& lc, const SolverContact& c, double gap) {
  return lc.a_moves != lc.b_moves && c.depth >= -gap;
}

// Whether a point of the group is near touching: on a support with a gap within `gap`.
bool any_near_touching(const std::vector<SolverContact>& contacts,
                       std::span<const ShockPropagation::LevelContact> group, double gap) {
  for (const ShockPropagation::LevelContact& lc : group) {
    const SolverContact& c = contacts[static_cast<std::size_t>(lc.index)];
    if (touches_support(lc, c, gap) && !touches_support(lc, c, 0.0)) return true;
  }
  return false;
}

// The group's moving bodies, or why the solve does not take the group. Everything it declines
// here is decided from the contacts' bodies and depths alone, before any velocity is read: a
// declined group (half of a tumbling pile's) costs one look at each of its contacts.
StickingOutcome collect_bodies(const std::vector<SolverContact>& contacts,
                               std::span<const ShockPropagation::LevelContact> group, double gap,
                               std::array<BodyPlan, kStickingMaxBodies>& plans, int& count) {
  if (group.size() > static_cast<std::size_t>(kStickingMaxPoints)) return StickingOutcome::too_large;
  count = 0;
  std::array<int, kStickingMaxBodies> touching{};  // per body, its points on a body that does not move
  // The body's slot, or -1 when the group has more bodies than the solve holds.
  auto add = [&](int body) {
    for (int i = 0; i < count; ++i)
      if (plans[static_cast<std::size_t>(i)].body == body) return i;
    if (count == kStickingMaxBodies) return -1;
    plans[static_cast<std::size_t>(count)].body = body;
    touching[static_cast<std::size_t>(count)] = 0;
    return count++;
  };
  for (const ShockPropagation::LevelContact& lc : group) {
    const SolverContact& c = contacts[static_cast<std::size_t>(lc.index)];
    if (c.friction <= 0.0) return StickingOutcome::frictionless;
    const int slot_a = lc.a_moves ? add(c.a) : 0;
    const int slot_b = lc.b_moves ? add(c.b) : 0;
    if (slot_a < 0 || slot_b < 0) return StickingOutcome::too_large;
    if (touches_support(lc, c, gap)) ++touching[static_cast<std::size_t>(lc.a_moves ? slot_a : slot_b)];
  }
  for (int i = 0; i < count; ++i)
    if (touching[static_cast<std::size_t>(i)] < kStickingMinPoints) return StickingOutcome::too_few_points;
  return StickingOutcome::solved;
}

// The points of the group where `body` moves.
int collect_points(const SolverBodyArray& sb, std::vector<SolverContact>& contacts,
                   std::span<const ShockPropagation::LevelContact> group, int body, double gap,
                   std::array<Point, kStickingMaxPoints>& points) {
  int count = 0;
  for (std::size_t k = 0; k < group.size(); ++k) {
    const ShockPropagation::LevelContact& lc = group[k];
    SolverContact& c = contacts[static_cast<std::size_t>(lc.index)];
    const bool as_a = lc.a_moves && c.a == body, as_b = lc.b_moves && c.b == body;
    if (!as_a && !as_b) continue;
    Point& p = points[static_cast<std::size_t>(count++)];
    p.k = static_cast<int>(k);
    p.c = &c;
    p.side = as_a ? 1.0 : -1.0;
    p.W = as_a ? &c.Wa : &c.Wb;
    p.r = as_a ? &c.ra : &c.rb;
    p.link = lc.a_moves && lc.b_moves;
    p.touching = touches_support(lc, c, gap);
    p.wanted = Vec3::Zero();
    if (p.link) continue;
    // u = v_A - v_B = target n: the moving point's velocity is the frozen one's plus side target n.
    const Vec3 frozen = as_a ? sb.point_velocity(c.b, c.Wb) : sb.point_velocity(c.a, c.Wa);
    p.wanted = frozen + p.side * lc.target * c.n;
  }
  return count;
}

// One body's solve over its points: its plan and each point's total (on A), or why sticking is not
// a solution. `worst` grows to the largest distance of a touching point from its target.
StickingOutcome solve_body(const SolverBodyArray& sb, std::span<const Point> pts, BodyPlan& plan,
                           std::array<Vec3, kStickingMaxPoints>& totals, double& worst) {
  // The body's velocity y = (v, omega) that brings every touching point to its wanted velocity,
  // by least squares: G y = sum J_i^T wanted_i, G = sum J_i^T J_i.
  // (collect_bodies has checked that the body has kStickingMinPoints touching points.)
  // With W = [r]x^T, G's blocks are sums over the points of E, [r]x^T = W and
  // [r]x [r]x^T = |r|^2 E - r r^T: G follows from the count, sum r and sum r r^T,
  // summed as scalars (as 6x6 blocks summed point by point, G went through memory in pieces of
  // different sizes, and each reload waited on the stores before it: a third of the solve's time).
  int touching = 0;
  double sx = 0.0, sy = 0.0, sz = 0.0;                                    // sum r
  double sxx = 0.0, syy = 0.0, szz = 0.0, sxy = 0.0, sxz = 0.0, syz = 0.0;  // sum r r^T
  double wx = 0.0, wy = 0.0, wz = 0.0;                                    // sum wanted
  double mx = 0.0, my = 0.0, mz = 0.0;                                    // sum r x wanted (= W^T wanted)
  for (const Point& p : pts) {
    if (!p.touching) continue;
    const double x = p.r->x(), y = p.r->y(), z = p.r->z();
    const double ux = p.wanted.x(), uy = p.wanted.y(), uz = p.wanted.z();
    ++touching;
    sx += x, sy += y, sz += z;
    sxx += x * x, syy += y * y, szz += z * z, sxy += x * y, sxz += x * z, syz += y * z;
    wx += ux, wy += uy, wz += uz;
    mx += y * uz - z * uy, my += z * ux - x * uz, mz += x * uy - y * ux;
  }
  Mat6 G;
  G.topLeftCorner<3, 3>() = static_cast<double>(touching) * Mat3::Identity();
  G.topRightCorner<3, 3>() = cross_matrix(Vec3(sx, sy, sz)).transpose();
  G.bottomLeftCorner<3, 3>() = cross_matrix(Vec3(sx, sy, sz));
  G.bottomRightCorner<3, 3>() << syy + szz, -sxy, -sxz,
                                 -sxy, sxx + szz, -syz,
                                 -sxz, -syz, sxx + syy;
  Vec6 rhs;
  rhs << wx, wy, wz, mx, my, mz;
  const Eigen::LDLT<Mat6> ldlt(G);
  const Vec6 pivots = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success || !(pivots.minCoeff() > kStickingPivotRatio * pivots.maxCoeff()))
    return StickingOutcome::ill_conditioned;
  const Vec6 velocity = ldlt.solve(rhs);

  // Check it against what the passes solve: touching points at their targets, points with a gap
  // approaching no faster than the gap allows (links are checked once both bodies have moved).
  for (const Point& p : pts) {
    if (p.link) continue;
    const Vec3 point = at_point(*p.W, velocity);
    if (p.touching) {
      worst = std::max(worst, (point - p.wanted).norm());
    } else if (p.side * p.c->n.dot(point - p.wanted) < -kStickingResidual) {
      return StickingOutcome::gap_closes;
    }
  }
  if (!(worst <= kStickingResidual)) return StickingOutcome::off_target;

  // The smallest totals over the phase that give the body that velocity: the generalised impulse
  // the touching points must supply is b = M (y - y_now) + sum over every point of J_i^T Q_old_i
  // (a free point gives back what it carried), and Q_i = J_i G^-1 b is the least-norm split of b
  // over the touching points (sum J_i^T Q_i = G G^-1 b = b). Each must lie in its cone.
  const SolverBody& state = sb.state(plan.body);
  Vec6 b;
  b.head<3>() = velocity.head<3>() / state.inv_mass - state.P;
  b.tail<3>() = state.inv_inertia.inverse() * velocity.tail<3>() - state.L;
  // (Summed as two 3-vectors: built as a 6-vector per point, each went through memory in pieces
  // and the sum's reloads waited on them.)
  Vec3 given_lin = Vec3::Zero(), given_ang = Vec3::Zero();
  for (const Point& p : pts) {
    const Vec3 q = p.side * p.c->accumulated;
    given_lin += q;
    given_ang += p.W->transpose() * q;
  }
  b.head<3>() += given_lin;
  b.tail<3>() += given_ang;
  const Vec6 split = ldlt.solve(b);
  plan.P = state.P;
  plan.L = state.L;
  for (const Point& p : pts) {
    const Vec3 on_body = p.touching ? at_point(*p.W, split) : Vec3::Zero();
    Vec3& total = totals[static_cast<std::size_t>(p.k)];
    total = p.side * on_body;  // on A, as accumulated is kept
    if (p.touching && !in_cone(*p.c, total)) return StickingOutcome::outside_cone;
    // The body's momenta change by what the point's total changed (as SolverBodyArray::apply).
    const Vec3 change = on_body - p.side * p.c->accumulated;
    plan.P += change;
    plan.L += p.W->transpose() * change;
  }
  // The velocities the momenta imply: the least-squares velocity to rounding (1e-16 relative).
  plan.v = state.inv_mass * plan.P;
  plan.omega = state.inv_inertia * plan.L;
  return StickingOutcome::solved;
}

// Whether every contact between two moving bodies, free of impulse, approaches no faster than its
// target allows once both bodies have their planned velocities.
bool links_hold(const std::vector<SolverContact>& contacts, std::span<const ShockPropagation::LevelContact> group,
                std::span<const BodyPlan> plans) {
  auto plan_of = [&](int body) -> const BodyPlan& {
    for (const BodyPlan& plan : plans)
      if (plan.body == body) return plan;
    return plans[0];  // not reached: every moving body of the group has a plan
  };
  for (const ShockPropagation::LevelContact& lc : group) {
    if (!(lc.a_moves && lc.b_moves)) continue;
    const SolverContact& c = contacts[static_cast<std::size_t>(lc.index)];
    const BodyPlan& a = plan_of(c.a);
    const BodyPlan& b = plan_of(c.b);
    const Vec3 u = a.v + c.Wa * a.omega - b.v - c.Wb * b.omega;
    if (c.n.dot(u) < lc.target - kStickingResidual) return false;
  }
  return true;
}

// The direct solve with the points on a support within `gap` of touching counted as touching.
StickingOutcome solve_with_gap(SolverBodyArray& sb, std::vector<SolverContact>& contacts,
                               std::span<const ShockPropagation::LevelContact> group, double gap,
                               ImpulseCounters& counters, double& worst_residual) {
  std::array<BodyPlan, kStickingMaxBodies> plans;
  int bodies = 0;
  if (const StickingOutcome o = collect_bodies(contacts, group, gap, plans, bodies); o != StickingOutcome::solved)
    return o;
  const std::span<BodyPlan> planned(plans.data(), static_cast<std::size_t>(bodies));

  // Each body on its own (a link's total is zero: both bodies give back what it carried).
  std::array<Vec3, kStickingMaxPoints> totals;  // Eigen leaves them uninitialised
  std::fill_n(totals.begin(), group.size(), Vec3::Zero());
  std::array<Point, kStickingMaxPoints> points;
  double worst = 0.0;
  for (BodyPlan& plan : planned) {
    const int count = collect_points(sb, contacts, group, plan.body, gap, points);
    const std::span<const Point> pts(points.data(), static_cast<std::size_t>(count));
    if (const StickingOutcome o = solve_body(sb, pts, plan, totals, worst); o != StickingOutcome::solved) return o;
  }
  if (bodies > 1 && !links_hold(contacts, group, planned)) return StickingOutcome::gap_closes;

  // Commit.
  for (std::size_t k = 0; k < group.size(); ++k)
    contacts[static_cast<std::size_t>(group[k].index)].accumulated = totals[k];
  for (const BodyPlan& plan : planned) {
    SolverBody& state = sb.state(plan.body);
    state.P = plan.P;
    state.L = plan.L;
    state.v = plan.v;
    state.omega = plan.omega;
  }
  counters.normal_impulses += group.size();
  counters.friction_evaluations += group.size();
  worst_residual = worst;
  return StickingOutcome::solved;
}

}  // namespace

StickingOutcome solve_sticking_group(SolverBodyArray& sb, std::vector<SolverContact>& contacts,
                                     std::span<const ShockPropagation::LevelContact> group, bool friction,
                                     ImpulseCounters& counters, double& worst_residual) {
  if (!friction) return StickingOutcome::frictionless;
  // Touching as the passes see it first; then, if that is declined for a reason a point with a
  // gap of rounding size can cause, with such points touching (kNearTouchingGap).
  const StickingOutcome strict = solve_with_gap(sb, contacts, group, 0.0, counters, worst_residual);
  if (strict == StickingOutcome::solved || strict == StickingOutcome::too_large ||
      strict == StickingOutcome::frictionless || !any_near_touching(contacts, group, kNearTouchingGap))
    return strict;
  const StickingOutcome near = solve_with_gap(sb, contacts, group, kNearTouchingGap, counters, worst_residual);
  return near == StickingOutcome::solved ? near : strict;
}

}  // namespace boxpile
