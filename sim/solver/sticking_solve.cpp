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

// A sticking point's velocity must end this close to its target, and a free point may approach at
// most this much faster than its target allows (m/s): the passes leave a group once no impulse
// changes a velocity by more than kRestingConverged, so a direct solve held to the same bound is as
// converged as they are; the rounding of the 6x6 solve is some 1e-16 m/s per m/s of velocity.
constexpr double kStickingResidual = kRestingConverged;
// Smallest pivot of a body's 6x6 normal matrix (or of its points' impulse system), relative to its
// largest, for the solve to be well posed: points on one line leave a pivot of rounding size (1e-16
// relative), while points spread over a face leave pivots of the order of (spread / lever)^2, far
// above this.
constexpr double kStickingPivotRatio = 1e-9;
// At most this many bodies and points in a group (a Jenga layer is three blocks and some 48
// points): larger groups go to the passes, so the solve needs no heap.
constexpr int kStickingMaxBodies = 4;
constexpr int kStickingMaxPoints = 64;
// A body with this many sticking points has its velocity fixed by them (unless they are on one
// line); one with fewer is solved for its points' impulses instead (solve_body_by_impulses).
constexpr int kStickingMinPoints = 3;

// The impulse system of at most kStickingMinPoints - 1 points: at most 6 x 6, kept on the stack.
using PointsMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using PointsVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

// One point of a body as the solve sees it: its place in the group, its offset r from the body's
// centre of mass and W = [r]x^T there, the sign of the impulse on the body (+1 when it is A), the
// contact's target u_n and the velocity the point must reach, and whether it sticks (it touches a
// body that does not move, depth >= 0), is free (a gap to such a body: it carries no impulse), or
// links two moving bodies (it carries no impulse either). Left uninitialised until filled: a
// group's array of them is set up for every group of every level.
struct Point {
  int k;
  SolverContact* c;
  const Vec3* r;
  const Mat3* W;
  double side;
  double target;
  Vec3 wanted;
  bool sticks;
  bool link;
};

// A moving body's solve: its new momenta and the velocities they imply.
struct BodyPlan {
  int body = 0;
  Vec3 P = Vec3::Zero(), L = Vec3::Zero();
  Vec3 v = Vec3::Zero(), omega = Vec3::Zero();
};

// J^T q for J = [E, W]: the generalised impulse (q, r x q) of the impulse q on the body at the
// point (W^T q = r x q).
Vec6 generalised(const Mat3& W, const Vec3& q) {
  Vec6 g;
  g.head<3>() = q;
  g.tail<3>() = W.transpose() * q;
  return g;
}

// J y = y_lin + W y_ang: the velocity of the point under the body velocity y.
Vec3 at_point(const Mat3& W, const Vec6& y) { return y.head<3>() + W * y.tail<3>(); }

// Whether a total impulse on A lies in the contact's friction cone, as resting_impulse decides it.
bool in_cone(const SolverContact& c, const Vec3& J) {
  const double jn = J.dot(c.n);
  return within_cone(jn, J - jn * c.n, c.friction);
}

// Whether a point of the group sticks under the hypothesis: it joins a moving body to one that
// does not move (frozen, fixed or the ground) and touches it (depth >= 0). A point with a gap, or
// between two moving bodies, carries no impulse instead.
bool touches_support(const ShockPropagation::LevelContact& lc, const SolverContact& c) {
  return lc.a_moves != lc.b_moves && c.depth >= 0.0;
}

// The group's moving bodies, or why the solve does not take the group. Everything it declines
// here is decided from the contacts alone, before any velocity is read.
StickingOutcome collect_bodies(const std::vector<SolverContact>& contacts,
                               std::span<const ShockPropagation::LevelContact> group,
                               std::array<BodyPlan, kStickingMaxBodies>& plans, int& count) {
  if (group.size() > static_cast<std::size_t>(kStickingMaxPoints)) return StickingOutcome::too_large;
  count = 0;
  // The body's slot, or -1 when the group has more bodies than the solve holds.
  auto add = [&](int body) {
    for (int i = 0; i < count; ++i)
      if (plans[static_cast<std::size_t>(i)].body == body) return i;
    if (count == kStickingMaxBodies) return -1;
    plans[static_cast<std::size_t>(count)].body = body;
    return count++;
  };
  for (const ShockPropagation::LevelContact& lc : group) {
    const SolverContact& c = contacts[static_cast<std::size_t>(lc.index)];
    if (c.friction <= 0.0) return StickingOutcome::frictionless;
    if ((lc.a_moves && add(c.a) < 0) || (lc.b_moves && add(c.b) < 0)) return StickingOutcome::too_large;
  }
  return StickingOutcome::solved;
}

// The points of the group where `body` moves.
int collect_points(const SolverBodyArray& sb, std::vector<SolverContact>& contacts,
                   std::span<const ShockPropagation::LevelContact> group, int body,
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
    p.r = as_a ? &c.ra : &c.rb;
    p.W = as_a ? &c.Wa : &c.Wb;
    p.link = lc.a_moves && lc.b_moves;
    p.sticks = touches_support(lc, c);
    p.target = lc.target;
    p.wanted = Vec3::Zero();
    if (p.link) continue;
    // u = v_A - v_B = target n: the moving point's velocity is the frozen one's plus side target n.
    const Vec3 frozen = as_a ? sb.point_velocity(c.b, c.Wb) : sb.point_velocity(c.a, c.Wa);
    p.wanted = frozen + p.side * lc.target * c.n;
  }
  return count;
}

// Whether a point that carries nothing, with relative velocity u, stays free in the passes: it
// approaches no faster than its target allows, and a resting update there (the passes' own, with
// the K of the bodies that move) would change no velocity by more than the passes' bound. Without
// the second test a sliding point with a gap could be left free where the passes give it friction.
bool stays_free(const SolverContact& c, const Vec3& u, double target, bool a_moves, bool b_moves) {
  if (c.n.dot(u) < target - kStickingResidual) return false;
  SolverContact trial = c;
  trial.accumulated = Vec3::Zero();
  if (!(a_moves && b_moves)) set_collision_matrix(trial, a_moves, b_moves);  // a link keeps Ka + Kb
  ImpulseCounters uncounted;
  const Vec3 j = resting_impulse(trial, u, target, true, uncounted);
  return (trial.K * j).norm() <= kStickingResidual;
}

// Whether the body moving at `velocity` brings its sticking points to their targets and leaves each
// of its free points free (stays_free; links are checked once both bodies have moved). `worst` grows
// to the largest distance of a sticking point from its target.
StickingOutcome check_targets(std::span<const Point> pts, const Vec6& velocity, double& worst) {
  for (const Point& p : pts) {
    if (p.link) continue;
    const Vec3 point = at_point(*p.W, velocity);
    if (p.sticks) {
      worst = std::max(worst, (point - p.wanted).norm());
    } else {
      // u = v_A - v_B = side (point - frozen point), and wanted = frozen point + side target n.
      const Vec3 u = p.side * (point - p.wanted) + p.target * p.c->n;
      if (!stays_free(*p.c, u, p.target, p.side > 0.0, p.side < 0.0)) return StickingOutcome::gap_closes;
    }
  }
  return worst <= kStickingResidual ? StickingOutcome::solved : StickingOutcome::off_target;
}

// Sets each point's total (on A) from the impulse `impulse_on_body(p, k)` on the body at p, its k-th
// sticking point, zero at the others, and the body's plan: its momenta change by what the totals
// changed (as SolverBodyArray::apply), its velocities are those the momenta imply. Returns whether
// every sticking point's total lies in its friction cone.
template <class ImpulseOnBody>
bool plan_from_impulses(const SolverBody& state, std::span<const Point> pts, ImpulseOnBody impulse_on_body,
                        BodyPlan& plan, std::array<Vec3, kStickingMaxPoints>& totals) {
  plan.P = state.P;
  plan.L = state.L;
  int sticking = 0;
  bool in_cones = true;
  for (const Point& p : pts) {
    const Vec3 on_body = p.sticks ? impulse_on_body(p, sticking++) : Vec3::Zero();
    Vec3& total = totals[static_cast<std::size_t>(p.k)];
    total = p.side * on_body;  // on A, as accumulated is kept
    in_cones = in_cones && (!p.sticks || in_cone(*p.c, total));
    const Vec3 change = on_body - p.side * p.c->accumulated;
    plan.P += change;
    plan.L += p.W->transpose() * change;
  }
  plan.v = state.inv_mass * plan.P;
  plan.omega = state.inv_inertia * plan.L;
  return in_cones;
}

// A body with kStickingMinPoints or more sticking points, not on one line: the points fix its
// velocity, and the impulses are the least-norm split of what that velocity takes.
StickingOutcome solve_body_by_velocity(const SolverBodyArray& sb, std::span<const Point> pts, BodyPlan& plan,
                                       std::array<Vec3, kStickingMaxPoints>& totals, double& worst) {
  // The body's velocity y = (v, omega) that brings every sticking point to its wanted velocity,
  // by least squares: G y = sum J_i^T wanted_i, G = sum J_i^T J_i.
  Mat6 G = Mat6::Zero();
  Vec6 rhs = Vec6::Zero();
  for (const Point& p : pts) {
    if (!p.sticks) continue;
    const Mat3& W = *p.W;
    G.topLeftCorner<3, 3>() += Mat3::Identity();
    G.topRightCorner<3, 3>() += W;
    G.bottomRightCorner<3, 3>() += W.transpose() * W;
    rhs += generalised(W, p.wanted);
  }
  G.bottomLeftCorner<3, 3>() = G.topRightCorner<3, 3>().transpose();
  const Eigen::LDLT<Mat6> ldlt(G);
  const Vec6 pivots = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success || !(pivots.minCoeff() > kStickingPivotRatio * pivots.maxCoeff()))
    return StickingOutcome::ill_conditioned;
  const Vec6 velocity = ldlt.solve(rhs);
  if (const StickingOutcome o = check_targets(pts, velocity, worst); o != StickingOutcome::solved) return o;

  // The smallest totals over the phase that give the body that velocity: the generalised impulse
  // the sticking points must supply is b = M (y - y_now) + sum over every point of J_i^T Q_old_i
  // (a free point gives back what it carried), and Q_i = J_i G^-1 b is the least-norm split of b
  // over the sticking points (sum J_i^T Q_i = G G^-1 b = b). Each must lie in its cone. The
  // velocities the momenta then imply are the least-squares velocity to rounding (1e-16 relative).
  const SolverBody& state = sb.state(plan.body);
  Vec6 b;
  b.head<3>() = velocity.head<3>() / state.inv_mass - state.P;
  b.tail<3>() = state.inv_inertia.inverse() * velocity.tail<3>() - state.L;
  for (const Point& p : pts) b += generalised(*p.W, p.side * p.c->accumulated);
  const Vec6 split = ldlt.solve(b);
  auto impulse_on_body = [&](const Point& p, int) { return at_point(*p.W, split); };
  if (!plan_from_impulses(state, pts, impulse_on_body, plan, totals)) return StickingOutcome::outside_cone;
  return StickingOutcome::solved;
}

// A body with one or two sticking points: they leave its velocity free in some directions (it can
// turn about the point, or about the line through the two), but they fix the impulses that bring
// them to their targets. With y_free the body's velocity once every point has given back its
// total, the impulses Q on the body at the sticking points solve the points' Delassus system
//
//     A Q = c,   A_ij = J_i M^-1 J_j^T = (1/m) E + W_i I^-1 W_j^T,   c_i = wanted_i - J_i y_free
//
// (A_ii is the body's share of the contact's K). One point: A is that K, positive definite. Two
// points: equal and opposite impulses along the line between them, (d, -d) with d = r_1 - r_2,
// move neither point (d x d = 0), so A is singular there, and the passes' fixed points differ only
// by such a squeeze. The least-norm solution, the one without it, solves (A + a N N^T) Q = c with N
// the squeeze's unit vector (a, A's mean diagonal, keeps the scale); the body's velocity is the
// same for every solution and is checked against the targets as any other. No sticking point: the
// body keeps y_free.
StickingOutcome solve_body_by_impulses(const SolverBodyArray& sb, std::span<const Point> pts, int sticking,
                                       BodyPlan& plan, std::array<Vec3, kStickingMaxPoints>& totals,
                                       double& worst) {
  const SolverBody& state = sb.state(plan.body);
  std::array<const Point*, kStickingMinPoints - 1> held;
  Vec3 P_free = state.P, L_free = state.L;
  int count = 0;
  for (const Point& p : pts) {
    if (p.sticks) held[static_cast<std::size_t>(count++)] = &p;
    const Vec3 carried = p.side * p.c->accumulated;
    P_free -= carried;
    L_free -= p.W->transpose() * carried;
  }
  Vec6 free_velocity;
  free_velocity.head<3>() = state.inv_mass * P_free;
  free_velocity.tail<3>() = state.inv_inertia * L_free;

  const int size = 3 * sticking;
  PointsVec Q(size);
  if (sticking > 0) {
    PointsMat A(size, size);
    PointsVec c(size);
    for (int i = 0; i < sticking; ++i) {
      const Point& pi = *held[static_cast<std::size_t>(i)];
      c.segment<3>(3 * i) = pi.wanted - at_point(*pi.W, free_velocity);
      for (int j = 0; j < sticking; ++j) {
        const Mat3& Wj = *held[static_cast<std::size_t>(j)]->W;
        A.block<3, 3>(3 * i, 3 * j) = state.inv_mass * Mat3::Identity() + *pi.W * state.inv_inertia * Wj.transpose();
      }
    }
    if (sticking == 2) {
      const Vec3 d = *held[0]->r - *held[1]->r;
      if (!(d.norm() > 0.0)) return StickingOutcome::ill_conditioned;
      PointsVec squeeze(size);
      squeeze << d, -d;
      squeeze.normalize();
      A += (A.trace() / size) * squeeze * squeeze.transpose();
    }
    const Eigen::LDLT<PointsMat> ldlt(A);
    const PointsVec pivots = ldlt.vectorD().cwiseAbs();
    if (ldlt.info() != Eigen::Success || !(pivots.minCoeff() > kStickingPivotRatio * pivots.maxCoeff()))
      return StickingOutcome::ill_conditioned;
    Q = ldlt.solve(c);
  }
  auto impulse_on_body = [&](const Point&, int k) { return Vec3(Q.segment<3>(3 * k)); };
  const bool in_cones = plan_from_impulses(state, pts, impulse_on_body, plan, totals);
  Vec6 velocity;
  velocity << plan.v, plan.omega;
  if (const StickingOutcome o = check_targets(pts, velocity, worst); o != StickingOutcome::solved) return o;
  return in_cones ? StickingOutcome::solved : StickingOutcome::outside_cone;
}

// One body's solve over its points: its plan and each point's total (on A), or why sticking is not
// a solution, by whichever of the two forms the number of its sticking points allows. `worst` grows
// to the largest distance of a sticking point from its target.
StickingOutcome solve_body(const SolverBodyArray& sb, std::span<const Point> pts, BodyPlan& plan,
                           std::array<Vec3, kStickingMaxPoints>& totals, double& worst) {
  const int sticking = static_cast<int>(std::count_if(pts.begin(), pts.end(), [](const Point& p) { return p.sticks; }));
  if (sticking >= kStickingMinPoints) return solve_body_by_velocity(sb, pts, plan, totals, worst);
  return solve_body_by_impulses(sb, pts, sticking, plan, totals, worst);
}

// Whether every contact between two moving bodies, free of impulse, stays free once both bodies have
// their planned velocities.
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
    if (!stays_free(c, u, lc.target, true, true)) return false;
  }
  return true;
}

}  // namespace

StickingOutcome solve_sticking_group(SolverBodyArray& sb, std::vector<SolverContact>& contacts,
                                     std::span<const ShockPropagation::LevelContact> group, bool friction,
                                     ImpulseCounters& counters, double& worst_residual) {
  if (!friction) return StickingOutcome::frictionless;
  std::array<BodyPlan, kStickingMaxBodies> plans;
  int bodies = 0;
  if (const StickingOutcome o = collect_bodies(contacts, group, plans, bodies); o != StickingOutcome::solved) return o;
  const std::span<BodyPlan> planned(plans.data(), static_cast<std::size_t>(bodies));

  // Each body on its own (a link's total is zero: both bodies give back what it carried).
  std::array<Vec3, kStickingMaxPoints> totals;  // Eigen leaves them uninitialised
  std::fill_n(totals.begin(), group.size(), Vec3::Zero());
  std::array<Point, kStickingMaxPoints> points;
  double worst = 0.0;
  for (BodyPlan& plan : planned) {
    const int count = collect_points(sb, contacts, group, plan.body, points);
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

}  // namespace boxpile
