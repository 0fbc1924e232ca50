// The shared checks (validation/stability/stability_checks.hpp) on runs whose answer is known: a body at
// rest passes everything; energy that rises, a body that moves, a spin, a bounce of known height
// and a wall passed through are each caught, with the measured figure.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/rulers/rebound_tracker.hpp"
#include "boxpile/validation/stability/scene_checks.hpp"
#include "boxpile/validation/stability/stability_checks.hpp"

using namespace boxpile;

namespace {

Scene one_box(const std::string& checks) {
  return parse_checked_scene(R"({"name": "t", "time": {"dt": 0.01, "duration": 1},
    "ground": {}, "bodies": [{"name": "box", "mass": 2, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5]}],
    "checks": )" + checks + "}", "t.json");
}

BodyState state(const Vec3& p, const Vec3& v = Vec3::Zero(), const Vec3& w = Vec3::Zero()) {
  return {"box", p, Quat::Identity(), v, w};
}

const SceneCheckResult& find(const std::vector<SceneCheckResult>& results, const std::string& name) {
  for (const SceneCheckResult& r : results)
    if (r.name == name) return r;
  FAIL("no check " << name);
  return results.front();
}

}  // namespace

TEST_CASE("a body at rest passes every check", "[checks]") {
  const Scene s = one_box(R"({"energy_rise": 1e-6, "rest": {"speed": 1e-3, "max_move": 1e-3},
                              "no_turning": {"limit": 1e-3}})");
  RunMonitor m(s);
  for (long k = 0; k <= 100; ++k) m.observe(k, {state({0, 0, 0.5})});
  const std::vector<SceneCheckResult> r = m.evaluate();
  CHECK(all_passed(r));
  CHECK(r.size() == 6);  // finite, energy, penetration, rest speed and move, turning
  CHECK(m.measures().energy_start == Approx(2 * 9.81 * 0.5));
  CHECK_FALSE(m.measures().moved_at_step);
}

TEST_CASE("energy that rises, a body that keeps moving and a spin are caught", "[checks]") {
  const Scene s = one_box(R"({"energy_rise": 1e-6, "rest": {"speed": 1e-3, "max_move": 1e-3},
                              "no_turning": {"limit": 1e-3, "until": 0.5}})");
  RunMonitor m(s);
  m.observe(0, {state({0, 0, 0.5})});
  // Lifted by 1 cm and moving at 0.1 m/s at step 10, spinning at 2 rad/s after 0.5 s only.
  m.observe(10, {state({0, 0, 0.51}, {0.1, 0, 0})});
  m.observe(60, {state({0.002, 0, 0.5}, Vec3::Zero(), {0, 0, 2})});
  const std::vector<SceneCheckResult> r = m.evaluate();
  CHECK_FALSE(all_passed(r));
  // The largest rise is the spin's: 1/2 I w^2 with I = m (a^2 + b^2) / 12 = 1/3 kg m^2 is 2/3 J
  // (the lift at step 10 added only 0.2062 J).
  const double spin_energy = 0.5 * (1.0 / 3.0) * 4.0;
  CHECK(find(r, "energy_rise").value == Approx(spin_energy / (2 * 9.81 * 0.5)));
  CHECK_FALSE(find(r, "energy_rise").passed);
  CHECK(find(r, "rest_move").value == Approx(0.01));
  CHECK(m.measures().moved_at_step == 10);
  // The fastest point at the end: the spin's, 2 rad/s at the unit cube's corner sqrt(3)/2 m out.
  CHECK(find(r, "rest_speed").value == Approx(2.0 * std::sqrt(0.75)));
  CHECK(find(r, "rest_speed").key == "rest");
  // The spin came after `until`: not counted.
  CHECK(find(r, "no_turning").passed);
  CHECK(first_instability(r)->name == "energy_rise");
  CHECK(describe(find(r, "rest_move")) == "rest_move 0.01 m > 0.001");
}

TEST_CASE("a bounce is measured from the first impact to the top of the rebound", "[checks]") {
  const Scene s = one_box(R"({"rebound": {"body": "box", "rest_height": 0.5, "height": 0.25, "tolerance": 0.05}})");
  RunMonitor m(s);
  m.observe(0, {state({0, 0, 1.5})});
  m.observe(1, {state({0, 0, 0.6}, {0, 0, -4})});
  m.observe(2, {state({0, 0, 0.52}, {0, 0, 2})});   // bounced
  m.observe(3, {state({0, 0, 0.74}, {0, 0, 0.1})});
  m.observe(4, {state({0, 0, 0.7}, {0, 0, -1})});   // falling again: the rebound is over
  m.observe(5, {state({0, 0, 0.9}, {0, 0, 1})});    // a later bounce does not count
  REQUIRE(m.measures().rebound);
  CHECK(*m.measures().rebound == Approx(0.24));
  CHECK(find(m.evaluate(), "rebound").value == Approx(0.04));
  CHECK(find(m.evaluate(), "rebound").passed);
}

TEST_CASE("the rebound tracker finds a ballistic bounce's apex, e^2 h, and not a launch's rise", "[checks]") {
  // A point thrown up at v0 from the ground, falling back and bouncing with restitution e: the
  // first rise (before any fall) is not a bounce; the rise after the impact peaks at
  // (e v_impact)^2 / (2 g). Sampled every dt, the apex is missed by at most g (dt/2)^2 / 2.
  const double g = 9.81, v0 = 2.0, e = 0.5, dt = 1e-3;
  const double t_impact = 2.0 * v0 / g, v_after = e * v0;
  ReboundTracker tracker;
  for (int k = 0; k * dt < t_impact + 2.0 * v_after / g; ++k) {
    const double t = k * dt;
    const double s = t < t_impact ? t : t - t_impact, v_start = t < t_impact ? v0 : v_after;
    tracker.observe(v_start * s - 0.5 * g * s * s, v_start - g * s);
    if (t < t_impact) CHECK_FALSE(tracker.apex());  // the launch's rise is not a bounce
  }
  REQUIRE(tracker.apex());
  CHECK(tracker.done());
  const double apex = v_after * v_after / (2.0 * g);  // 0.0510 m; the launch's rise was 0.204 m
  CHECK(*tracker.apex() == Approx(apex).margin(0.5 * g * 0.25 * dt * dt));
  CHECK(*tracker.apex() <= apex);
}

TEST_CASE("a body that passes a wall is caught, and a stopped run fails finiteness alone", "[checks]") {
  const Scene s = one_box(R"({"stays_behind": [{"body": "box", "normal": [-2, 0, 0], "offset": 0.01}]})");
  RunMonitor m(s);
  m.observe(0, {state({-1, 0, 0.5})});
  m.observe(1, {state({0.3, 0, 0.5})});
  const std::vector<SceneCheckResult> checks = m.evaluate();  // kept: `wall` refers into it
  const SceneCheckResult& wall = find(checks, "stays_behind box");
  CHECK(wall.value == Approx(-0.31));
  CHECK_FALSE(wall.passed);
  m.stopped_non_finite();  // the run loop found a non-finite state (run_loop.hpp)
  m.observe(2, {state({0.5, 0, 0.5})});  // not observed any more
  const std::vector<SceneCheckResult> r = m.evaluate();
  REQUIRE(r.size() == 1);
  CHECK(r[0].name == "finite");
  CHECK_FALSE(r[0].passed);
}

TEST_CASE("a body must end beyond a plane, wherever it went on the way", "[checks]") {
  // Held to x >= 0.325 at the end (normal given unnormalised): the margin is the last position's.
  const Scene s = one_box(R"({"ends_beyond": [{"body": "box", "normal": [3, 0, 0], "offset": 0.325}]})");
  RunMonitor m(s);
  m.observe(0, {state({-1, 0, 0.5})});
  m.observe(1, {state({2.0, 0, 0.5})});  // past it on the way: not what counts
  m.observe(2, {state({0.3, 0, 0.5})});
  std::vector<SceneCheckResult> r = m.evaluate();
  CHECK(find(r, "ends_beyond box").value == Approx(0.3 - 0.325));
  CHECK_FALSE(find(r, "ends_beyond box").passed);
  CHECK(find(r, "ends_beyond box").key == "ends_beyond");
  CHECK(describe(find(r, "ends_beyond box")) == "ends_beyond box -0.025 m < 0");
  m.observe(3, {state({9.48, 0, 0.5})});
  r = m.evaluate();
  CHECK(find(r, "ends_beyond box").value == Approx(9.48 - 0.325));
  CHECK(find(r, "ends_beyond box").passed);
}

TEST_CASE("the table of checks: one row per file, in report order, each read from its own key", "[checks]") {
  std::vector<std::string_view> keys;
  for (const CheckRow* row : check_rows()) {
    INFO(row->key);
    keys.push_back(row->key);
    CHECK(row->meaning.size() > 20);
    CHECK(row->read != nullptr);
    CHECK(find_check_row(row->key) == row);
    // The two held by default are the two that say nothing of the scene's own motion.
    CHECK(row->held_by_default == !row->of_its_own);
  }
  CHECK(keys == std::vector<std::string_view>{"energy_rise", "energy_conserved", "penetration", "rest", "no_turning",
                                              "rebound", "slides", "stays_behind", "ends_beyond"});
  CHECK(find_check_row("reasons") == nullptr);
  // Results come in the table's order whatever the order of the file's keys.
  const Scene s = one_box(R"({"no_turning": {"limit": 1}, "penetration": 0.5, "rest": {}, "energy_conserved": 0.1})");
  RunMonitor m(s);
  m.observe(0, {state({0, 0, 0.5})});
  std::vector<std::string> names;
  for (const SceneCheckResult& r : m.evaluate()) names.push_back(r.name);
  CHECK(names == std::vector<std::string>{"finite", "energy_rise", "energy_conserved", "penetration", "rest_speed",
                                          "rest_move", "no_turning"});
}

TEST_CASE("scene checks: unknown keys and unknown bodies are errors naming the path", "[checks]") {
  auto error_of = [](const std::string& checks) {
    try {
      one_box(checks);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of(R"({"energy_rse": 1e-6})") ==
        "t.json: checks: unknown key \"energy_rse\"; did you mean \"energy_rise\"?");
  CHECK(error_of(R"({"rebound": {"body": "bx", "rest_height": 0.5, "height": 0.25}})") ==
        "t.json: checks.rebound.body: no body named \"bx\" in the scene");
  CHECK(error_of(R"({"rest": {"max_move": -1}})").find("checks.rest.max_move: must be > 0") != std::string::npos);
  CHECK(error_of(R"({"stays_behind": [{"body": "box", "normal": [0, 0, 0], "offset": 0}]})") ==
        "t.json: checks.stays_behind[0].normal: must not be zero");
  CHECK(error_of(R"({"ends_beyond": [{"body": "ram", "normal": [1, 0, 0], "offset": 0.3}]})") ==
        "t.json: checks.ends_beyond[0].body: no body named \"ram\" in the scene");
  CHECK(error_of(R"({"ends_beyond": [{"body": "box", "normal": [1, 0, 0]}]})").find("checks.ends_beyond[0]") !=
        std::string::npos);
  CHECK(error_of(R"([1, 2])").find("t.json: checks: expected object") == 0);
  // Rest is judged by speed; the old energy limit is refused with what replaced it.
  CHECK(error_of(R"({"rest": {"kinetic_per_body": 1e-6}})") ==
        "t.json: checks.rest.kinetic_per_body: is no longer a check: rest is judged by speed, \"speed\" (m/s)");
  // A reason must be for a check the scene holds, and say something.
  CHECK(error_of(R"({"reasons": {"rebound": "why"}})") ==
        "t.json: checks.reasons.rebound: gives a reason for a check the scene does not hold");
  CHECK(error_of(R"({"reasons": {"penetration": ""}})") == "t.json: checks.reasons.penetration: must not be empty");
  CHECK(error_of(R"({"reasons": {"rest_move": "x"}})").find("unknown key \"rest_move\"") != std::string::npos);
}

TEST_CASE("rest is judged by speed whatever the mass, and each result carries its scene key and reason", "[checks]") {
  // 0.5 mm/s passes a 1 mm/s limit for a 1,000 kg box (kinetic energy 1.25e-4 J, which the old
  // 1e-6 J per body refused), and 2 mm/s fails it for a 1 kg one (2e-6 J).
  auto rest_speed = [](double mass, double speed) {
    const Scene s = parse_scene(R"({"name": "t", "time": {"dt": 0.01, "duration": 1}, "ground": {},
      "bodies": [{"name": "box", "mass": )" + std::to_string(mass) + R"(, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5]}],
      "checks": {"rest": {"speed": 1e-3, "max_move": 1e-3},
                 "reasons": {"rest": "the rest reason", "penetration": "the penetration reason"}}})", "t.json");
    RunMonitor m(s);
    m.observe(0, {state({0, 0, 0.5})});
    m.observe(1, {state({0, 0, 0.5}, {speed, 0, 0})});
    const std::vector<SceneCheckResult> r = m.evaluate();
    CHECK(find(r, "rest_speed").reason == "the rest reason");
    CHECK(find(r, "rest_move").reason == "the rest reason");
    CHECK(find(r, "penetration").reason == "the penetration reason");
    CHECK(find(r, "energy_rise").key == "energy_rise");
    CHECK(find(r, "energy_rise").reason.empty());
    CHECK(read_scene_checks(s).without_reason() == std::vector<std::string_view>{"energy_rise"});
    return find(r, "rest_speed");
  };
  const SceneCheckResult heavy = rest_speed(1000.0, 5e-4);
  CHECK(heavy.passed);
  CHECK(heavy.value == Approx(5e-4));
  const SceneCheckResult light = rest_speed(1.0, 2e-3);
  CHECK_FALSE(light.passed);
  CHECK(light.value == Approx(2e-3));
}
