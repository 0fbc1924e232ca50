// The direct solve of a shock-propagation group whose touching points all stick
// (sticking_solve.hpp): where it accepts, it must give what many projected Gauss-Seidel passes
// converge to; where sticking is not the answer (a slope steeper than the friction angle, targets no
// rigid motion meets, points on a line, a link between two moving bodies that would close), it must
// leave the group to the passes.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <random>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/solver/impulse.hpp"
#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/solver/sticking_solve.hpp"
#include "boxpile/sim/solver/solver_body.hpp"
#include "boxpile/sim/solver/impulse_method.hpp"
#include "boxpile/sim/world.hpp"

using namespace boxpile;

namespace {

constexpr double kFriction = 0.5;
constexpr double kDt = 1.0 / 240.0;
constexpr double kGravity = 9.81;

RigidBody box(const Vec3& centre, const Vec3& half, double mass, const Vec3& v, const Vec3& omega) {
  return make_body("box", {BoxShape{half, Vec3::Zero(), Quat::Identity()}}, mass, Pose{centre, Quat::Identity()}, v,
                   omega, Material{}, false);
}

// Moving bodies (the first `moving` of `bodies`) on the ground or on frozen bodies (the rest), with
// their contacts as a level of shock propagation sees them.
struct Group {
  std::vector<RigidBody> bodies;
  int moving = 1;
  std::vector<SolverContact> contacts;
  std::vector<ShockPropagation::LevelContact> level;
  SolverBodyArray sb;

  // A point of body `a` on body `b` (kGround or another body) with normal n from b to a.
  void touch(const Vec3& point, const Vec3& n, int b, double depth = 0.0, int a = 0) {
    SolverContact c;
    c.a = a;
    c.b = b;
    c.n = n;
    c.ra = point - bodies[static_cast<std::size_t>(a)].x;
    c.rb = b == kGround ? point : Vec3(point - bodies[static_cast<std::size_t>(b)].x);
    c.Wa = cross_matrix(c.ra).transpose();
    c.Wb = cross_matrix(c.rb).transpose();
    const bool b_moves = b != kGround && b < moving;
    ContactMatrices m;
    m.Ka = collision_matrix_share(bodies[static_cast<std::size_t>(a)], c.ra);
    if (b_moves) m.Kb = collision_matrix_share(bodies[static_cast<std::size_t>(b)], c.rb);
    c.depth = depth;
    c.friction = kFriction;
    set_collision_matrix(c, m, true, b_moves);
    contacts.push_back(c);
    level.push_back({static_cast<int>(contacts.size()) - 1, true, b_moves, 0.0});
  }
  // Gathers the bodies and sets each point's target as shock propagation does (frozen_target,
  // allow_gap) and begins the resting phase.
  void begin() {
    sb.gather(bodies);
    for (ShockPropagation::LevelContact& lc : level) {
      SolverContact& c = contacts[static_cast<std::size_t>(lc.index)];
      const double frozen = lc.b_moves ? 0.0 : std::min(0.0, -c.n.dot(sb.point_velocity(c.b, c.Wb)));
      lc.target = allow_gap(c, frozen, kDt);
      begin_resting_phase(c, sb.relative_velocity(c));
    }
  }
  // Many passes of the resting impulse, as the passes of shock propagation run them.
  void passes(int count) {
    ImpulseCounters counters;
    for (int k = 0; k < count; ++k)
      for (const ShockPropagation::LevelContact& lc : level) {
        SolverContact& c = contacts[static_cast<std::size_t>(lc.index)];
        sb.apply(c, resting_impulse(c, sb.relative_velocity(c), lc.target, true, counters), lc.a_moves, lc.b_moves);
      }
  }
  StickingOutcome direct(double& residual) {
    ImpulseCounters counters;
    return solve_sticking_group(sb, contacts, level, true, counters, residual);
  }
};

// A 1 x 0.6 x 0.4 m box of 2 kg on the ground, falling and sliding a little at the start of the
// resting phase, touching at its four bottom corners.
Group box_on_ground(const Vec3& n, const Vec3& v, const Vec3& omega) {
  Group g;
  g.bodies.push_back(box(Vec3(0.0, 0.0, 0.2), Vec3(0.5, 0.3, 0.2), 2.0, v, omega));
  for (const double x : {-0.5, 0.5})
    for (const double y : {-0.3, 0.3}) g.touch(Vec3(x, y, 0.0), n, kGround);
  return g;
}

Vec3 velocity(const Group& g, int body = 0) { return g.sb.state(body).v; }
Vec3 spin(const Group& g, int body = 0) { return g.sb.state(body).omega; }

// Every point with an impulse carries it inside the friction cone.
void check_in_cones(const Group& g) {
  for (const SolverContact& c : g.contacts) {
    const double jn = c.accumulated.dot(c.n);
    CHECK(jn >= 0.0);
    CHECK((c.accumulated - jn * c.n).norm() <= kFriction * jn * (1.0 + 1e-12));
  }
}

// Begins `g`'s resting phase and solves it directly, which must take it, and checks that it ends
// with the velocities 2,000 passes from the same start converge to, its residual within the
// passes' bound.
void solve_as_the_passes_do(Group& g) {
  Group passes = g;
  passes.begin();
  g.begin();
  passes.passes(2000);
  double residual = -1.0;
  REQUIRE(g.direct(residual) == StickingOutcome::solved);
  CHECK(residual <= kRestingConverged);
  CHECK((velocity(g) - velocity(passes)).norm() < 1e-10);
  CHECK((spin(g) - spin(passes)).norm() < 1e-10);
}

// Steps the world `steps` times and counts the steps whose shock propagation ran passes: a step
// whose every group was solved directly counts one pass per level and no more.
int steps_with_passes(World& w, int steps) {
  int count = 0;
  for (int k = 0; k < steps; ++k) {
    w.step();
    const ImpulseStepStats& st = w.method_as<ImpulseMethod>()->last_step_stats();
    if (st.shock_pass_count != 1 || st.shock_passes_used != st.shock_levels) ++count;
  }
  return count;
}

// Every body at rest to rounding (1e-12 m/s, the passes' convergence bound).
void check_at_rest(const World& w) {
  for (const RigidBody& b : w.bodies()) CHECK(b.v.norm() < 1e-12);
}

}  // namespace

TEST_CASE("a box landing on the ground: the direct solve gives the passes' velocity", "[solver][sticking]") {
  const Vec3 v(0.1, -0.05, -0.5), omega(0.2, -0.3, 0.1);
  Group passes = box_on_ground(Vec3::UnitZ(), v, omega);
  Group direct = passes;
  passes.begin();
  direct.begin();
  const Vec3 P_before = direct.sb.state(0).P;
  passes.passes(2000);
  double residual = -1.0;
  REQUIRE(direct.direct(residual) == StickingOutcome::solved);
  // Sticking on the ground leaves the box at rest: both to rounding (1e-10 m/s, far below any
  // velocity of the step).
  CHECK((velocity(direct) - velocity(passes)).norm() < 1e-10);
  CHECK((spin(direct) - spin(passes)).norm() < 1e-10);
  CHECK(velocity(direct).norm() < 1e-12);
  CHECK(spin(direct).norm() < 1e-12);
  CHECK(residual <= kRestingConverged);
  check_in_cones(direct);
  // The impulses are what changed the body's momentum.
  Vec3 total = Vec3::Zero();
  for (const SolverContact& c : direct.contacts) total += c.accumulated;
  CHECK((direct.sb.state(0).P - P_before - total).norm() < 1e-12);
}

TEST_CASE("a box on a moving frozen box follows it as the passes do", "[solver][sticking]") {
  // The lower box sinks, turns and slides a little (frozen: infinite mass for this level); the
  // upper box, falling onto it, must end moving with its four points.
  Group g;
  g.bodies.push_back(box(Vec3(0.05, 0.02, 0.6), Vec3(0.4, 0.25, 0.2), 3.0, Vec3(0.02, 0.0, -0.2), Vec3(0.0, 0.05, 0.0)));
  g.bodies.push_back(box(Vec3(0.0, 0.0, 0.2), Vec3(0.5, 0.3, 0.2), 2.0, Vec3(0.01, -0.02, -0.03),
                         Vec3(0.0, 0.0, 0.02)));
  for (const double x : {-0.35, 0.45})
    for (const double y : {-0.23, 0.27}) g.touch(Vec3(x, y, 0.4), Vec3::UnitZ(), 1);
  solve_as_the_passes_do(g);
  for (const SolverContact& c : g.contacts) CHECK(g.sb.relative_velocity(c).norm() < 1e-12);
  check_in_cones(g);
}

TEST_CASE("a box on a slope sticks when tan(theta) < mu and is left to the passes when steeper", "[solver][sticking]") {
  // One step of gravity, g dt downward, must be taken out by the slope's impulse: its tangential
  // part over its normal part is tan(theta).
  const double friction_angle = std::atan(kFriction);
  for (const double theta : {friction_angle - 0.05, friction_angle + 0.05}) {
    const Vec3 n(std::sin(theta), 0.0, std::cos(theta));
    Group g = box_on_ground(n, Vec3(0.0, 0.0, -kGravity * kDt), Vec3::Zero());
    g.begin();
    double residual = -1.0;
    const StickingOutcome outcome = g.direct(residual);
    if (theta < friction_angle) {
      REQUIRE(outcome == StickingOutcome::solved);
      CHECK(velocity(g).norm() < 1e-12);
      check_in_cones(g);
    } else {
      CHECK(outcome == StickingOutcome::outside_cone);
      // Nothing changed: the passes take the group from where it was.
      CHECK((velocity(g) - Vec3(0.0, 0.0, -kGravity * kDt)).norm() == 0.0);
      for (const SolverContact& c : g.contacts) CHECK(c.accumulated.isZero(0.0));
    }
  }
}

TEST_CASE("the direct solve leaves to the passes what sticking cannot solve", "[solver][sticking]") {
  double residual = -1.0;
  SECTION("a box pushed sideways faster than friction can stop") {
    Group g = box_on_ground(Vec3::UnitZ(), Vec3(2.0, 0.0, -0.1), Vec3::Zero());
    g.begin();
    CHECK(g.direct(residual) == StickingOutcome::outside_cone);
  }
  SECTION("targets no rigid motion meets: one corner pushed out") {
    Group g = box_on_ground(Vec3::UnitZ(), Vec3(0.0, 0.0, -0.1), Vec3::Zero());
    g.begin();
    g.level[0].target = 0.01;
    CHECK(g.direct(residual) == StickingOutcome::off_target);
  }
  SECTION("a box on an edge: two points") {
    Group g;
    g.bodies.push_back(box(Vec3(0.0, 0.0, 0.2), Vec3(0.5, 0.3, 0.2), 2.0, Vec3(0.0, 0.0, -0.1), Vec3::Zero()));
    for (const double y : {-0.3, 0.3}) g.touch(Vec3(0.5, y, 0.0), Vec3::UnitZ(), kGround);
    g.begin();
    CHECK(g.direct(residual) == StickingOutcome::too_few_points);
  }
  SECTION("three points on one edge") {
    Group g;
    g.bodies.push_back(box(Vec3(0.0, 0.0, 0.2), Vec3(0.5, 0.3, 0.2), 2.0, Vec3(0.0, 0.0, -0.1), Vec3::Zero()));
    for (const double y : {-0.3, 0.0, 0.3}) g.touch(Vec3(0.5, y, 0.0), Vec3::UnitZ(), kGround);
    g.begin();
    CHECK(g.direct(residual) == StickingOutcome::ill_conditioned);
  }
  SECTION("a point with a gap carries nothing and the touching ones hold the box") {
    Group g = box_on_ground(Vec3::UnitZ(), Vec3(0.0, 0.0, -0.1), Vec3::Zero());
    g.touch(Vec3(0.0, 0.3, 0.1), -Vec3::UnitY(), kGround, -0.01);  // 1 cm from a wall
    g.begin();
    REQUIRE(g.direct(residual) == StickingOutcome::solved);
    CHECK(g.contacts.back().accumulated.isZero(0.0));
    CHECK(velocity(g).norm() < 1e-12);
  }
}

TEST_CASE("two boxes side by side: each sticks to its support and their link stays free", "[solver][sticking]") {
  // Two boxes landing on the ground touching each other face to face (a Jenga layer's blocks):
  // solved directly, both end at rest as the passes leave them, and the face between them carries
  // nothing.
  auto make = [](const Vec3& v1) {
    Group g;
    g.moving = 2;
    g.bodies.push_back(box(Vec3(0.0, 0.0, 0.2), Vec3(0.5, 0.3, 0.2), 2.0, Vec3(0.0, 0.0, -0.1), Vec3(0.1, 0.0, 0.0)));
    g.bodies.push_back(box(Vec3(0.0, 0.6, 0.2), Vec3(0.5, 0.3, 0.2), 2.0, v1, Vec3::Zero()));
    g.bodies.push_back(box(Vec3(0.0, 0.6, -0.2), Vec3(0.5, 0.3, 0.2), 2.0, Vec3(0.0, -0.5, 0.0), Vec3::Zero()));
    for (const double x : {-0.5, 0.5})
      for (const double y : {-0.3, 0.3}) g.touch(Vec3(x, y, 0.0), Vec3::UnitZ(), kGround);
    for (const double x : {-0.5, 0.5})
      for (const double z : {0.05, 0.35}) g.touch(Vec3(x, 0.3, z), Vec3::UnitY(), 0, 0.0, 1);  // 1 on 0
    return g;
  };
  double residual = -1.0;
  SECTION("both on the ground") {
    Group g = make(Vec3(0.0, 0.0, -0.2));
    for (const double x : {-0.5, 0.5})
      for (const double y : {0.3, 0.9}) g.touch(Vec3(x, y, 0.0), Vec3::UnitZ(), kGround, 0.0, 1);
    Group passes = g;
    passes.begin();
    g.begin();
    passes.passes(2000);
    REQUIRE(g.direct(residual) == StickingOutcome::solved);
    for (const int body : {0, 1}) {
      CHECK((velocity(g, body) - velocity(passes, body)).norm() < 1e-10);
      CHECK((spin(g, body) - spin(passes, body)).norm() < 1e-10);
      CHECK(velocity(g, body).norm() < 1e-12);
    }
    for (std::size_t k = 4; k < 8; ++k) CHECK(g.contacts[k].accumulated.isZero(0.0));
    check_in_cones(g);
  }
  SECTION("one of them on a frozen box that carries it into the other") {
    // Body 1, landing on body 2, sticks to it; body 2 slides toward body 0 at 0.5 m/s, so the
    // face between 1 and 0 would close: the passes must solve it.
    Group g = make(Vec3(0.0, -0.5, -0.05));
    for (const double x : {-0.5, 0.5})
      for (const double y : {0.3, 0.9}) g.touch(Vec3(x, y, 0.0), Vec3::UnitZ(), 2, 0.0, 1);
    g.begin();
    const Vec3 before = velocity(g, 1);
    CHECK(g.direct(residual) == StickingOutcome::gap_closes);
    CHECK(velocity(g, 1) == before);
  }
}

TEST_CASE("points a rounding away from touching count as touching when the group needs them", "[solver][sticking]") {
  // A box on the ground whose two corners on one side lie 1e-15 m above it (rounding of a resting
  // face): touching as the passes see it, the box stands on two points and cannot stick; with the
  // near points touching it does, and the solve gives what the passes converge to.
  const Vec3 v(0.0, 0.0, -0.04), omega(0.0, 0.0, 0.0);
  Group g;
  g.bodies.push_back(box(Vec3(0.0, 0.0, 0.2), Vec3(0.5, 0.3, 0.2), 2.0, v, omega));
  for (const double x : {-0.5, 0.5})
    for (const double y : {-0.3, 0.3}) g.touch(Vec3(x, y, 0.0), Vec3::UnitZ(), kGround, x < 0.0 ? -1e-15 : 0.0);
  solve_as_the_passes_do(g);
  check_in_cones(g);

  SECTION("a gap far beyond rounding is not closed") {
    // The same box with those corners 1 mm up: it rests on two points, and the passes solve it.
    Group far;
    far.bodies.push_back(box(Vec3(0.0, 0.0, 0.2), Vec3(0.5, 0.3, 0.2), 2.0, v, omega));
    for (const double x : {-0.5, 0.5})
      for (const double y : {-0.3, 0.3}) far.touch(Vec3(x, y, 0.0), Vec3::UnitZ(), kGround, x < 0.0 ? -1e-3 : 0.0);
    far.begin();
    const Vec3 before = velocity(far);
    double residual = -1.0;
    CHECK(far.direct(residual) == StickingOutcome::too_few_points);
    CHECK(velocity(far) == before);
  }
}

TEST_CASE("every layer of the resting Jenga tower is solved directly at every step", "[solver][sticking]") {
  // Each shock level of the tower is one layer of three blocks on the layer below. Rounding leaves
  // some of a block's points on the blocks below 1e-16 to 1e-13 m apart: counted as gaps, they
  // left a block too few points or points on a line, and 13% of the layers went to the passes.
  World w(load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/hard/jenga.json"));
  CHECK(steps_with_passes(w, 480) == 0);
  CHECK(w.method_as<ImpulseMethod>()->last_step_stats().shock_levels == 18);
  check_at_rest(w);
}

TEST_CASE("a resting stack's shock levels are each solved directly in one pass", "[solver][sticking]") {
  // Each level of a stack at rest is one box on the frozen box below, every corner sticking: the
  // direct solve takes it (one pass per level, its residual within the passes' bound), and the
  // stack keeps nothing of its velocity.
  World w(load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/stack_10.json"));
  for (int k = 0; k < 240; ++k) w.step();
  const ImpulseStepStats& st = w.method_as<ImpulseMethod>()->last_step_stats();
  CHECK(st.shock_levels == 10);
  CHECK(st.shock_passes_used == 10);
  CHECK(st.shock_pass_count == 1);
  CHECK(st.shock_change[0] <= kRestingConverged);
  check_at_rest(w);
}

TEST_CASE("every group of a resting pyramid on corners is solved directly at every step", "[solver][sticking]") {
  // The 21-box pyramid of the sweeps and the lab report: each box stands on the corners of the
  // boxes below. Every group of every level sticks, so the direct solve takes them all, each level
  // in one pass, at every step of its settling (a solve whose rounding or conditioning test
  // declined 6% of these groups let the passes run 27 per step instead of 6, and the pyramid
  // crept at dt = 1/60 with few shock passes). The lab report's settings, whose longer contact
  // loop leaves the groups nearest their cones' edges.
  Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/pyramid.json");
  scene.solver.collision_passes = 10;
  scene.solver.contact_passes = 20;
  scene.solver.shock_passes = 20;
  World w(scene);
  CHECK(steps_with_passes(w, 600) == 0);
  CHECK(w.method_as<ImpulseMethod>()->last_step_stats().shock_levels == 6);
  check_at_rest(w);
}
