// DART 6.12 as a reference engine, beyond the checks every reference engine passes
// (test_conformance.cpp, tag [reference]: free fall, a compound's frame, damping, a stack of five,
// a fixed body, contacts, repeatable runs): a resting cube's contacts with every detector,
// contacts between two bodies and with a fixed one, the gyroscopic term, materials as DART
// combines them, restitution, a stack of five at DART's own precision, the wire, and its settings
// reaching DART through the registry. Tag [dart].
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "boxpile/reference/dart/dart_engine.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/body.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/tests/support/engine_scenes.hpp"
#include "boxpile/validation/core/engine_settings.hpp"

using namespace boxpile;
using nlohmann::json;

namespace {

using test::empty_scene;
using test::l_compound;
using test::run;
using test::states_of;
using test::unit_box;

constexpr double kG = 9.81;

std::vector<BodyContact> dart_contacts_of(const Engine& e) {
  std::vector<BodyContact> c;
  e.contacts(c);
  return c;
}

// The engine "dart" through the registry, with settings given as `--set` words.
std::unique_ptr<Engine> dart_with(const Scene& scene, const std::vector<std::string>& words) {
  return make_engine("dart", scene, parse_setting_words("dart", words, "test"));
}

Scene dart_fixture(const std::string& name) {
  return load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + name + ".json");
}

}  // namespace

TEST_CASE("DART: a resting cube's contacts follow our convention with every detector", "[dart]") {
  // A unit cube at rest on the ground, turned 0.3 rad about z, after 1 s: the ground is body B,
  // the normal +z, the points at the four bottom corners, midway between the surfaces (z =
  // -depth/2), the depth the small penetration DART's error reduction leaves (ERP 0.01, at most
  // 1e-3 m/s). FCL's meshes give two more points inside the bottom face, where the ground box's
  // triangles' shared diagonal crosses its edges (measured).
  Scene scene = empty_scene(Effects{true, true, false, false, false}, true);
  BodyDesc cube = unit_box("cube", Vec3(0, 0, 0.5));
  cube.frame.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
  scene.bodies = {cube};
  const std::map<std::string, int> points = {{"dart", 4}, {"fcl", 6}, {"fcl_primitive", 4}, {"ode", 4}};
  for (const auto& [name, count] : points) {
    INFO(name);
    const auto engine = dart_with(scene, {"detector=" + name});
    run(*engine, 240);
    const BodyState s = states_of(*engine)[0];
    const std::vector<BodyContact> contacts = dart_contacts_of(*engine);
    INFO("cube at " << s.position.transpose() << ", " << contacts.size() << " contacts");
    CHECK(static_cast<int>(contacts.size()) == count);
    for (const BodyContact& c : contacts) {
      INFO("point " << c.contact.position.transpose() << " depth " << c.contact.depth);
      CHECK(c.body_a == 0);
      CHECK(c.body_b == kGround);
      CHECK(c.contact.feature.kind() == FeatureKind::Plane);
      CHECK((c.contact.normal - Vec3::UnitZ()).norm() < 1e-9);
      CHECK(c.contact.depth > 0.0);
      CHECK(c.contact.depth < 1e-3);
      CHECK(std::abs(c.contact.position.z() + 0.5 * c.contact.depth) < 1e-9);
      // At a bottom corner of the cube, in its own axes (FCL's meshes: also where the world's
      // diagonal x = -y crosses an edge of the bottom face).
      const Vec3 local = s.orientation.conjugate() * (c.contact.position - s.position);
      const bool corner = std::abs(std::abs(local.x()) - 0.5) < 1e-6 && std::abs(std::abs(local.y()) - 0.5) < 1e-6;
      const bool diagonal = std::abs(c.contact.position.x() + c.contact.position.y()) < 1e-6 &&
                            std::abs(local.head<2>().cwiseAbs().maxCoeff() - 0.5) < 1e-6;
      CHECK((corner || (name == "fcl" && diagonal)));
    }
    // The cube's centre sits the contacts' depth below 0.5.
    REQUIRE(!contacts.empty());
    CHECK(std::abs(s.position.z() - (0.5 - contacts[0].contact.depth)) < 1e-6);
  }
}

TEST_CASE("DART: contacts between two bodies point from B toward A, a fixed body is B", "[dart]") {
  Scene scene = empty_scene(Effects{true, true, false, false, false}, true);
  scene.bodies = {unit_box("low", Vec3(0, 0, 0.5)), unit_box("high", Vec3(0.2, 0.1, 1.5))};
  DartEngine engine(scene);
  run(engine, 10);
  const std::vector<BodyState> states = states_of(engine);
  int ground = 0, between = 0;
  for (const BodyContact& c : dart_contacts_of(engine)) {
    CHECK(c.body_a != kGround);
    if (c.body_b == kGround) {
      ++ground;
      CHECK((c.contact.normal - Vec3::UnitZ()).norm() < 1e-9);
      continue;
    }
    ++between;
    const Vec3 ab = states[static_cast<std::size_t>(c.body_a)].position - states[static_cast<std::size_t>(c.body_b)].position;
    CHECK(c.contact.normal.dot(ab) > 0.9 * ab.norm());
    CHECK(std::abs(c.contact.position.z() - 1.0) < 1e-3);
    CHECK(c.contact.depth > 0.0);
  }
  CHECK(ground == 4);
  CHECK(between == 4);

  // A fixed body is B, whichever object DART names first.
  Scene on_slab = empty_scene(Effects{true, true, false, false, false}, false);
  BodyDesc slab = unit_box("slab", Vec3(0, 0, -0.5));
  slab.fixed = true;
  slab.boxes = {BoxShape{Vec3(2, 2, 0.5), Vec3::Zero(), Quat::Identity()}};
  on_slab.bodies = {slab, unit_box("cube", Vec3(0.3, 0.2, 0.5))};
  DartEngine resting(on_slab);
  run(resting, 10);
  const std::vector<BodyContact> contacts = dart_contacts_of(resting);
  CHECK(contacts.size() == 4);
  for (const BodyContact& c : contacts) {
    CHECK(c.body_a == 1);
    CHECK(c.body_b == 0);
    CHECK((c.contact.normal - Vec3::UnitZ()).norm() < 1e-9);
  }
}

TEST_CASE("DART: with the gyroscopic effect, DART's own term turns a spinning compound", "[dart]") {
  // No gravity, no torque (the effect off is a case of the engines' shared tests in
  // test_conformance.cpp: the engine cancels DART's omega x I omega). With the effect on, DART's
  // own term acts: the angular velocity precesses while the angular momentum I_world omega stays
  // to the Euler error of a step (measured: changed by less than 5e-3 of itself in 1 s), and the
  // centre of mass still moves straight at v.
  Scene scene = empty_scene(Effects{false, false, false, false, true}, false);
  BodyDesc l = l_compound("l", Vec3(1, 2, 3));
  l.velocity = Vec3(0.5, -0.2, 0.1);
  l.angular_velocity = Vec3(0.3, -0.4, 0.8);
  scene.bodies = {l};
  const RigidBody body = make_bodies(scene)[0];
  DartEngine engine(scene);
  run(engine, 240);
  const BodyState s = states_of(engine)[0];
  const Vec3 com = s.position - s.orientation * body.frame_offset;
  CHECK((com - (body.x + engine.time() * l.velocity)).norm() < 1e-9);
  const Mat3 R = s.orientation.toRotationMatrix();
  const Vec3 momentum = R * body.inertia_body * R.transpose() * s.angular_velocity;
  const Vec3 momentum0 = body.inertia_body * l.angular_velocity;
  INFO("omega " << s.angular_velocity.transpose() << ", L " << momentum.transpose() << " from "
                << momentum0.transpose());
  CHECK((s.angular_velocity - l.angular_velocity).norm() > 1e-2);  // it precesses
  CHECK((momentum - momentum0).norm() < 5e-3 * momentum0.norm());
}
TEST_CASE("DART: materials combine as DART does, equal to ours for equal materials", "[dart]") {
  // A box sliding down a 30 degree incline for 1 s. DART's pair friction is min(mu_a, mu_b): box
  // 0.1 on ground 0.9 slides with mu 0.1 (ours, ODE's and MuJoCo's pairs: sqrt = 0.3),
  // a = g (sin - 0.1 cos); box 0.3 on ground 0.3 gives mu 0.3 in every rule.
  const double theta = M_PI / 6;
  const Vec3 n(-std::sin(theta), 0, std::cos(theta));
  for (const auto& [box_mu, ground_mu, pair_mu] : {std::tuple{0.1, 0.9, 0.1}, std::tuple{0.3, 0.3, 0.3}}) {
    INFO("box " << box_mu << " on ground " << ground_mu);
    Scene scene = empty_scene(Effects{true, true, false, false, false}, true);
    scene.ground = HalfSpace{n, 0.0};
    scene.material = Material{ground_mu, 0.0, std::nullopt};
    BodyDesc box = unit_box("box", 0.5 * n);
    box.frame.orientation = Quat(Eigen::AngleAxisd(-theta, Vec3::UnitY()));
    box.material = Material{box_mu, 0.0, std::nullopt};
    scene.bodies = {box};
    DartEngine engine(scene);
    run(engine, 240);
    const double expected = kG * (std::sin(theta) - pair_mu * std::cos(theta));
    const double speed = states_of(engine)[0].velocity.norm();
    INFO("speed after 1 s " << speed << ", expected " << expected);
    CHECK(std::abs(speed - expected) < 0.01 * expected);
  }
}

TEST_CASE("DART: restitution of a pair of equal materials is that material's", "[dart]") {
  // A cube dropped flat from 0.5 m onto the ground, both e = 0.5: it leaves at half its impact
  // speed (each shape gets sqrt(e), DART multiplies the two). Speeds read one step before and
  // after the impact step.
  Scene scene = empty_scene(Effects{true, true, true, false, false}, true);
  scene.material = Material{0.5, 0.5, std::nullopt};
  BodyDesc cube = unit_box("cube", Vec3(0, 0, 1.0));
  cube.material = Material{0.5, 0.5, std::nullopt};
  scene.bodies = {cube};
  DartEngine engine(scene);
  double impact = 0.0, rebound = 0.0;
  for (int k = 0; k < 480 && rebound <= 0.0; ++k) {
    const double before = states_of(engine)[0].velocity.z();
    engine.step();
    const double after = states_of(engine)[0].velocity.z();
    if (before < 0.0 && after > 0.0) {
      impact = -before;
      rebound = after;
    }
  }
  INFO("impact " << impact << " m/s, rebound " << rebound << " m/s");
  REQUIRE(impact > 3.0);
  CHECK(std::abs(rebound / impact - 0.5) < 0.02);
}

TEST_CASE("DART: five stacked cubes stand for 5 s", "[dart]") {
  // Measured with the Dantzig solver and DART's own detector: top z - 4.5 = -4.3e-6 m (ERP 0.01
  // leaves about 1e-6 m in each of the 5 contact layers), drift 1.2e-6 m. The gates allow 5 and
  // 10 times that (the LCP's pivoting order may differ with rounding elsewhere); any slow sinking
  // or sliding fails them.
  const Scene scene = dart_fixture("stack_5");
  DartEngine engine(scene);
  run(engine, step_count(scene.time));
  const std::vector<BodyState> s = states_of(engine);
  const BodyState& top = s.back();
  double drift = 0.0;
  for (const BodyState& b : s) drift = std::max(drift, b.position.head<2>().norm());
  WARN("stack_5: top z - 4.5 = " << top.position.z() - 4.5 << " m, drift " << drift << " m");
  CHECK(top.position.z() - 4.5 > -2e-5);
  CHECK(top.position.z() - 4.5 < 1e-6);
  CHECK(drift < 1e-5);
  CHECK(top.velocity.norm() < 1e-6);
}

TEST_CASE("DART: a cube on a 30 degree wire slides as g sin t^2 / 2 and stops at the end", "[dart]") {
  // Hung at its centre on a frictionless wire, no contacts: the anchor follows the wire exactly
  // (reduced coordinates), the body slides at g sin 30 (the carriage's small mass has weight
  // too), and the prismatic joint's upper limit stops it at the far end.
  Scene scene = empty_scene(Effects{true, true, false, false, false}, false);
  const double theta = M_PI / 6, length = 1.0;
  BodyDesc cube = unit_box("cube", Vec3::Zero());
  Wire wire;
  wire.from = Vec3::Zero();
  wire.to = length * Vec3(std::cos(theta), 0, -std::sin(theta));
  cube.wire = wire;
  scene.bodies = {cube};
  DartEngine engine(scene);
  const Vec3 axis = wire.to.normalized();
  const int n = 120;  // 0.5 s: 0.61 m along the wire
  double worst_off = 0.0;
  for (int k = 0; k < n; ++k) {
    engine.step();
    const Vec3 x = states_of(engine)[0].position;
    worst_off = std::max(worst_off, (x - axis * axis.dot(x)).norm());
  }
  const double along = axis.dot(states_of(engine)[0].position);
  const double dt = scene.time.dt;
  const double t = n * dt;
  const double expected = 0.5 * kG * std::sin(theta) * t * t;
  INFO("along " << along << " m, expected " << expected << " m; worst distance from the line " << worst_off << " m");
  CHECK(worst_off < 1e-9);
  CHECK(std::abs(along - expected) < kG * std::sin(theta) * t * dt);  // the Euler error a t dt
  run(engine, 240);
  const BodyState end = states_of(engine)[0];
  INFO("after 1.5 s at " << axis.dot(end.position) << " m, speed " << end.velocity.norm());
  CHECK(std::abs(axis.dot(end.position) - length) < 1e-3);
  CHECK(end.velocity.norm() < 1e-2);
}

TEST_CASE("DART's settings reach DART", "[dart]") {
  SECTION("the registry lists DART's defaults and applies given values") {
    const json resolved = resolved_settings("dart", Scene{}, parse_setting_words("dart", {"detector=ode", "erp=0.2"}, "test"));
    CHECK(resolved["detector"] == "ode");
    CHECK(resolved["erp"] == 0.2);
    CHECK(resolved["lcp_solver"] == "dantzig");
    CHECK(resolved["max_erv"] == 1e-3);
    CHECK_THROWS_AS(parse_setting_words("dart", {"detector=bullet"}, "test"), InputError);
    CHECK_THROWS_AS(parse_setting_words("dart", {"erp=2"}, "test"), InputError);
  }
  SECTION("PGS as the main solver, 5 sweeps, lets the stack sink further than Dantzig") {
    const Scene scene = dart_fixture("stack_5");
    const auto pgs = dart_with(scene, {"lcp_solver=pgs", "pgs_iterations=5"});
    DartEngine dantzig(scene);
    run(*pgs, 240);
    run(dantzig, 240);
    const double sink_pgs = 4.5 - states_of(*pgs).back().position.z();
    const double sink_dantzig = 4.5 - states_of(dantzig).back().position.z();
    INFO("top sank " << sink_pgs << " m (PGS) and " << sink_dantzig << " m (Dantzig)");
    CHECK(sink_pgs > 10 * sink_dantzig);
  }
  SECTION("the error correction: erp, max_erv and error_allowance") {
    // A cube started 0.01 m deep in the ground, 0.25 s. DART's defaults push it out at max_erv
    // (1e-3 m/s: 2.5e-4 m in 0.25 s, the depth stays near 0.01 m); erp 0.2 with max_erv 0.5 push
    // 0.48 m/s and remove the depth within a few steps; an error allowance of 0.02 m leaves it.
    Scene scene = empty_scene(Effects{true, true, false, false, false}, true);
    scene.bodies = {unit_box("cube", Vec3(0, 0, 0.49))};
    const auto depth_after = [&](const std::vector<std::string>& words) {
      const auto engine = dart_with(scene, words);
      run(*engine, 60);
      return 0.5 - states_of(*engine)[0].position.z();
    };
    const double defaults = depth_after({});
    const double fast = depth_after({"erp=0.2", "max_erv=0.5"});
    const double allowed = depth_after({"erp=0.2", "max_erv=0.5", "error_allowance=0.02"});
    INFO("depth after 0.25 s: " << defaults << " m (defaults), " << fast << " m (erp 0.2), " << allowed
                                << " m (allowance 0.02 m)");
    CHECK(std::abs(defaults - (0.01 - 60 * scene.time.dt * 1e-3)) < 5e-5);
    CHECK(fast < 1e-4);
    CHECK(std::abs(allowed - 0.01) < 5e-5);
  }
  SECTION("max_contacts caps the points of a collision pass") {
    Scene scene = empty_scene(Effects{true, true, false, false, false}, true);
    scene.bodies = {unit_box("cube", Vec3(0, 0, 0.5))};
    const auto engine = dart_with(scene, {"max_contacts=2"});
    run(*engine, 10);
    CHECK(dart_contacts_of(*engine).size() == 2);
  }
}
