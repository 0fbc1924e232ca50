// The reader of the engine protocol's answers (reference/process/protocol.hpp), without a
// process: each kind of broken answer is refused with a message naming the field.
#include <catch2/catch.hpp>

#include "boxpile/reference/process/protocol.hpp"
#include "boxpile/sim/io/scene_loader.hpp"

namespace {

using boxpile::protocol::parse_step;
using boxpile::protocol::ReplyError;
using boxpile::protocol::StepAsk;

const std::string kBody =
    R"({"position": [0, 0, 0.5], "orientation": [1, 0, 0, 0], "velocity": [0, 0, 0], "angular_velocity": [0, 0, 0]})";

std::string step_line(const std::string& bodies, const std::string& extra = "") {
  return R"({"ok": true, "time": 0.01, "bodies": [)" + bodies + "]" + extra + "}";
}

void require_refused(const std::string& line, const StepAsk& ask, const std::string& fragment) {
  INFO(line);
  try {
    parse_step(line, ask);
    FAIL("accepted");
  } catch (const ReplyError& e) {
    CHECK_THAT(e.what(), Catch::Contains(fragment));
  }
}

}  // namespace

TEST_CASE("a step answer is read into states and contacts", "[protocol]") {
  const auto reply = parse_step(
      step_line(kBody, R"(, "engine_seconds": 2e-5, "contacts": [{"a": 0, "b": -1, "position": [0.5, 0.5, 0], "normal": [0, 0, 1], "depth": 1e-5}])"),
      StepAsk{1, true, true});
  CHECK(reply.time == 0.01);
  CHECK(reply.engine_seconds == 2e-5);
  REQUIRE(reply.bodies.size() == 1);
  CHECK(reply.bodies[0].position.z() == 0.5);
  REQUIRE(reply.contacts.size() == 1);
  CHECK(reply.contacts[0].body_b == boxpile::kGround);
  CHECK(reply.contacts[0].contact.depth == 1e-5);
}

TEST_CASE("broken step answers are refused naming what is wrong", "[protocol]") {
  const StepAsk one{1, true, false}, with_contacts{1, true, true};
  require_refused("", one, "is not JSON");
  require_refused("[1, 2]", one, "is an array, not a JSON object");
  require_refused(R"({"time": 0})", one, "has no \"ok\"");
  require_refused(R"({"ok": false, "error": "diverged"})", one, "ok: false: diverged");
  require_refused(step_line(kBody + "," + kBody), one, "\"bodies\" has 2 entries; the scene has 1 bodies");
  require_refused(R"({"ok": true, "time": NaN, "bodies": []})", one, "not finite (NaN)");
  require_refused(R"({"ok": true, "time": 1e400, "bodies": []})", one, "is not JSON");  // beyond a double
  require_refused(R"({"ok": true, "time": null, "bodies": []})", one, "\"time\" is null");
  require_refused(step_line(R"({"position": [0, 0], "orientation": [1, 0, 0, 0], "velocity": [0, 0, 0], "angular_velocity": [0, 0, 0]})"),
                  one, "\"bodies[0].position\" has 2 numbers, not 3");
  require_refused(step_line(R"({"position": [0, 0, 0], "orientation": [2, 0, 0, 0], "velocity": [0, 0, 0], "angular_velocity": [0, 0, 0]})"),
                  one, "\"bodies[0].orientation\" is not a unit quaternion");
  require_refused(step_line(kBody), with_contacts, "has no \"contacts\"");
  require_refused(step_line(kBody, R"(, "contacts": [{"a": 1, "b": -1, "position": [0, 0, 0], "normal": [0, 0, 1], "depth": 0}])"),
                  with_contacts, "\"contacts[0].a\" is 1, not a body index in [0, 0]");
  require_refused(step_line(kBody, R"(, "contacts": [{"a": 0, "b": -1, "position": [0, 0, 0], "normal": [0, 0, 2], "depth": 0}])"),
                  with_contacts, "\"contacts[0].normal\" is not a unit vector");
}

TEST_CASE("a hello is read, and another protocol version is refused", "[protocol]") {
  const auto hello = boxpile::protocol::parse_hello(
      R"({"ok": true, "protocol": 1, "name": "x", "version": "1", "precision": "float32", "contacts": true, "timing": false,)"
      R"( "settings": [{"key": "iterations", "kind": "integer", "unit": "", "min": 1, "max": 100, "default": 10, "what": "w"}]})");
  CHECK(hello.precision == "float32");
  CHECK(hello.contacts);
  REQUIRE(hello.settings.size() == 1);
  CHECK(hello.settings[0].max == 100);
  CHECK_THROWS_WITH(boxpile::protocol::parse_hello(R"({"ok": true, "protocol": 2})"), Catch::Contains("speaks protocol 2"));
  CHECK_THROWS_WITH(boxpile::protocol::parse_hello(
                        R"({"ok": true, "protocol": 1, "name": "x", "version": "1", "precision": "half", "contacts": true, "timing": false})"),
                    Catch::Contains("not float32 or float64"));
}

TEST_CASE("the resolved scene carries our mass properties and the combined materials", "[protocol]") {
  boxpile::Scene scene = boxpile::load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/bone_hits_pile.json");
  const nlohmann::json s = boxpile::protocol::scene_message(scene);
  const std::vector<boxpile::RigidBody> bodies = boxpile::make_bodies(scene);
  REQUIRE(s["bodies"].size() == bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    CHECK(s["bodies"][i]["mass"].get<double>() == bodies[i].mass);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) CHECK(s["bodies"][i]["inertia"][r][c].get<double>() == bodies[i].inertia_body(r, c));
    }
  }
  // The bone is on its wire; the scene turns restitution off, so every restitution is 0.
  int wired = 0;
  for (const auto& b : s["bodies"]) wired += b.contains("wire") ? 1 : 0;
  CHECK(wired == 1);
  CHECK_FALSE(scene.effects.restitution);
  for (const auto& b : s["bodies"]) CHECK(b["restitution"].get<double>() == 0.0);
  CHECK(s["gravity"][2].get<double>() == -9.81);
}
