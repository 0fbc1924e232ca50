// The run loop, recordings and replay pages: a blow-up stops the loop at the step that made it,
// a recording keeps every frame's contact set and reads back exactly, and a replay page's data
// holds exactly what the recordings hold (or says how it was thinned).
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/recording.hpp"
#include "boxpile/validation/replay/replay_data.hpp"
#include "boxpile/validation/replay/replay_page.hpp"
#include "boxpile/validation/core/run_loop.hpp"

using namespace boxpile;
using nlohmann::json;

namespace {

Scene fixture(const std::string& name) {
  return load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + name + ".json");
}

// Records `scene` in `engine` for `steps` steps, a frame every `every` steps.
Recording record(const Scene& scene, const std::string& engine, long steps, long every) {
  const auto e = make_engine(engine, scene);
  Recorder recorder(scene, engine);
  RunHooks hooks;
  hooks.frame = [&](const StepView& v) { recorder.frame(v); };
  const RunLoopResult result = run_loop(*e, scene.time.dt, steps, every, hooks);
  REQUIRE_FALSE(result.stopped);
  return recorder.recording();
}

// An engine whose one body falls at 1 m/s until step `bad`, where its velocity becomes NaN.
class BlowUp : public Engine {
 public:
  explicit BlowUp(long bad) : bad_(bad) {}
  std::string_view name() const override { return "blowup"; }
  void step() override { ++steps_; }
  double time() const override { return 0.1 * static_cast<double>(steps_); }
  void body_states(std::vector<BodyState>& out) const override {
    out.resize(1);
    out[0].name = "box";
    out[0].position = Vec3(0.0, 0.0, 1.0 - time());
    out[0].velocity = steps_ >= bad_ ? Vec3(0.0, 0.0, std::numeric_limits<double>::quiet_NaN()) : Vec3(0.0, 0.0, -1.0);
  }
  void contacts(std::vector<BodyContact>& out) const override { out.clear(); }

 private:
  long bad_;
  long steps_ = 0;
};

}  // namespace

TEST_CASE("the run loop stops at the step that leaves a state non-finite and names it", "[replay]") {
  BlowUp engine(3);
  std::vector<long> steps_seen, frames_seen;
  RunHooks hooks;
  hooks.step = [&](const StepView& v) { steps_seen.push_back(v.step); };
  hooks.frame = [&](const StepView& v) { frames_seen.push_back(v.step); };
  const RunLoopResult r = run_loop(engine, 0.1, 10, 2, hooks);
  REQUIRE(r.stopped);
  CHECK(r.stopped->step == 3);
  CHECK(r.stopped->t == Approx(0.3).margin(1e-12));
  CHECK(r.stopped->body == "box");
  CHECK(r.stopped->quantity == "velocity");
  CHECK(r.steps == 2);
  CHECK(steps_seen == std::vector<long>{0, 1, 2});  // no hook sees the bad step
  CHECK(frames_seen == std::vector<long>{0, 2});  // step 2 was a frame already
  REQUIRE(r.final_states.size() == 1);
  CHECK(r.final_states[0].velocity.allFinite());
  CHECK(r.final_states[0].position.z() == Approx(0.8).margin(1e-12));  // after step 2
}

TEST_CASE("a run that stops between frames records its last finite state as a frame", "[replay]") {
  BlowUp engine(4);
  std::vector<long> frames_seen;
  RunHooks hooks;
  hooks.frame = [&](const StepView& v) {
    frames_seen.push_back(v.step);
    CHECK(v.states[0].velocity.allFinite());
  };
  const RunLoopResult r = run_loop(engine, 0.1, 10, 5, hooks);
  REQUIRE(r.stopped);
  CHECK(r.stopped->step == 4);
  CHECK(frames_seen == std::vector<long>{0, 3});
}

TEST_CASE("the run loop takes every step and records the start, every k-th step and the last", "[replay]") {
  BlowUp engine(100);
  std::vector<long> frames_seen;
  RunHooks hooks;
  hooks.frame = [&](const StepView& v) { frames_seen.push_back(v.step); };
  const RunLoopResult r = run_loop(engine, 0.1, 7, 3, hooks);
  CHECK_FALSE(r.stopped);
  CHECK(r.steps == 7);
  CHECK(r.final_t == Approx(0.7).margin(1e-12));
  CHECK(frames_seen == std::vector<long>{0, 3, 6, 7});
}

TEST_CASE("a recording of a resting stack holds its contacts and reads back exactly", "[replay]") {
  const Scene scene = fixture("stack_5");
  for (const std::string engine : {"own", "ode", "bullet"}) {
    INFO("engine " << engine);
    const Recording r = record(scene, engine, 24, 8);
    REQUIRE(r.frames.t.size() == 4);  // steps 0, 8, 16, 24
    CHECK(r.shapes.bodies.size() == 5);
    REQUIRE(r.shapes.ground);
    CHECK(r.frames.contacts[0].empty());  // no step yet
    for (std::size_t f = 1; f < r.frames.t.size(); ++f) {
      // Every resting pair touches: the bottom box and the ground, and each box and the next.
      std::vector<bool> touches(5, false);
      for (const BodyContact& c : r.frames.contacts[f]) {
        const int lower = c.body_b == kGround ? -1 : std::min(c.body_a, c.body_b);
        const int upper = c.body_b == kGround ? c.body_a : std::max(c.body_a, c.body_b);
        if (upper == lower + 1) touches[static_cast<std::size_t>(upper)] = true;
        // Normals from B toward A: up when A is the upper body.
        const double up = c.body_a == upper ? 1.0 : -1.0;
        CHECK(c.contact.normal.z() * up == Approx(1.0).margin(1e-6));
        CHECK(std::abs(c.contact.depth) < 1e-3);
      }
      for (std::size_t i = 0; i < 5; ++i) CHECK(touches[i]);
    }

    const Recording back = recording_from_json(json::parse(recording_json(r).dump()), "recording.json");
    CHECK(back.scene == "stack_5");
    CHECK(back.engine == engine);
    CHECK(back.dt == r.dt);
    REQUIRE(back.frames.t.size() == r.frames.t.size());
    for (std::size_t f = 0; f < r.frames.t.size(); ++f) {
      CHECK(back.frames.t[f] == r.frames.t[f]);
      CHECK(back.frames.energy[f] == r.frames.energy[f]);
      for (std::size_t i = 0; i < 5; ++i) {
        CHECK(back.frames.states[f][i].position == r.frames.states[f][i].position);
        CHECK(back.frames.states[f][i].angular_velocity == r.frames.states[f][i].angular_velocity);
      }
      REQUIRE(back.frames.contacts[f].size() == r.frames.contacts[f].size());
      for (std::size_t k = 0; k < r.frames.contacts[f].size(); ++k) {
        const BodyContact& a = r.frames.contacts[f][k];
        const BodyContact& b = back.frames.contacts[f][k];
        CHECK(b.contact.position == a.contact.position);
        CHECK(b.contact.normal == a.contact.normal);
        CHECK(b.contact.depth == a.contact.depth);
        CHECK(b.contact.feature == a.contact.feature);
        CHECK(b.body_a == a.body_a);
        CHECK(b.body_b == a.body_b);
      }
    }
  }
}

TEST_CASE("a malformed recording is refused with the JSON path of the problem", "[replay]") {
  const Recording r = record(fixture("stack_5"), "own", 4, 4);
  json doc = json::parse(recording_json(r).dump());
  doc["frames"][1]["contacts"][0]["body_b"] = "b9";
  CHECK_THROWS_WITH(recording_from_json(doc, "run.json"),
                    Catch::Contains("run.json") && Catch::Contains("frames[1].contacts[0].body_b") &&
                        Catch::Contains("b9"));
  doc = json::parse(recording_json(r).dump());
  doc["frames"][0]["bodies"].erase(4);
  CHECK_THROWS_AS(recording_from_json(doc, "run.json"), InputError);
  doc = json::parse(recording_json(r).dump());
  doc.erase("shapes");
  CHECK_THROWS_WITH(recording_from_json(doc, "run.json"), Catch::Contains("shapes"));
}

TEST_CASE("base64 follows RFC 4648", "[replay]") {
  const auto bytes = [](const std::string& s) { return std::vector<unsigned char>(s.begin(), s.end()); };
  const std::vector<std::pair<std::string, std::string>> vectors = {
      {"", ""}, {"f", "Zg=="}, {"fo", "Zm8="}, {"foo", "Zm9v"}, {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="}, {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    CHECK(base64(bytes(plain)) == encoded);
    CHECK(unbase64(encoded) == bytes(plain));
  }
  CHECK_FALSE(unbase64("Zm9"));    // not a multiple of 4
  CHECK_FALSE(unbase64("Zm9*"));   // not in the alphabet
  CHECK_FALSE(unbase64("Z=9v"));   // padding inside
}

TEST_CASE("a replay page's data holds every frame, body and contact of its recordings", "[replay]") {
  const Scene scene = fixture("stack_5");
  const Recording own = record(scene, "own", 24, 4);
  const Recording ode = record(scene, "ode", 24, 4);
  const json data = replay_data("stack_5", {&own, &ode}, {{0.5, "own / ode: position differs"}});
  check_replay_data(data, "data");
  CHECK(data.at("frame_stride") == 1);
  CHECK(data.at("contact_stride") == 1);
  CHECK(data.at("notes").empty());
  REQUIRE(data.at("engines").size() == 2);
  for (std::size_t e = 0; e < 2; ++e) {
    const Recording& r = e == 0 ? own : ode;
    const json& d = data.at("engines")[e];
    CHECK(d.at("name") == r.engine);
    CHECK(d.at("t").size() == 7);
    const auto states = unbase64(d.at("states").get<std::string>());
    REQUIRE(states);
    CHECK(states->size() == 7 * 5 * 13 * 4);
    std::size_t points = 0;
    for (std::size_t f = 0; f < 7; ++f) {
      CHECK(d.at("contact_counts")[f] == r.frames.contacts[f].size());
      points += r.frames.contacts[f].size();
    }
    CHECK(unbase64(d.at("contacts").get<std::string>())->size() == points * 7 * 4);
    // The first float of the last frame's last body: its x as a little-endian float32.
    const std::size_t at = ((6 * 5) + 4) * 13 * 4;
    const std::uint32_t bits = static_cast<std::uint32_t>((*states)[at]) | static_cast<std::uint32_t>((*states)[at + 1]) << 8 |
                               static_cast<std::uint32_t>((*states)[at + 2]) << 16 |
                               static_cast<std::uint32_t>((*states)[at + 3]) << 24;
    CHECK(std::bit_cast<float>(bits) == static_cast<float>(r.frames.states[6][4].position.x()));
  }
  CHECK(data.at("marks")[0].at("t") == 0.5);
  CHECK(data.at("engines")[0].at("stopped").is_null());

  // A run that blew up says where it stopped.
  Recording stopped = ode;
  stopped.stopped = NonFiniteStop{25, 25 * scene.time.dt, "b3", "velocity", ""};
  const json with_stop = replay_data("stack_5", {&stopped}, {});
  CHECK(with_stop.at("engines")[0].at("stopped").at("body") == "b3");
  CHECK(with_stop.at("engines")[0].at("stopped").at("step") == 25);

  json broken = data;
  broken["engines"][1]["states"] = "AAAA";
  CHECK_THROWS_WITH(check_replay_data(broken, "replay.json"),
                    Catch::Contains("replay.json") && Catch::Contains("engines[1].states"));
}

TEST_CASE("a replay page over its budget keeps every k-th frame or contact set and says so", "[replay]") {
  const Recording r = record(fixture("stack_5"), "bullet", 24, 4);  // 7 frames of 5 bodies
  ReplayBudget budget;
  budget.body_states = 20;  // 35 states: every 2nd frame, and the last
  json data = replay_data("stack_5", {&r}, {}, budget);
  check_replay_data(data, "data");
  CHECK(data.at("frame_stride") == 2);
  CHECK(data.at("engines")[0].at("t") == json({r.frames.t[0], r.frames.t[2], r.frames.t[4], r.frames.t[6]}));
  REQUIRE(data.at("notes").size() == 1);
  CHECK_THAT(data.at("notes")[0].get<std::string>(), Catch::Contains("one recorded frame in 2 is kept"));

  std::size_t points = 0;
  for (const auto& c : r.frames.contacts) points += c.size();
  budget = ReplayBudget{};
  budget.contact_points = (points + 1) / 2;  // about half of them: contacts on every 2nd frame
  data = replay_data("stack_5", {&r}, {}, budget);
  check_replay_data(data, "data");
  CHECK(data.at("contact_stride") == 2);
  const json& counts = data.at("engines")[0].at("contact_counts");
  for (std::size_t f = 0; f < 7; ++f) CHECK(counts[f] == (f % 2 == 0 ? r.frames.contacts[f].size() : 0));
  CHECK_THAT(data.at("notes")[0].get<std::string>(), Catch::Contains("contacts are drawn on one frame in 2"));
}

TEST_CASE("the marks of a replay are where a report's pairs first pass a threshold", "[replay]") {
  const json report = {{"pairs",
                        {{{"engines", {"own", "ode"}}, {"position_passes", 1.5}, {"orientation_passes", 1.2},
                          {"position_threshold", 0.01}, {"orientation_threshold", 0.05}, {"verdict", "chaos"}},
                         {{"engines", {"own", "bullet"}}, {"position_passes", nullptr}, {"orientation_passes", nullptr}},
                         {{"engines", {"ode", "bullet"}}, {"position_passes", 0.25}, {"orientation_passes", nullptr},
                          {"position_threshold", 0.01}, {"verdict", "differ"}}}}};
  const std::vector<ReplayMark> marks = marks_from_report(report);
  REQUIRE(marks.size() == 2);  // own / bullet agree
  CHECK(marks[0].t == 0.25);
  CHECK_THAT(marks[0].label, Catch::Contains("ode / bullet") && Catch::Contains("position") && Catch::Contains("differ"));
  CHECK(marks[1].t == 1.2);
  CHECK_THAT(marks[1].label, Catch::Contains("own / ode") && Catch::Contains("orientation"));
}

TEST_CASE("a replay page is one file: three.js, the data and the viewer inline, no script closed early",
          "[replay]") {
  const Recording r = record(fixture("stack_5"), "own", 4, 4);
  const ThreeJs three{"var THREE = {}; /* three */", "THREE.OrbitControls = function () {}; /* orbit */"};
  const std::string html = replay_html(replay_data("</script><b>stack", {&r}, {}), three);
  CHECK(html.find("/* three */") != std::string::npos);
  CHECK(html.find("/* orbit */") != std::string::npos);
  CHECK(html.find("/*@") == std::string::npos);  // every marker replaced
  CHECK(html.find("<\\/script><b>stack") != std::string::npos);
  // Four scripts, each closed once: the data's "</script>" did not end one early.
  std::size_t closes = 0;
  for (std::size_t at = html.find("</script>"); at != std::string::npos; at = html.find("</script>", at + 1)) ++closes;
  CHECK(closes == 4);
  CHECK(html.find(" src=") == std::string::npos);
}
