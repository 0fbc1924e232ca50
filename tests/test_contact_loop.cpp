// The contact loop (sim/solver/contact_loop.cpp) takes the lab text's "remaining non-separating
// contacts": a point that separates when the loop begins, by more than rounding, takes no part,
// and a point at rest stays in whatever the sign of its rounding. Two unit boxes built by hand, box
// 1 on box 0 on the ground, each touching at the four corners of its face.
#include <catch2/catch.hpp>

#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/sim/solver/contact_loop.hpp"
#include "boxpile/sim/solver/impulse.hpp"
#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/solver/solver_body.hpp"
#include "boxpile/sim/solver/step_context.hpp"

using namespace boxpile;

namespace {

constexpr double kDt = 1.0 / 240.0;
constexpr double kFall = 9.81 * kDt;  // m/s: what gravity adds in a step, the loop's start

// Box 0 at rest on the ground and (with `boxes` = 2) box 1 on it, both falling at g dt as the loop
// finds them after gravity; box 1 moves up relative to box 0 by `upward` (m/s) more.
struct TwoBoxes {
  Scene scene;
  std::vector<RigidBody> bodies;
  RigidBody ground;
  std::vector<BodyContact> found;  // not read by the loop
  std::vector<WireJoint> wires;
  WorldCounters counters;
  StepStats stats;
  std::vector<CollisionEvent> events;
  std::vector<SolverContact> contacts;
  SolverBodyArray resting;
  ContactLoop loop;

  explicit TwoBoxes(double upward, int boxes = 2) {
    ground.fixed = true;
    ground.update_derived();
    for (int k = 0; k < boxes; ++k) {
      const Vec3 v(0.0, 0.0, -kFall + (k == 1 ? upward : 0.0));
      bodies.push_back(make_body("box", {BoxShape{Vec3(0.5, 0.5, 0.5), Vec3::Zero(), Quat::Identity()}}, 1.0,
                                 Pose{Vec3(0.0, 0.0, 0.5 + k), Quat::Identity()}, v, Vec3::Zero(), Material{}, false));
      for (const double x : {-0.5, 0.5})
        for (const double y : {-0.5, 0.5}) touch(k, k == 0 ? kGround : 0, Vec3(x, y, k));
    }
    const StepStorage storage{bodies.size()};
    resting.reserve(bodies.size());
    loop.reserve(storage);
  }

  // A point of body a on body b at `point`, normal +z, touching (depth 0), set up as the method
  // prepares its solver contacts.
  void touch(int a, int b, const Vec3& point) {
    const RigidBody& body_b = b == kGround ? ground : bodies[static_cast<std::size_t>(b)];
    SolverContact& c = contacts.emplace_back();
    c.a = a;
    c.b = b;
    c.n = Vec3::UnitZ();
    c.ra = point - bodies[static_cast<std::size_t>(a)].x;
    c.rb = point - body_b.x;
    c.Wa = cross_matrix(c.ra).transpose();
    c.Wb = cross_matrix(c.rb).transpose();
    c.friction = scene.material.friction;
    c.Ka = collision_matrix_share(bodies[static_cast<std::size_t>(a)], c.ra);
    if (b != kGround) c.Kb = collision_matrix_share(body_b, c.rb);
    set_collision_matrix(c, Mat3(c.Ka + c.Kb));
  }

  // Runs the loop; returns the resting updates it made.
  std::uint64_t run() {
    StepContext ctx{scene, bodies, ground, found, wires, 0.0, kDt, counters, stats, events};
    ImpulseStep step{ctx, SolverBodies{bodies, ground}, resting, contacts};
    loop.run(step);
    return counters.impulses.normal_impulses;
  }
};

}  // namespace

TEST_CASE("the contact loop leaves out points that separate and keeps points at rest", "[solver][contact-loop]") {
  const auto passes = static_cast<std::uint64_t>(Scene{}.solver.contact_passes);
  // Box 0 alone on the ground: what the loop makes of it when nothing else takes part. (Ten passes
  // of the ramp do not stop it, 1e-3 m/s remain: shock propagation, which follows, does.)
  TwoBoxes alone(0.0, 1);
  REQUIRE(alone.run() == passes * 4);
  const Vec3 v_alone = alone.bodies[0].v, omega_alone = alone.bodies[0].omega;
  CHECK(v_alone.z() > -kFall / 10.0);  // slowed to a tenth of its fall at least

  SECTION("box 1 lifting off box 0 at 1 cm/s: its four points take no part") {
    TwoBoxes s(0.01);
    CHECK(s.run() == passes * 4);
    // Box 1 keeps its velocity, and box 0 ends as it does alone, both to the bit.
    CHECK(s.bodies[1].v == Vec3(0.0, 0.0, -kFall + 0.01));
    CHECK(s.bodies[1].omega == Vec3::Zero());
    CHECK(s.bodies[0].v == v_alone);
    CHECK(s.bodies[0].omega == omega_alone);
  }
  SECTION("box 1 separating from box 0 by rounding only: all eight points are solved, as at rest") {
    TwoBoxes rest(0.0);
    CHECK(rest.run() == passes * 8);
    CHECK(rest.bodies[0].v != v_alone);  // box 1's weight reaches box 0 through its points
    // 1e-9 m/s is below kRestingSpeed: box 1 is at rest on box 0, and the loop ends as it does for
    // a box 1 at rest, to within the rounding-size start (1e-9 m/s, times the ramp's few passes).
    constexpr double kRoundingStart = 1e-9;  // m/s
    TwoBoxes s(kRoundingStart);
    CHECK(s.run() == passes * 8);
    for (int k = 0; k < 2; ++k) {
      CHECK((s.bodies[k].v - rest.bodies[k].v).norm() < 10 * kRoundingStart);
      CHECK((s.bodies[k].omega - rest.bodies[k].omega).norm() < 10 * kRoundingStart);
    }
  }
}
