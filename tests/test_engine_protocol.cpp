// The engine protocol end to end (docs/engine-protocol.md): our World over the protocol gives the
// in-process World's states to the last bit; the Python example engine falls on the analytic
// path and rests; a broken engine's answers are refused, and no child outlives its engine.
#include <signal.h>

#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "boxpile/reference/process/process_engine.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/world.hpp"

namespace {

using boxpile::BodyState;
using boxpile::ProcessEngine;
using boxpile::ProcessEngineOptions;

boxpile::Scene fixture(const std::string& name) { return boxpile::load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/" + name); }

ProcessEngineOptions options(std::string name, std::string command) {
  ProcessEngineOptions o;
  o.name = std::move(name);
  o.command = std::move(command);
  o.timeout = std::chrono::milliseconds(20'000);  // generous: the sanitizer build is slow
  return o;
}

std::string python_engine() { return "python3 " + std::string(BOXPILE_EXAMPLES_DIR) + "/engines/box_engine.py"; }
std::string broken_engine(const std::string& mode) {
  return "python3 " + std::string(BOXPILE_TESTS_DIR) + "/engines/broken_engine.py " + mode;
}

bool process_exists(pid_t pid) { return kill(pid, 0) == 0; }

// Steps both engines `steps` times and requires every state to be the same double.
void require_identical(boxpile::Engine& a, boxpile::Engine& b, long steps) {
  std::vector<BodyState> sa, sb;
  for (long k = 0; k <= steps; ++k) {
    if (k > 0) {
      a.step();
      b.step();
    }
    a.body_states(sa);
    b.body_states(sb);
    REQUIRE(sa.size() == sb.size());
    REQUIRE(a.time() == b.time());
    for (std::size_t i = 0; i < sa.size(); ++i) {
      INFO("step " << k << ", body " << sa[i].name);
      REQUIRE(sa[i].name == sb[i].name);
      REQUIRE(sa[i].position == sb[i].position);
      REQUIRE(sa[i].orientation.coeffs() == sb[i].orientation.coeffs());
      REQUIRE(sa[i].velocity == sb[i].velocity);
      REQUIRE(sa[i].angular_velocity == sb[i].angular_velocity);
    }
  }
  std::vector<boxpile::BodyContact> ca, cb;
  a.contacts(ca);
  b.contacts(cb);
  REQUIRE(ca.size() == cb.size());
  for (std::size_t i = 0; i < ca.size(); ++i) {
    REQUIRE(ca[i].body_a == cb[i].body_a);
    REQUIRE(ca[i].body_b == cb[i].body_b);
    REQUIRE(ca[i].contact.position == cb[i].contact.position);
    REQUIRE(ca[i].contact.depth == cb[i].contact.depth);
  }
}

}  // namespace

TEST_CASE("our World over the protocol gives the in-process states to the last bit", "[protocol]") {
  // Doubles go over the wire in their shortest round-trip form (at most 17 significant digits),
  // so nothing is lost either way; any difference is a bug in the resolved scene or the reader.
  for (const char* name : {"scenes/stack_10.json", "scenes/bone_hits_pile.json"}) {
    INFO(name);
    boxpile::Scene scene = fixture(name);
    // The bone reaches the pile at about 1.3 s and knocks it over: 2 s holds the impact.
    const long steps = std::lround(std::min(scene.time.duration, 2.0) / scene.time.dt);
    boxpile::World own(scene);
    ProcessEngine served(scene, options("own-world", BOXPILE_OWN_WORLD_ENGINE));
    CHECK(served.hello().precision == "float64");
    CHECK(served.hello().contacts);
    require_identical(own, served, steps);
    // Its own time is what it reported: positive, and less than the round trips' wall time.
    REQUIRE(served.reported_seconds().has_value());
    CHECK(*served.reported_seconds() > 0.0);
  }
}

// Callers that read the states alone (stability, sweeps, accuracy) switch the contacts off: the
// program is then asked for none, answers with none, and its states stay those of the World in
// this process to the last bit; switched on again, the next step brings the contacts back.
TEST_CASE("contacts switched off are not asked for, and the states are unchanged", "[protocol]") {
  boxpile::Scene scene = fixture("scenes/stack_10.json");
  boxpile::World own(scene);
  ProcessEngine served(scene, options("own-world", BOXPILE_OWN_WORLD_ENGINE));
  served.report_contacts(false);
  own.report_contacts(false);  // ours finds them for its step anyway and still reports them
  std::vector<boxpile::BodyState> sa, sb;
  std::vector<boxpile::BodyContact> ca, cb;
  for (int k = 1; k <= 240; ++k) {
    own.step();
    served.step();
    own.body_states(sa);
    served.body_states(sb);
    for (std::size_t i = 0; i < sa.size(); ++i) {
      INFO("step " << k << ", body " << sa[i].name);
      REQUIRE(sa[i].position == sb[i].position);
      REQUIRE(sa[i].velocity == sb[i].velocity);
    }
    served.contacts(cb);
    REQUIRE(cb.empty());
  }
  own.contacts(ca);
  CHECK(ca.size() == 40);  // ten stacked cubes on the ground: four points on each of the ten faces
  served.report_contacts(true);
  own.step();
  served.step();
  own.contacts(ca);
  served.contacts(cb);
  CHECK(cb.size() == ca.size());
}

TEST_CASE("an engine's hello alone tells its capabilities before any scene", "[protocol]") {
  const boxpile::protocol::Hello hello = ProcessEngine::ask_hello("pybox", python_engine(), std::chrono::seconds(20));
  CHECK(hello.name == "pybox");
  CHECK(hello.precision == "float64");
  CHECK(hello.contacts);
  CHECK(hello.timing);
  CHECK(hello.settings.empty());
}

TEST_CASE("the Python example engine falls on the analytic path of semi-implicit Euler", "[protocol]") {
  boxpile::Scene scene = fixture("scenes/free_fall.json");
  ProcessEngine engine(scene, options("pybox", python_engine()));
  std::vector<BodyState> states;
  engine.body_states(states);
  const boxpile::Vec3 x0 = states[0].position, v0 = scene.bodies[0].velocity, g = scene.gravity;
  const double dt = scene.time.dt;
  const long steps = std::lround(0.5 / dt);  // well before it reaches the ground (10 m below)
  for (long k = 1; k <= steps; ++k) {
    engine.step();
    engine.body_states(states);
    // v_k = v0 + k g dt, x_k = x0 + k v0 dt + k (k + 1) / 2 g dt^2: the sum of the velocities
    // after each step. Rounding over 120 steps stays below 1e-12 m.
    const double kk = static_cast<double>(k);
    const boxpile::Vec3 expected = x0 + kk * dt * v0 + 0.5 * kk * (kk + 1.0) * dt * dt * g;
    REQUIRE((states[0].position - expected).norm() < 1e-12);
    REQUIRE((states[0].velocity - (v0 + kk * dt * g)).norm() < 1e-12);
  }
  std::vector<boxpile::BodyContact> contacts;
  engine.contacts(contacts);
  CHECK(contacts.empty());
}

TEST_CASE("a box resting on the ground in the Python example engine stays at rest", "[protocol]") {
  boxpile::Scene scene = fixture("scenes/box_at_rest.json");
  ProcessEngine engine(scene, options("pybox", python_engine()));
  std::vector<BodyState> start, states;
  engine.body_states(start);
  double drift = 0.0, speed = 0.0;
  const long steps = std::lround(2.0 / scene.time.dt);
  for (long k = 0; k < steps; ++k) {
    engine.step();
    engine.body_states(states);
    drift = std::max(drift, (states[0].position - start[0].position).norm());
    speed = states[0].velocity.norm();
  }
  // The box starts exactly on the ground, where no vertex is below the plane yet: it falls one
  // step, g dt^2 = 1.70e-4 m, before its corners touch; then the overlap bias lifts it back to
  // the slop (1e-4 m deep) and it stays there, still.
  const double one_step = scene.gravity.norm() * scene.time.dt * scene.time.dt;
  CHECK(drift < one_step * (1.0 + 1e-9));
  CHECK(std::abs(states[0].position.z() - start[0].position.z()) < 1.05e-4);
  CHECK(speed < 1e-3);
  std::vector<boxpile::BodyContact> contacts;
  engine.contacts(contacts);
  CHECK(contacts.size() == 4);  // the four bottom corners
}

TEST_CASE("broken engines are refused naming the engine, the request and the step", "[protocol]") {
  const boxpile::Scene scene = fixture("scenes/stack_5.json");
  struct Case {
    const char* mode;
    const char* message;
  };
  const Case cases[] = {
      {"exit-at-step-3", "step 3: the program exited with status 3"},
      {"garbage", "step 2: the answer is not JSON; the line was: \"this is \\x01 not JSON\""},
      {"wrong-count", "step 2: the answer \"bodies\" has 4 entries; the scene has 5 bodies"},
      {"nan", "step 2: the answer is not JSON: it has a number that is not finite (NaN)"},
      {"not-ok", "step 2: the answer answered ok: false: the solver diverged"},
      {"bad-version", "hello: the answer speaks protocol 2; this boxpile speaks version 1 alone"},
  };
  for (const Case& c : cases) {
    INFO(c.mode);
    try {
      ProcessEngine engine(scene, options("broken", broken_engine(c.mode)));
      for (int k = 0; k < 5; ++k) engine.step();
      FAIL("no error");
    } catch (const boxpile::EngineProtocolError& e) {
      const std::string what = e.what();
      CHECK_THAT(what, Catch::Contains("engine \"broken\""));
      CHECK_THAT(what, Catch::Contains(c.message));
      if (std::string(c.mode) == "exit-at-step-3") CHECK_THAT(what, Catch::Contains("giving up at step 3"));
    }
  }
}

TEST_CASE("an engine that does not answer within the timeout is stopped, and no child outlives it", "[protocol]") {
  const boxpile::Scene scene = fixture("scenes/stack_5.json");
  ProcessEngineOptions o = options("sleeper", broken_engine("sleep"));
  o.timeout = std::chrono::milliseconds(3000);  // Python starts well within it, even under load
  pid_t pid = -1;
  try {
    ProcessEngine engine(scene, std::move(o));
    pid = engine.pid();
    REQUIRE(process_exists(pid));
    engine.step();
    FAIL("no timeout");
  } catch (const boxpile::EngineProtocolError& e) {
    CHECK_THAT(e.what(), Catch::Contains("step 1: no answer within 3 s (--engine-timeout)"));
  }
  REQUIRE(pid > 0);
  CHECK_FALSE(process_exists(pid));  // killed and reaped: not even a zombie

  // A healthy engine's child is gone once the engine is.
  pid_t healthy = -1;
  {
    ProcessEngine engine(scene, options("pybox", python_engine()));
    healthy = engine.pid();
    engine.step();
  }
  CHECK_FALSE(process_exists(healthy));
}
