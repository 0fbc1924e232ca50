// Penetration recovery (sim/solver/recovery.cpp) on a stack of three unit boxes, built by hand so
// that each shock level's phase can be followed: a phase none of whose contacts can change is
// skipped whole, and skipping it must give the very pseudo-velocities its run would.
#include <catch2/catch.hpp>

#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/sim/solver/impulse.hpp"
#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/solver/recovery.hpp"
#include "boxpile/sim/solver/shock_propagation.hpp"
#include "boxpile/sim/solver/solver_body.hpp"
#include "boxpile/sim/solver/step_context.hpp"

using namespace boxpile;

namespace {

constexpr double kDt = 1.0 / 240.0;

// Three unit boxes of 1 kg at rest, box k centred at height 0.5 + k less the overlap below it
// (`overlap[k]`, m, with the ground for box 0), touching at the four corners of each face they
// share; each step's stages are the method's own (shock propagation, then recovery).
struct Stack {
  Scene scene;
  std::vector<RigidBody> bodies;
  RigidBody ground;
  std::vector<BodyContact> found;  // not read by the stages under test
  std::vector<char> same;          // nor this
  std::vector<WireJoint> wires;
  WorldCounters counters;
  ImpulseCounters impulses;
  ImpulseStepStats stats;
  std::vector<CollisionEvent> events;
  ThreadPool pool{1};
  std::vector<SolverContact> contacts;
  std::vector<ContactMatrices> matrices;  // beside contacts, as the method keeps them
  SolverBodyArray resting;
  ShockPropagation shock;
  PenetrationRecovery recovery;

  explicit Stack(const std::vector<double>& overlap) {
    ground.fixed = true;
    ground.update_derived();
    double bottom = 0.0;  // the face the next box stands on
    for (const double o : overlap) {
      const Vec3 centre(0.0, 0.0, bottom - o + 0.5);
      bodies.push_back(make_body("box", {BoxShape{Vec3(0.5, 0.5, 0.5), Vec3::Zero(), Quat::Identity()}}, 1.0,
                                 Pose{centre, Quat::Identity()}, Vec3::Zero(), Vec3::Zero(), Material{}, false));
      const int a = static_cast<int>(bodies.size()) - 1;
      for (const double x : {-0.5, 0.5})
        for (const double y : {-0.5, 0.5}) touch(a, a - 1 < 0 ? kGround : a - 1, Vec3(x, y, bottom - o / 2), o);
      bottom = centre.z() + 0.5;
    }
    const StepStorage storage{bodies.size()};
    resting.reserve(bodies.size());
    shock.reserve(storage);
    recovery.reserve(storage);
  }

  // A point of body a on body b (kGround or the box below), normal +z, `depth` deep, set up as the
  // method prepares its solver contacts.
  void touch(int a, int b, const Vec3& point, double depth) {
    const RigidBody& body_b = b == kGround ? ground : bodies[static_cast<std::size_t>(b)];
    SolverContact& c = contacts.emplace_back();
    c.a = a;
    c.b = b;
    c.n = Vec3::UnitZ();
    c.ra = point - bodies[static_cast<std::size_t>(a)].x;
    c.rb = point - body_b.x;
    c.Wa = cross_matrix(c.ra).transpose();
    c.Wb = cross_matrix(c.rb).transpose();
    c.depth = depth;
    c.slop = penetration_slop_for(scene.solver, 1.0);
    ContactMatrices& m = matrices.emplace_back();
    m.Ka = collision_matrix_share(bodies[static_cast<std::size_t>(a)], c.ra);
    if (b != kGround) m.Kb = collision_matrix_share(body_b, c.rb);
    set_collision_matrix(c, Mat3(m.Ka + m.Kb));
  }

  // Shock propagation's levels, then recovery with or without skipping idle phases.
  void solve(bool skip_idle) {
    StepContext ctx{scene, bodies, ground, found, same, wires, 0.0, kDt, counters, events, pool};
    ImpulseStep step{ctx, SolverBodies{bodies, ground}, resting, contacts, matrices, impulses, stats};
    shock.run(step);
    recovery.skip_idle_phases(skip_idle);
    recovery.run(step, &shock);
  }
};

// How far from its targets recovery may leave a point, m/s: its passes stop once no change would
// move a point 5% of the slop over the step (some of which can be left at a point, more than one
// change at a time summed: twice that).
double converged(double slop) { return 2.0 * 0.05 * slop / kDt; }

// The pseudo-velocities of a stack after recovery, with idle phases skipped or run, and the phases
// skipped.
struct Outcome {
  std::vector<Vec3> v, omega;
  int skipped = 0;
  int top_level = 0;
};

Outcome recover(const std::vector<double>& overlap, bool skip_idle) {
  Stack s(overlap);
  s.solve(skip_idle);
  return {s.recovery.pseudo_v(), s.recovery.pseudo_omega(), s.recovery.skipped_phases(), s.shock.top_level()};
}

}  // namespace

TEST_CASE("recovery skips a level none of whose contacts can change, with the same result", "[solver][recovery]") {
  // The top box 5 cm into the middle one; the lower two exactly touching: levels 0 and 1 ask for
  // no push and nothing has pushed their bodies, so both are skipped; the top level and the phase
  // of every contact run.
  const std::vector<double> overlap = {0.0, 0.0, 0.05};
  const Outcome skipped = recover(overlap, true);
  const Outcome run = recover(overlap, false);
  REQUIRE(skipped.top_level == 2);
  CHECK(skipped.skipped == 2);
  CHECK(run.skipped == 0);
  // Bit for bit the pseudo-velocities of the phases run in full.
  CHECK(skipped.v == run.v);
  CHECK(skipped.omega == run.omega);
  // And they do what recovery is for: the top box rises out of the middle one at beta of the
  // overlap beyond the slop per step, and the pair below stays closed to within the slop.
  const double slop = penetration_slop_for(SolverSettings{}, 1.0);
  const double separating = SolverSettings{}.penetration_recovery * (0.05 - slop) / kDt;
  CHECK(skipped.v[2].z() - skipped.v[1].z() == Approx(separating).margin(converged(slop)));
  CHECK(skipped.v[1].z() - skipped.v[0].z() >= -slop / kDt - converged(slop));
  CHECK(skipped.v[0].z() >= -converged(slop));
}

TEST_CASE("recovery does not skip a level whose bodies were pushed below it", "[solver][recovery]") {
  // The bottom box 5 cm into the ground, the others exactly touching: no contact above the ground
  // asks for a push, but level 0's push reaches them, and every level lifts its box with the one
  // below (their contacts hold at the slop). Nothing is skipped.
  const std::vector<double> overlap = {0.05, 0.0, 0.0};
  const Outcome out = recover(overlap, true);
  REQUIRE(out.top_level == 2);
  CHECK(out.skipped == 0);
  const double slop = penetration_slop_for(SolverSettings{}, 1.0);
  const double rise = SolverSettings{}.penetration_recovery * (0.05 - slop) / kDt;
  CHECK(out.v[0].z() == Approx(rise).margin(converged(slop)));
  // Each upper box may approach the one below by at most the slop over the step: it rises with it.
  CHECK(out.v[0].z() - out.v[1].z() <= slop / kDt + converged(slop));
  CHECK(out.v[1].z() - out.v[2].z() <= slop / kDt + converged(slop));
}

TEST_CASE("shock propagation on the last run's contact set keeps its levels and groups, with the same result",
          "[solver][shock]") {
  // The same stack stepped from two different states: shock propagation told that the contact set
  // is the last run's (it keeps its levels and groups, and sets only the targets again) must give,
  // to the bit, what a fresh run forms from scratch. The second state moves differently from the
  // first, so targets kept from the first run would show.
  const std::vector<double> overlap = {0.0, 0.0, 0.0};
  auto set_state = [](Stack& s, double sink, double slide) {
    for (auto& c : s.contacts) c.friction = 0.5;  // each level's group solved directly where it sticks
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
      const double k = static_cast<double>(i + 1);
      s.bodies[i].set_velocity(Vec3(slide * k, 0.0, -sink * k), Vec3(0.0, 0.1 * slide, 0.0));
    }
  };
  auto run = [](Stack& s, bool same_contacts) {
    StepContext ctx{s.scene, s.bodies, s.ground, s.found, s.same, s.wires, 0.0, kDt, s.counters, s.events, s.pool};
    ImpulseStep step{ctx, SolverBodies{s.bodies, s.ground}, s.resting, s.contacts, s.matrices, s.impulses, s.stats};
    s.shock.run(step, same_contacts);
  };

  Stack kept(overlap);
  const std::vector<SolverContact> prepared = kept.contacts;
  set_state(kept, 0.05, 0.0);
  run(kept, false);
  kept.contacts = prepared;  // as the method prepares them again at the next step
  set_state(kept, 0.2, 0.3);
  run(kept, true);

  Stack fresh(overlap);
  set_state(fresh, 0.2, 0.3);
  run(fresh, false);

  REQUIRE(kept.shock.top_level() == 2);
  CHECK(kept.shock.levels() == fresh.shock.levels());
  for (std::size_t i = 0; i < kept.bodies.size(); ++i) {
    INFO("box " << i);
    CHECK(kept.bodies[i].v == fresh.bodies[i].v);
    CHECK(kept.bodies[i].omega == fresh.bodies[i].omega);
  }
  // And the levels did their work: no box approaches the one below (or the ground) any more, from
  // approach speeds of 0.2 m/s each; the boxes still slide (friction takes 0.1 m/s of 0.3 m/s).
  for (std::size_t i = 0; i < kept.bodies.size(); ++i) {
    const double below = i == 0 ? 0.0 : kept.bodies[i - 1].v.z();
    CHECK(kept.bodies[i].v.z() - below > -1e-12);
    CHECK(kept.bodies[i].v.x() > 0.1);
  }
}
