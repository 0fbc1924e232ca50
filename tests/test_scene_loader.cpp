// The scene and query loaders: valid files load with the right values and defaults, and every kind
// of bad input gives an InputError naming the file, the JSON path and what is wrong.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/sim/io/scene_loader.hpp"

using namespace boxpile;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace {

const std::string kSource = "inline_scene.json";
const std::string kFixtures = BOXPILE_FIXTURES_DIR;

// Values read from JSON and normalised: a few ulps of rounding at most.
constexpr double kTight = 1e-12;

// Two bodies: a unit cube on the ground and a compound of two cubes resting exactly on it.
json base_scene() {
  return R"({
    "name": "two",
    "ground": {"normal": [0, 0, 1], "offset": 0},
    "bodies": [
      {"name": "b0", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5]},
      {"name": "b1", "mass": 2,
       "boxes": [{"half_extents": [0.5, 0.5, 0.5]},
                 {"half_extents": [0.5, 0.5, 0.5], "offset": [1, 0, 0]}],
       "position": [0, 0, 1.5]}
    ],
    "time": {"dt": 0.01, "duration": 1}
  })"_json;
}

// Checks that loading fails with an InputError at `path` whose message names the file, the
// path and contains `word`.
void check_error(const std::function<Scene()>& load, const std::string& source,
                 const std::string& path, const std::string& word) {
  try {
    load();
    FAIL("loaded without an error; expected one at \"" << path << "\" about \"" << word << "\"");
  } catch (const InputError& e) {
    const std::string message = e.what();
    INFO("message: " << message);
    CHECK(e.file() == source);
    CHECK(e.json_path() == path);
    CHECK_THAT(message, Contains(source) && Contains(path) && Contains(word));
  }
}

void check_scene_error(const std::string& text, const std::string& path, const std::string& word) {
  INFO("scene: " << text);
  check_error([&] { return parse_scene(text, kSource); }, kSource, path, word);
}

// A change to the base scene and the error it must cause.
struct BadCase {
  std::string label;
  std::function<void(json&)> edit;
  std::string path;
  std::string word;
};

void run_cases(const std::vector<BadCase>& cases) {
  for (const BadCase& c : cases) {
    DYNAMIC_SECTION(c.label) {
      json scene = base_scene();
      c.edit(scene);
      check_scene_error(scene.dump(2), c.path, c.word);
    }
  }
}

json& body(json& scene, int i) { return scene["bodies"][static_cast<std::size_t>(i)]; }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Valid scenes

TEST_CASE("a full scene loads with every value", "[scene]") {
  const Scene s = parse_scene(R"({
    "name": "full", "note": "every key once",
    "gravity": [0, -1, -9],
    "ground": {"normal": [0, 0, 2], "offset": -1},
    "material": {"friction": 0.7, "restitution": 0.2},
    "effects": ["gravity", "damping", "gyroscopic"],
    "damping": {"linear": 0.1, "angular": 0.3},
    "bodies": [
      {"name": "cube", "mass": 2, "half_extents": [0.5, 1, 1.5], "position": [1, 2, 3],
       "orientation": [2, 0, 0, 0], "velocity": [1, 0, 0], "angular_velocity": [0, 0, 2],
       "material": {"friction": 0.1}},
      {"name": "floor", "fixed": true, "half_extents": [10, 10, 0.5], "position": [0, 0, -1.5]},
      {"name": "l", "mass": 3,
       "boxes": [{"half_extents": [1, 0.5, 0.25]},
                 {"half_extents": [0.25, 0.5, 0.75], "offset": [0.75, 0, 1],
                  "orientation": [0, 0, 0, 3]}],
       "position": [10, 0, 5]}
    ],
    "solver": {"method": "impulse", "collision_passes": 7, "contact_passes": 15.0,
               "shock_propagation": false, "integrator": "semi_implicit_euler"},
    "collision": {"reduce_to_four": true, "margin": 0.01, "reuse_contacts": false},
    "time": {"dt": 0.002, "duration": 2.5},
    "allow_initial_overlap": false
  })", kSource);

  CHECK(s.name == "full");
  CHECK(s.note == "every key once");
  CHECK(s.source == kSource);
  CHECK(s.gravity == Vec3(0, -1, -9));
  REQUIRE(s.ground);
  CHECK(s.ground->normal.isApprox(Vec3::UnitZ(), kTight));  // normalised
  CHECK(s.ground->offset == -1.0);
  CHECK(s.material.friction == 0.7);
  CHECK(s.material.restitution == 0.2);
  CHECK(s.effects.gravity);
  CHECK_FALSE(s.effects.friction);
  CHECK_FALSE(s.effects.restitution);
  CHECK(s.effects.damping);
  CHECK(s.effects.gyroscopic);
  CHECK(s.damping.linear == 0.1);
  CHECK(s.damping.angular == 0.3);

  REQUIRE(s.bodies.size() == 3);
  const BodyDesc& cube = s.bodies[0];
  CHECK(cube.name == "cube");
  CHECK(cube.mass == 2.0);
  REQUIRE(cube.boxes.size() == 1);
  CHECK(cube.boxes[0].half_extents == Vec3(0.5, 1, 1.5));
  CHECK(cube.boxes[0].offset == Vec3::Zero());
  CHECK(cube.frame.position == Vec3(1, 2, 3));
  CHECK(cube.frame.orientation.isApprox(Quat::Identity(), kTight));  // [2, 0, 0, 0] normalised
  CHECK(cube.velocity == Vec3(1, 0, 0));
  CHECK(cube.angular_velocity == Vec3(0, 0, 2));
  REQUIRE(cube.material);
  CHECK(cube.material->friction == 0.1);
  CHECK(cube.material->restitution == 0.2);  // not given: the scene's
  CHECK_FALSE(cube.fixed);

  const BodyDesc& floor = s.bodies[1];
  CHECK(floor.fixed);
  CHECK(floor.mass == 0.0);  // a fixed body without a mass
  CHECK_FALSE(floor.material);

  const BodyDesc& l = s.bodies[2];
  REQUIRE(l.boxes.size() == 2);
  CHECK(l.boxes[1].offset == Vec3(0.75, 0, 1));
  CHECK(std::abs(l.boxes[1].orientation.z() - 1.0) < kTight);  // [0, 0, 0, 3] normalised

  CHECK(s.solver.method == "impulse");
  CHECK(s.solver.collision_passes == 7);
  CHECK(s.solver.contact_passes == 15);
  CHECK_FALSE(s.solver.shock_propagation);
  CHECK(s.solver.integrator == PositionIntegrator::SemiImplicitEuler);
  CHECK(s.collision.reduce_to_four);
  CHECK(s.collision.margin == 0.01);
  CHECK_FALSE(s.collision.reuse_contacts);
  CHECK(s.time.dt == 0.002);
  CHECK(s.time.duration == 2.5);
  CHECK_FALSE(s.allow_initial_overlap);
}

TEST_CASE("a minimal scene gets the documented defaults", "[scene]") {
  const Scene s = parse_scene(R"({
    "name": "one",
    "bodies": [{"name": "b", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0]}],
    "time": {"dt": 0.01, "duration": 0}
  })", kSource);
  CHECK(s.note.empty());
  CHECK(s.gravity == Vec3(0, 0, -9.81));
  CHECK_FALSE(s.ground);
  CHECK(s.material.friction == 0.5);
  CHECK(s.material.restitution == 0.0);
  // Without "effects": gravity, friction and restitution on; damping and gyroscopic off.
  CHECK(s.effects.gravity);
  CHECK(s.effects.friction);
  CHECK(s.effects.restitution);
  CHECK_FALSE(s.effects.damping);
  CHECK_FALSE(s.effects.gyroscopic);
  CHECK(s.damping.linear == 0.0);
  CHECK(s.damping.angular == 0.0);
  CHECK(s.solver.method == "impulse");
  CHECK(s.solver.collision_passes == 5);
  CHECK(s.solver.contact_passes == 10);
  CHECK(s.solver.shock_propagation);
  CHECK(s.solver.integrator == PositionIntegrator::SemiImplicitEuler);
  CHECK_FALSE(s.collision.reduce_to_four);
  CHECK(s.collision.margin == 0.0);
  CHECK(s.collision.reuse_contacts);
  CHECK_FALSE(s.allow_initial_overlap);

  const BodyDesc& b = s.bodies.at(0);
  CHECK(b.frame.orientation.isApprox(Quat::Identity(), 0.0));
  CHECK(b.velocity == Vec3::Zero());
  CHECK(b.angular_velocity == Vec3::Zero());
  CHECK_FALSE(b.fixed);
  CHECK_FALSE(b.material);
}

TEST_CASE("an empty effects list leaves only contact; damping may be set without its effect",
          "[scene]") {
  json scene = base_scene();
  scene["effects"] = json::array();
  scene["damping"] = {{"linear", 0.5}};
  const Scene s = parse_scene(scene.dump(), kSource);
  CHECK_FALSE(s.effects.gravity);
  CHECK_FALSE(s.effects.friction);
  CHECK_FALSE(s.effects.restitution);
  CHECK_FALSE(s.effects.damping);
  CHECK(s.damping.linear == 0.5);  // kept, unused until "damping" is listed
}

TEST_CASE("a stack written in decimal loads: touching is not overlapping", "[scene]") {
  // Thin boxes at z = 0.05, 0.15, ..., 0.95: the decimals are not exact binary fractions, so
  // neighbours touch only up to rounding.
  json scene = base_scene();
  scene["bodies"] = json::array();
  for (int k = 0; k < 10; ++k) {
    std::string name = "b";
    name += std::to_string(k);
    scene["bodies"].push_back({{"name", name}, {"mass", 0.1},
                               {"half_extents", {0.3, 0.3, 0.05}},
                               {"position", {0.1 * 3, 0.7, 0.05 + 0.1 * k}}});
  }
  const Scene s = parse_scene(scene.dump(), kSource);
  CHECK(s.bodies.size() == 10);
}

TEST_CASE("allow_initial_overlap lets overlapping bodies load", "[scene]") {
  json scene = base_scene();
  body(scene, 1)["position"] = {0, 0, 1.25};
  scene["allow_initial_overlap"] = true;
  const Scene s = parse_scene(scene.dump(), kSource);
  CHECK(s.allow_initial_overlap);
  // Two fixed bodies may overlap (and a fixed body the ground): they never move apart.
  json fixed = base_scene();
  body(fixed, 0)["fixed"] = true;
  body(fixed, 0)["position"] = {0, 0, 0.25};
  body(fixed, 1)["fixed"] = true;
  body(fixed, 1)["position"] = {0, 0, 1.25};
  CHECK_NOTHROW(parse_scene(fixed.dump(), kSource));
}

TEST_CASE("the fixture scenes load", "[scene]") {
  const Scene stack = load_scene(kFixtures + "/scenes/stack_5.json");
  CHECK(stack.name == "stack_5");
  REQUIRE(stack.bodies.size() == 5);
  for (std::size_t k = 0; k < 5; ++k) {
    CHECK(stack.bodies[k].mass == 1.0);
    CHECK(stack.bodies[k].boxes.at(0).half_extents == Vec3::Constant(0.5));
    CHECK(stack.bodies[k].frame.position == Vec3(0, 0, 0.5 + static_cast<double>(k)));
  }
  CHECK(stack.effects.gravity);
  CHECK(stack.effects.friction);
  CHECK_FALSE(stack.effects.restitution);
  CHECK(stack.material.friction == 0.5);
  CHECK(stack.material.restitution == 0.0);
  CHECK(stack.time.dt == 1.0 / 240.0);
  CHECK(stack.time.duration == 5.0);
  REQUIRE(stack.ground);

  const Scene l = load_scene(kFixtures + "/scenes/compound_on_ground.json");
  REQUIRE(l.bodies.size() == 1);
  CHECK(l.bodies[0].boxes.size() == 2);
  REQUIRE(l.ground);
}

// ---------------------------------------------------------------------------------------------
// Bad scenes: every case names the file, the JSON path and what is wrong

TEST_CASE("JSON syntax errors give line and column", "[scene]") {
  check_scene_error("{\n  \"name\": \"x\",\n  \"bodies\": [1, 2,,]\n}", "", "line 3, column 19");
  check_scene_error("{\n  \"name\": tru\n}", "", "line 2, column 14");
  check_scene_error("{\"name\": \"x\"", "", "line 1, column 13");  // input ends early
  check_scene_error("", "", "line 1, column 1");
  // Columns count characters, not bytes: the 2-byte "é" is one column.
  check_scene_error("{\"é\": 1 2}", "", "line 1, column 9");
}

TEST_CASE("a file that cannot be read names the reason", "[scene]") {
  const std::string missing = kFixtures + "/no_such_scene.json";
  check_error([&] { return load_scene(missing); }, missing, "", "cannot open");
  check_error([&] { return load_scene(kFixtures); }, kFixtures, "", "cannot open");
}

TEST_CASE("wrong types say what was expected and what was found", "[scene]") {
  run_cases({
      {"top level", [](json& s) { s = json::array({1, 2}); }, "", "expected object, got array"},
      {"mass", [](json& s) { body(s, 0)["mass"] = "heavy"; }, "bodies[0].mass",
       "expected number, got string \"heavy\""},
      {"fixed", [](json& s) { body(s, 0)["fixed"] = 1; }, "bodies[0].fixed",
       "expected boolean, got number 1"},
      {"name", [](json& s) { s["name"] = 5; }, "name", "expected string"},
      {"bodies", [](json& s) { s["bodies"] = json::object(); }, "bodies", "expected array"},
      {"vector element", [](json& s) { body(s, 0)["position"][2] = nullptr; },
       "bodies[0].position[2]", "expected number, got null"},
      {"ground", [](json& s) { s["ground"] = true; }, "ground", "expected object"},
      {"passes", [](json& s) { s["solver"] = {{"contact_passes", 2.5}}; },
       "solver.contact_passes", "integer"},
      {"effects", [](json& s) { s["effects"] = "gravity"; }, "effects", "expected array"},
  });
}

TEST_CASE("missing required keys are named", "[scene]") {
  run_cases({
      {"name", [](json& s) { s.erase("name"); }, "", "missing required key \"name\""},
      {"bodies", [](json& s) { s.erase("bodies"); }, "", "missing required key \"bodies\""},
      {"time", [](json& s) { s.erase("time"); }, "", "missing required key \"time\""},
      {"dt", [](json& s) { s["time"].erase("dt"); }, "time", "missing required key \"dt\""},
      {"body name", [](json& s) { body(s, 0).erase("name"); }, "bodies[0]",
       "missing required key \"name\""},
      {"mass", [](json& s) { body(s, 0).erase("mass"); }, "bodies[0]",
       "missing required key \"mass\""},
      {"position", [](json& s) { body(s, 1).erase("position"); }, "bodies[1]",
       "missing required key \"position\""},
      {"box half extents", [](json& s) { body(s, 1)["boxes"][1].erase("half_extents"); },
       "bodies[1].boxes[1]", "missing required key \"half_extents\""},
  });
}

TEST_CASE("unknown keys name the closest valid key", "[scene]") {
  run_cases({
      {"body key", [](json& s) {
         body(s, 0)["half_extent"] = body(s, 0)["half_extents"];
         body(s, 0).erase("half_extents");
       }, "bodies[0]", "unknown key \"half_extent\"; did you mean \"half_extents\"?"},
      {"top level", [](json& s) { s["gravty"] = {0, 0, -1}; }, "",
       "unknown key \"gravty\"; did you mean \"gravity\"?"},
      {"transposed", [](json& s) { s["time"]["td"] = 1; }, "time", "did you mean \"dt\"?"},
      {"nested", [](json& s) { s["solver"] = {{"colision_passes", 3}}; }, "solver",
       "did you mean \"collision_passes\"?"},
      {"nothing close", [](json& s) { s["zzz"] = 1; }, "",
       "unknown key \"zzz\"; valid keys are \"name\""},
  });
}

TEST_CASE("numbers must be finite", "[scene]") {
  // JSON has no NaN or Inf literals; a literal beyond the range of a double is how they arrive.
  std::string text = base_scene().dump();
  const auto at = text.find("[0.5,0.5,0.5]");
  REQUIRE(at != std::string::npos);
  check_scene_error(text.replace(at, 13, "[0.5,1e999,0.5]"), "bodies[0].half_extents[1]",
                    "finite");
  json scene = base_scene();
  scene["gravity"] = {0, 0, -1};
  std::string g = scene.dump();
  g.replace(g.find("-1]"), 2, "-1e400");
  check_scene_error(g, "gravity[2]", "finite");
  json mass = base_scene();
  mass["time"]["duration"] = 1;
  std::string m = mass.dump();
  m.replace(m.find("\"duration\":1"), 12, "\"duration\":1e309");
  check_scene_error(m, "time.duration", "finite");
}

TEST_CASE("arrays of the wrong length", "[scene]") {
  run_cases({
      {"half extents", [](json& s) { body(s, 0)["half_extents"] = {1, 1}; },
       "bodies[0].half_extents", "expected an array of 3 elements, got 2"},
      {"orientation", [](json& s) { body(s, 0)["orientation"] = {1, 0, 0}; },
       "bodies[0].orientation", "expected an array of 4 elements, got 3"},
      {"gravity", [](json& s) { s["gravity"] = {0, 0, -9.81, 0}; }, "gravity",
       "expected an array of 3 elements, got 4"},
  });
}

TEST_CASE("values out of range", "[scene]") {
  run_cases({
      {"negative mass", [](json& s) { body(s, 0)["mass"] = -1; }, "bodies[0].mass",
       "must be in [1e-06, 1e+06] kg, got -1"},
      {"zero mass", [](json& s) { body(s, 1)["mass"] = 0; }, "bodies[1].mass", "must be in [1e-06, 1e+06] kg"},
      {"negative extent", [](json& s) { body(s, 0)["half_extents"] = {0.5, -0.5, 0.5}; },
       "bodies[0].half_extents[1]", "must be > 0, got -0.5"},
      {"zero extent in a compound",
       [](json& s) { body(s, 1)["boxes"][0]["half_extents"] = {0.5, 0.5, 0}; },
       "bodies[1].boxes[0].half_extents[2]", "must be > 0, got 0"},
      {"zero quaternion", [](json& s) { body(s, 0)["orientation"] = {0, 0, 0, 0}; },
       "bodies[0].orientation", "zero quaternion"},
      {"zero box quaternion", [](json& s) { body(s, 1)["boxes"][1]["orientation"] = {0, 0, 0, 0}; },
       "bodies[1].boxes[1].orientation", "zero quaternion"},
      {"zero ground normal", [](json& s) { s["ground"]["normal"] = {0, 0, 0}; },
       "ground.normal", "zero vector"},
      {"negative friction", [](json& s) { s["material"] = {{"friction", -0.1}}; },
       "material.friction", "must be in [0, 1000], got -0.1"},
      {"negative body friction", [](json& s) { body(s, 0)["material"] = {{"friction", -1}}; },
       "bodies[0].material.friction", "must be in [0, 1000]"},
      {"restitution above 1", [](json& s) { s["material"] = {{"restitution", 1.5}}; },
       "material.restitution", "must be in [0, 1], got 1.5"},
      {"negative restitution", [](json& s) { body(s, 1)["material"] = {{"restitution", -0.5}}; },
       "bodies[1].material.restitution", "must be in [0, 1]"},
      {"zero dt", [](json& s) { s["time"]["dt"] = 0; }, "time.dt", "must be a number in (0, 1] s, got 0"},
      {"negative dt", [](json& s) { s["time"]["dt"] = -0.01; }, "time.dt", "must be a number in (0, 1] s"},
      {"negative duration", [](json& s) { s["time"]["duration"] = -1; }, "time.duration",
       "must be a finite number >= 0 s, got -1"},
      {"zero collision passes", [](json& s) { s["solver"] = {{"collision_passes", 0}}; },
       "solver.collision_passes", "must be in [1, 64], got 0"},
      {"negative contact passes", [](json& s) { s["solver"] = {{"contact_passes", -3}}; },
       "solver.contact_passes", "must be in [1, 64], got -3"},
      {"negative margin", [](json& s) { s["collision"] = {{"margin", -0.1}}; },
       "collision.margin", "must be in [0, 1000] m"},
      {"negative damping", [](json& s) { s["damping"] = {{"angular", -2}}; }, "damping.angular",
       "must be in [0, 1e+06] 1/s"},
      {"empty scene name", [](json& s) { s["name"] = ""; }, "name", "must not be empty"},
      {"empty body name", [](json& s) { body(s, 1)["name"] = ""; }, "bodies[1].name",
       "must not be empty"},
      {"moving fixed body", [](json& s) {
         body(s, 0)["fixed"] = true;
         body(s, 0)["velocity"] = {1, 0, 0};
       }, "bodies[0].velocity", "fixed body does not move"},
  });
}

TEST_CASE("unknown names in a vocabulary", "[scene]") {
  run_cases({
      {"misspelt effect", [](json& s) { s["effects"] = {"gravity", "frction"}; }, "effects[1]",
       "unknown effect \"frction\"; did you mean \"friction\"?"},
      {"foreign effect", [](json& s) { s["effects"] = {"wind"}; }, "effects[0]",
       "unknown effect \"wind\"; expected one of \"gravity\", \"friction\""},
      {"effect twice", [](json& s) { s["effects"] = {"gravity", "friction", "gravity"}; },
       "effects[2]", "listed twice"},
      {"solver method", [](json& s) { s["solver"] = {{"method", "impluse"}}; }, "solver.method",
       "unknown solver method \"impluse\"; did you mean \"impulse\"?"},
      {"integrator", [](json& s) { s["solver"] = {{"integrator", "rk4"}}; }, "solver.integrator",
       "unknown integrator \"rk4\"; expected one of \"explicit_euler\""},
  });
}

TEST_CASE("body names are unique; a key appears once per object", "[scene]") {
  run_cases({
      {"duplicate name", [](json& s) { body(s, 1)["name"] = "b0"; }, "bodies[1].name",
       "duplicate body name \"b0\" (also bodies[0])"},
  });
  // nlohmann would keep the last of two equal keys: the loader refuses instead.
  check_scene_error(R"({"name": "x", "bodies": [{"name": "b", "mass": 1, "mass": 2,
                       "half_extents": [1, 1, 1], "position": [0, 0, 0]}],
                       "time": {"dt": 0.1, "duration": 1}})",
                    "bodies[0].mass", "duplicate key \"mass\"");
  check_scene_error(R"({"name": "x", "name": "y"})", "name", "duplicate key");
  check_scene_error(R"({"name": "x", "bodies": [{}, {"boxes": [{}, {"offset": [0, 0, 0],
                       "offset": [1, 0, 0]}]}]})",
                    "bodies[1].boxes[1].offset", "duplicate key \"offset\"");
  // The same keys in different objects are fine, and so is the path after nested arrays.
  check_scene_error(R"({"name": "x", "bodies": [{"name": "a"}, {"name": "b", "boxes": [[1], [2]],
                       "boxes": 1}]})",
                    "bodies[1].boxes", "duplicate key");
  check_scene_error(R"({"name": "x", "bodies": [{"name": "a", "mass": 1, "position": [0, 0, 0],
                       "boxes": [{"half_extents": [1, 1, 1]}, {"half_extents": [1e999, 1, 1]}]}],
                       "time": {"dt": 1, "duration": 1}})",
                    "bodies[0].boxes[1].half_extents[0]", "finite");
}

TEST_CASE("a body is one box or a compound, of 1 to kMaxBoxesPerBody boxes", "[scene]") {
  run_cases({
      {"both", [](json& s) { body(s, 1)["half_extents"] = {1, 1, 1}; }, "bodies[1]",
       "has both \"half_extents\" (one box) and \"boxes\""},
      {"neither", [](json& s) { body(s, 0).erase("half_extents"); }, "bodies[0]",
       "missing required key \"half_extents\" (one box) or \"boxes\""},
      {"empty compound", [](json& s) { body(s, 1)["boxes"] = json::array(); },
       "bodies[1].boxes", "must not be empty"},
      {"too many boxes", [](json& s) {
         json boxes = json::array();
         for (int k = 0; k <= kMaxBoxesPerBody; ++k) {
           boxes.push_back({{"half_extents", {0.1, 0.1, 0.1}}, {"offset", {0.2 * k, 0, 0}}});
         }
         body(s, 1)["boxes"] = boxes;
       }, "bodies[1].boxes", "at most 16 boxes per body, got 17"},
  });
}

TEST_CASE("bodies that overlap at the start are an error", "[scene]") {
  run_cases({
      {"two bodies", [](json& s) { body(s, 1)["position"] = {0, 0, 1.25}; }, "bodies[1]",
       "body \"b1\" overlaps body \"b0\" (bodies[0]) by 0.25 m"},
      {"the ground", [](json& s) { body(s, 0)["position"] = {5, 5, 0.25}; }, "bodies[0]",
       "body \"b0\" overlaps the ground by 0.25 m"},
      {"a tilted ground", [](json& s) {
         s["ground"] = {{"normal", {1, 0, 1}}, {"offset", 0}};
       }, "bodies[0]", "overlaps the ground"},
      {"a box of a compound", [](json& s) {
         // b1's second box at x = 1 reaches into a cube placed beside b0.
         s["bodies"].push_back({{"name", "b2"}, {"mass", 1}, {"half_extents", {0.5, 0.5, 0.5}},
                                {"position", {1.5, 0, 1.5}}});
       }, "bodies[2]", "body \"b2\" overlaps body \"b1\""},
      {"a fixed and a free body", [](json& s) {
         body(s, 0)["fixed"] = true;
         body(s, 1)["position"] = {0, 0, 1.4};
       }, "bodies[1]", "overlaps body \"b0\""},
  });
  // The message says how to allow it.
  json scene = base_scene();
  body(scene, 1)["position"] = {0, 0, 1.25};
  check_scene_error(scene.dump(), "bodies[1]", "\"allow_initial_overlap\": true");
}

// ---------------------------------------------------------------------------------------------
// Wires (the bone)

namespace {

// b1 (the compound at z = 1.5) hangs from a wire along x at z = 2 by the point 0.5 m above its
// body origin.
json wired_scene() {
  json s = base_scene();
  body(s, 1)["wire"] = {{"from", {-2, 0, 2}}, {"to", {3, 0, 2}}, {"anchor", {0, 0, 0.5}}};
  return s;
}

}  // namespace

TEST_CASE("a body may hang from a wire", "[scene][wire]") {
  const Scene s = parse_scene(wired_scene().dump(), kSource);
  REQUIRE(s.bodies.size() == 2);
  CHECK_FALSE(s.bodies[0].wire);
  REQUIRE(s.bodies[1].wire);
  CHECK(s.bodies[1].wire->from == Vec3(-2, 0, 2));
  CHECK(s.bodies[1].wire->to == Vec3(3, 0, 2));
  CHECK(s.bodies[1].wire->anchor == Vec3(0, 0, 0.5));
  CHECK_FALSE(s.bodies[1].fixed);

  SECTION("the anchor may start at an end of the wire") {
    json scene = wired_scene();
    body(scene, 1)["wire"]["from"] = {0, 0, 2};
    CHECK_NOTHROW(parse_scene(scene.dump(), kSource));
  }
  SECTION("the anchor is placed by the body's orientation") {
    // Turned 90 degrees about x, the anchor (0, 0, 0.5) of the body frame is (0, -0.5, 1.5) in
    // the world; the cubes of the compound look the same turned.
    json scene = wired_scene();
    body(scene, 1)["orientation"] = {std::sqrt(0.5), std::sqrt(0.5), 0, 0};
    body(scene, 1)["wire"]["from"] = {0, -0.5, 1.5};
    body(scene, 1)["wire"]["to"] = {3, -0.5, 4.5};
    const Scene turned = parse_scene(scene.dump(), kSource);
    REQUIRE(turned.bodies[1].wire);
    body(scene, 1)["wire"]["anchor"] = {0, 0.5, 0};  // now (0, 0, 2): off this wire
    check_scene_error(scene.dump(), "bodies[1].wire.anchor", "off the wire");
  }
  SECTION("a wire written in decimal holds an anchor that is on it up to rounding") {
    // (0.1 + 0.2) and 0.3 differ by 5.6e-17: far inside the 1e-9 m tolerance.
    json scene = wired_scene();
    body(scene, 1)["position"] = {0, 0, 1.5};
    body(scene, 1)["wire"] = {{"from", {-0.1, 0, 0.1 + 0.2 + 1.7}}, {"to", {0.7, 0, 2}},
                              {"anchor", {0, 0, 0.5}}};
    CHECK_NOTHROW(parse_scene(scene.dump(), kSource));
  }
}

TEST_CASE("bad wires name the path and say what is wrong", "[scene][wire]") {
  auto wire = [](json& s) -> json& { return body(s, 1)["wire"]; };
  const std::vector<BadCase> cases = {
      {"zero length", [&](json& s) { wire(s)["to"] = {-2, 0, 2}; }, "bodies[1].wire",
       "zero-length wire"},
      {"anchor beside the wire", [&](json& s) { wire(s)["anchor"] = {0, 0.25, 0.5}; },
       "bodies[1].wire.anchor", "the anchor starts 0.25 m off the wire (at [0, 0.25, 2]"},
      {"anchor beyond an end", [&](json& s) { wire(s)["to"] = {-1, 0, 2}; },
       "bodies[1].wire.anchor", "the anchor starts 1 m off the wire"},
      {"anchor a nanometre and a half off",
       [&](json& s) { wire(s)["anchor"] = {0, 0, 0.5 + 1.5e-9}; }, "bodies[1].wire.anchor",
       "within 1e-09 m"},
      {"fixed body", [](json& s) {
         body(s, 0)["fixed"] = true;
         body(s, 0)["wire"] = {{"from", {0, 0, 0}}, {"to", {0, 0, 1}}, {"anchor", {0, 0, 0}}};
       }, "bodies[0].wire", "a fixed body cannot slide on a wire"},
      {"missing anchor", [&](json& s) { wire(s).erase("anchor"); }, "bodies[1].wire",
       "missing required key \"anchor\""},
      {"misspelt key", [&](json& s) {
         wire(s)["ancor"] = wire(s)["anchor"];
         wire(s).erase("anchor");
       }, "bodies[1].wire", "did you mean \"anchor\"?"},
      {"not finite", [&](json& s) { wire(s)["from"] = {0, "x", 0}; }, "bodies[1].wire.from[1]",
       "expected number"},
      {"not an object", [&](json& s) { wire(s) = {1, 2, 3}; }, "bodies[1].wire", "expected object"},
  };
  for (const BadCase& c : cases) {
    DYNAMIC_SECTION(c.label) {
      json scene = wired_scene();
      c.edit(scene);
      check_scene_error(scene.dump(2), c.path, c.word);
    }
  }
}

TEST_CASE("the bad fixture files give their errors", "[scene]") {
  struct FileCase {
    std::string file, path, word;
  };
  const std::vector<FileCase> cases = {
      {"negative_extent.json", "bodies[0].half_extents[1]", "must be > 0"},
      {"syntax_error.json", "", "line 6, column 5"},
      {"unknown_key.json", "bodies[1]", "did you mean \"half_extents\"?"},
      {"overlap.json", "bodies[1]", "overlaps body \"bottom\""},
      {"missing_key.json", "bodies[0]", "missing required key \"position\""},
      {"zero_quaternion.json", "bodies[0].orientation", "zero quaternion"},
      {"unknown_effect.json", "effects[1]", "did you mean \"friction\"?"},
      {"duplicate_name.json", "bodies[1].name", "duplicate body name"},
  };
  for (const FileCase& c : cases) {
    DYNAMIC_SECTION(c.file) {
      const std::string path = kFixtures + "/bad/" + c.file;
      check_error([&] { return load_scene(path); }, path, c.path, c.word);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Contact queries

namespace {

void check_query_error(const std::string& text, const std::string& path, const std::string& word) {
  INFO("query: " << text);
  try {
    parse_query(text, kSource);
    FAIL("loaded without an error; expected one at \"" << path << "\" about \"" << word << "\"");
  } catch (const InputError& e) {
    const std::string message = e.what();
    INFO("message: " << message);
    CHECK(e.json_path() == path);
    CHECK_THAT(message, Contains(kSource) && Contains(path) && Contains(word));
  }
}

}  // namespace

TEST_CASE("box-box and box-plane queries load", "[scene][query]") {
  const ContactQuery q = parse_query(R"({
    "name": "yawed", "note": "why this case exists",
    "a": {"half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.9], "orientation": [0, 0, 0, 2]},
    "b": {"half_extents": [1, 2, 3], "position": [0, 0, 0]}
  })", kSource);
  CHECK(q.source == kSource);
  CHECK(q.a.half_extents == Vec3::Constant(0.5));
  CHECK(q.a.pose.position == Vec3(0, 0, 0.9));
  CHECK(std::abs(q.a.pose.orientation.z() - 1.0) < kTight);
  REQUIRE(q.b);
  CHECK_FALSE(q.plane);
  CHECK(q.b->half_extents == Vec3(1, 2, 3));
  CHECK(q.b->pose.orientation.isApprox(Quat::Identity(), 0.0));

  const ContactQuery p = parse_query(R"({
    "a": {"half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.4]},
    "b": {"plane": {"normal": [0, 3, 4], "offset": 0.5}}
  })", kSource);
  CHECK_FALSE(p.b);
  REQUIRE(p.plane);
  CHECK(p.plane->normal.isApprox(Vec3(0, 0.6, 0.8), kTight));
  CHECK(p.plane->offset == 0.5);
}

TEST_CASE("bad queries follow the scene rules", "[scene][query]") {
  const std::string b = R"("b": {"half_extents": [1, 1, 1], "position": [0, 0, 0]})";
  check_query_error(R"({"a": {"half_extents": [0.5, 0.5, 0.5]}, )" + b + "}", "a",
                    "missing required key \"position\"");
  check_query_error(R"({"a": {"half_extent": [1, 1, 1], "position": [0, 0, 0]}, )" + b + "}",
                    "a", "did you mean \"half_extents\"?");
  check_query_error(R"({"a": {"half_extents": [1, -1, 1], "position": [0, 0, 0]}, )" + b + "}",
                    "a.half_extents[1]", "must be > 0");
  check_query_error(R"({"a": {"half_extents": [1, 1, 1], "position": [0, 0, 0],
                              "orientation": [0, 0, 0, 0]}, )" + b + "}",
                    "a.orientation", "zero quaternion");
  check_query_error(R"({"a": {"half_extents": [1, 1, 1], "position": [0, 0, 0]},
                        "b": {"plane": {"normal": [0, 0, 0]}}})",
                    "b.plane.normal", "zero vector");
  check_query_error(R"({"a": {"half_extents": [1, 1, 1], "position": [0, 0, 0]},
                        "b": {"plane": {}, "position": [0, 0, 0]}})",
                    "b", "unknown key \"position\"");
  check_query_error(R"({"a": {"half_extents": [1, 1, 1], "position": [0, 0, 0]}})", "",
                    "missing required key \"b\"");
  check_query_error(R"({"a": {"half_extents": [1, 1, 1], "position": [0, 0, 0]}, )" + b +
                        R"(, "note": 3})",
                    "note", "expected string");
  check_query_error("{\"a\": {\n", "", "line 2, column 1");
}

TEST_CASE("the bad query fixtures give their errors; a missing query names the reason",
          "[scene][query]") {
  const auto check_file = [](const std::string& path, const std::string& json_path,
                             const std::string& word) {
    try {
      load_query(path);
      FAIL("loaded without an error: " << path);
    } catch (const InputError& e) {
      INFO("message: " << e.what());
      CHECK(e.file() == path);
      CHECK(e.json_path() == json_path);
      CHECK_THAT(std::string(e.what()), Contains(path) && Contains(word));
    }
  };
  check_file(kFixtures + "/bad/query_negative_extent.json", "a.half_extents[2]", "must be > 0");
  check_file(kFixtures + "/bad/query_unknown_key.json", "b", "did you mean \"orientation\"?");
  check_file(kFixtures + "/no_such_query.json", "", "cannot open: No such file");
}

// ---------------------------------------------------------------------------------------------
// The reading layer itself

TEST_CASE("edit distance and the closest match", "[scene]") {
  using json_input::closest_match;
  using json_input::edit_distance;
  CHECK(edit_distance("", "") == 0);
  CHECK(edit_distance("mass", "mass") == 0);
  CHECK(edit_distance("half_extent", "half_extents") == 1);
  CHECK(edit_distance("gravty", "gravity") == 1);
  CHECK(edit_distance("td", "dt") == 1);  // a swap counts once
  CHECK(edit_distance("kitten", "sitting") == 3);

  const std::vector<std::string_view> keys = {"name", "mass", "half_extents", "position"};
  CHECK(closest_match("nmae", keys) == "name");
  CHECK(closest_match("mas", keys) == "mass");
  CHECK(closest_match("halfextents", keys) == "half_extents");
  CHECK_FALSE(closest_match("velocity", keys));
  CHECK_FALSE(closest_match("zzz", keys));
}

TEST_CASE("numbers in messages read back as the same double", "[scene]") {
  CHECK(json_input::format_number(-1.0) == "-1");
  CHECK(json_input::format_number(0.5) == "0.5");
  CHECK(json_input::format_number(0.1 + 0.2) == "0.30000000000000004");
}

TEST_CASE("solver settings of our engine load and are checked", "[scene]") {
  const std::string base = R"({"name": "s", "bodies": [{"name": "b", "mass": 1, "half_extents": [0.5, 0.5, 0.5],
    "position": [0, 0, 0.5]}], "time": {"dt": 0.01, "duration": 1}, "solver": )";
  const Scene s = parse_scene(base + R"({"shock_passes": 7, "contact_margin": 0.002, "penetration_recovery": 0.5,
    "penetration_slop": 0.001, "recovery_passes": 3}})", "solver.json");
  CHECK(s.solver.shock_passes == 7);
  CHECK(s.solver.contact_margin == 0.002);
  CHECK(s.solver.penetration_recovery == 0.5);
  CHECK(s.solver.penetration_slop == 0.001);
  CHECK(s.solver.recovery_passes == 3);
  CHECK_THROWS_WITH(parse_scene(base + R"({"penetration_recovery": 1.5}})", "solver.json"),
                    Catch::Contains("solver.json") && Catch::Contains("solver.penetration_recovery"));
  CHECK_THROWS_WITH(parse_scene(base + R"({"shock_passes": 65}})", "solver.json"),
                    Catch::Contains("solver.shock_passes") && Catch::Contains("[1, 64]"));
  CHECK_THROWS_WITH(parse_scene(base + R"({"contact_margin": -1}})", "solver.json"),
                    Catch::Contains("solver.contact_margin"));
}

TEST_CASE("the penalty method's keys load, and each method's keys are errors under the other", "[scene]") {
  const Scene s = parse_scene(R"({
    "name": "springs", "ground": {},
    "material": {"friction": 0.2, "static_friction": 0.5},
    "bodies": [{"name": "b", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5],
                "material": {"friction": 0.3}}],
    "solver": {"method": "penalty", "stiffness": 2e4, "damping": 50, "friction_stiffness": 1e4,
               "substeps": 8, "contact_margin": 0.002},
    "time": {"dt": 0.004, "duration": 1}
  })", kSource);
  CHECK(s.solver.method == "penalty");
  CHECK(s.solver.penalty.stiffness == 2e4);
  CHECK(s.solver.penalty.damping == 50.0);
  CHECK(s.solver.penalty.friction_stiffness == 1e4);
  CHECK(s.solver.penalty.substeps == 8);
  CHECK(s.solver.contact_margin == 0.002);  // shared by both methods
  CHECK(s.material.static_mu() == 0.5);
  CHECK(s.material.friction == 0.2);
  // A body giving its own friction gets mu_s = its friction, not the scene's static one.
  CHECK(s.bodies[0].material->static_mu() == 0.3);

  auto error_of = [](const std::string& text) {
    try {
      parse_scene(text, kSource);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string body = R"("bodies": [{"name": "b", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5]}],
                              "time": {"dt": 0.004, "duration": 1}})";
  CHECK_THAT(error_of(R"({"name": "x", "solver": {"stiffness": 1000}, )" + body),
             Catch::Contains("solver.stiffness") && Catch::Contains("belongs to the penalty method"));
  CHECK_THAT(error_of(R"({"name": "x", "solver": {"method": "penalty", "shock_passes": 3}, )" + body),
             Catch::Contains("solver.shock_passes") && Catch::Contains("belongs to the impulse method"));
  CHECK_THAT(error_of(R"({"name": "x", "solver": {"method": "penalty"}, "collision": {"reuse_contacts": true}, )" + body),
             Catch::Contains("collision.reuse_contacts") && Catch::Contains("belongs to the impulse method"));
  CHECK_THAT(error_of(R"({"name": "x", "material": {"static_friction": 0.9}, )" + body),
             Catch::Contains("material.static_friction") && Catch::Contains("belongs to the penalty method"));
  CHECK_THAT(error_of(R"({"name": "x", "material": {"friction": 0.5, "static_friction": 0.4}, "solver": {"method": "penalty"}, )" + body),
             Catch::Contains("material.static_friction") && Catch::Contains("at least the dynamic one"));
  CHECK_THAT(error_of(R"({"name": "x", "material": {"restitution": 0.5}, "effects": ["gravity", "restitution"], "solver": {"method": "penalty", "damping": 10}, )" + body),
             Catch::Contains("solver.damping") && Catch::Contains("restitution"));
  CHECK_THAT(error_of(R"({"name": "x", "solver": {"method": "penalty", "substeps": 0}, )" + body),
             Catch::Contains("solver.substeps"));
}

// ---------------------------------------------------------------------------------------------
// Truth

TEST_CASE("a scene's truth loads: final states, trajectories, a rebound", "[scene][truth]") {
  json scene = base_scene();
  scene["truth"] = R"({
    "final_positions": {"b0": [1, 2, 0.5]},
    "final_velocities": {"b1": [0, 0, 0]},
    "final_orientations": {"b0": [0, 0, 0, 2]},
    "trajectories": {"b0": {"acceleration": [-1, 0, 0], "until": 0.5}, "b1": {"start": [0, 0, 2], "velocity": [1, 0, 0], "acceleration": [0, 0, -2]}},
    "rebound": {"body": "b1", "height": 0.75}
  })"_json;
  const Scene s = parse_scene(scene.dump(), kSource);
  REQUIRE(s.truth.final_positions.size() == 1);
  CHECK(s.truth.final_positions[0].body == 0);
  CHECK(s.truth.final_positions[0].value == Vec3(1, 2, 0.5));
  REQUIRE(s.truth.final_velocities.size() == 1);
  CHECK(s.truth.final_velocities[0].body == 1);
  REQUIRE(s.truth.final_orientations.size() == 1);
  CHECK_THAT(s.truth.final_orientations[0].orientation.z(), Catch::Matchers::WithinAbs(1.0, kTight));  // normalised
  REQUIRE(s.truth.trajectories.size() == 2);
  const TruthTrajectory& slide = s.truth.trajectories[0];
  // Start and velocity default to the body's; held at rest after `until`.
  CHECK(slide.start == Vec3(0, 0, 0.5));
  CHECK(slide.velocity == Vec3::Zero());
  CHECK(slide.at(0.5).isApprox(Vec3(-0.125, 0, 0.5), kTight));
  CHECK(slide.at(2.0).isApprox(Vec3(-0.125, 0, 0.5), kTight));
  const TruthTrajectory& fall = s.truth.trajectories[1];
  CHECK(fall.body == 1);
  CHECK(fall.at(1.0).isApprox(Vec3(1, 0, 1), kTight));
  REQUIRE(s.truth.rebound);
  CHECK(s.truth.rebound->body == 1);
  CHECK(s.truth.rebound->height == 0.75);
  CHECK(s.truth.duration == 1.0);
  CHECK(parse_scene(base_scene().dump(), kSource).truth.empty());
}

TEST_CASE("a bad truth names the file and the field", "[scene][truth]") {
  auto with_truth = [](json t) { return [t](json& s) { s["truth"] = t; }; };
  run_cases({
      {"unknown body", with_truth({{"final_positions", {{"bo", {0, 0, 0}}}}}), "truth.final_positions.bo",
       "no body named \"bo\""},
      {"not an object", with_truth({{"final_positions", {1, 2, 3}}}), "truth.final_positions",
       "must be an object {BODY: ...}"},
      {"a point of two numbers", with_truth({{"final_velocities", {{"b0", {0, 0}}}}}), "truth.final_velocities.b0",
       "3"},
      {"a misspelt form", with_truth({{"final_position", {{"b0", {0, 0, 0}}}}}), "truth",
       "did you mean \"final_positions\"?"},
      {"a trajectory without acceleration", with_truth({{"trajectories", {{"b0", {{"until", 1}}}}}}),
       "truth.trajectories.b0", "missing required key \"acceleration\""},
      {"a negative until", with_truth({{"trajectories", {{"b0", {{"acceleration", {0, 0, 0}}, {"until", -1}}}}}}),
       "truth.trajectories.b0.until", "-1"},
      {"a zero quaternion", with_truth({{"final_orientations", {{"b0", {0, 0, 0, 0}}}}}),
       "truth.final_orientations.b0", "zero quaternion"},
      {"a rebound of nobody", with_truth({{"rebound", {{"body", "b7"}, {"height", 1}}}}), "truth.rebound.body",
       "no body named \"b7\""},
      {"an empty truth", with_truth(json::object()), "truth", "states no truth"},
      {"a fixed body", [](json& s) {
         body(s, 0)["fixed"] = true;
         s["truth"] = {{"final_positions", {{"b0", {0, 0, 0.5}}}}};
       }, "truth.final_positions.b0", "is fixed"},
  });
}
