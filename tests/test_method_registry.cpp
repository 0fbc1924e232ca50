// A contact method is one row of the registry (sim/solver/contact_method.hpp): this file adds a
// method of its own, "freefall" (no contacts, gravity scaled by its one setting, semi-implicit
// Euler), and checks that the loader, the settings table, `boxpile settings`, the engine rows and
// the run all take it from that row alone.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/own_settings.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/solver/contact_method.hpp"
#include "boxpile/sim/world.hpp"
#include "boxpile/validation/core/engine_settings.hpp"

namespace boxpile {
namespace {

// Bodies fall under gravity times `gravity_scale`, whatever they meet: v += s g h, then x += v h.
class FreeFall final : public ContactMethod {
 public:
  explicit FreeFall(double scale) : scale_(scale) {}
  void step(StepContext& ctx) override {
    for (RigidBody& b : ctx.bodies) {
      if (b.fixed) continue;
      b.v += scale_ * ctx.scene.gravity * ctx.dt;
      b.P = b.mass * b.v;
      b.x += b.v * ctx.dt;
    }
    ++steps_;
  }
  nlohmann::json diagnostics(std::size_t) const override {
    return {{"method", "freefall"}, {"steps", steps_}};
  }

 private:
  double scale_;
  long steps_ = 0;  // the method's own counter
};

ContactMethodRow free_fall_row() {
  ContactMethodRow row;
  row.name = "freefall";
  row.what = "test only: no contacts, gravity scaled";
  row.settings = {
      {{.key = "gravity_scale", .kind = SettingInfo::Kind::Number, .what = "gravity is multiplied by this",
        .min = 0, .max = 10, .scene_key = "solver.gravity_scale"},
       [](Scene& s, const nlohmann::json& v) { s.solver.method_values["gravity_scale"] = v.get<double>(); },
       [](const Scene& s) {
         const auto it = s.solver.method_values.find("gravity_scale");
         return nlohmann::json(it == s.solver.method_values.end() ? 1.0 : it->second);
       }},
  };
  row.make = [](const Scene& scene, const std::vector<RigidBody>&) -> std::unique_ptr<ContactMethod> {
    const auto it = scene.solver.method_values.find("gravity_scale");
    return std::make_unique<FreeFall>(it == scene.solver.method_values.end() ? 1.0 : it->second);
  };
  return row;
}

// Registered before main, as a method of the project would be: before the settings table is
// built from the registry.
const bool kRegistered = [] {
  register_contact_method(free_fall_row());
  return true;
}();

std::string scene_text(const std::string& solver) {
  return R"({"name": "drop", "gravity": [0, 0, -9.81], "ground": {"normal": [0, 0, 1], "offset": 0},
    "bodies": [{"name": "box", "mass": 2.0, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 1.0]}],
    "solver": )" + solver + R"(, "time": {"dt": 0.01, "duration": 1.0}})";
}

}  // namespace

TEST_CASE("a method registered from one file is loaded, run and listed", "[method_registry]") {
  REQUIRE(kRegistered);
  REQUIRE(find_contact_method("freefall"));

  SECTION("the scene naming it runs it: semi-implicit Euler's free fall, exactly") {
    const Scene scene = parse_scene(scene_text(R"({"method": "freefall", "gravity_scale": 0.5})"), "drop.json");
    CHECK(scene.solver.method == "freefall");
    World world(scene);
    CHECK(world.contact_method() == "freefall");
    const int n = 100;
    for (int k = 0; k < n; ++k) world.step();
    // v_n = n s g h and z_n = z0 + s g h^2 n (n + 1) / 2: the continuous z0 + s g t^2 / 2 plus
    // semi-implicit Euler's error s g t h / 2. The box passes through the ground (1 m) into -1.5 m:
    // the method has no contacts.
    const double g = -9.81 * 0.5, h = 0.01, t = n * h;
    const double z = 1.0 + g * h * h * n * (n + 1) / 2.0;
    CHECK(world.bodies()[0].x.z() == Approx(z).epsilon(1e-13));
    CHECK(world.bodies()[0].x.z() == Approx(1.0 + g * t * t / 2.0 + g * t * h / 2.0).epsilon(1e-13));
    CHECK(world.bodies()[0].v.z() == Approx(n * g * h).epsilon(1e-13));
    CHECK(world.bodies()[0].x.x() == 0.0);
    CHECK(world.method_diagnostics() == nlohmann::json{{"method", "freefall"}, {"steps", n}});
  }

  SECTION("its setting is declared once: the table, `boxpile settings` and the engine rows list it") {
    const Setting<Scene>* row = own_settings_table().find("gravity_scale");
    REQUIRE(row);
    CHECK(row->info.group == "freefall");
    CHECK(row->info.scene_key == "solver.gravity_scale");
    CHECK(row->info.default_value == 1.0);
    const std::string table = settings_markdown();
    CHECK(table.find("gravity_scale") != std::string::npos);
    CHECK(table.find("gravity is multiplied by this") != std::string::npos);
    // The forced engine of the method offers its setting and not the others' (the impulse
    // method's passes); "own" offers every method's.
    bool offered = false, foreign = false;
    for (const SettingInfo& s : engine_settings("own-freefall")) {
      offered = offered || s.key == "gravity_scale";
      foreign = foreign || s.key == "contact_passes";
    }
    CHECK(offered);
    CHECK_FALSE(foreign);
    // `--set own.gravity_scale=2` through the same row, on a scene of the method.
    const Scene scene = parse_scene(scene_text(R"({"method": "freefall"})"), "drop.json");
    EngineConfig config{scene, {}};
    apply_settings("own-freefall", {{"gravity_scale", 2.0}}, config);
    World world(scene_with_settings("own-freefall", config.scene, config.settings));
    world.step();
    CHECK(world.bodies()[0].v.z() == Approx(2.0 * -9.81 * 0.01).epsilon(1e-14));
  }

  SECTION("its settings belong to it; unknown names list every method") {
    CHECK_THROWS_WITH(parse_scene(scene_text(R"({"method": "impulse", "gravity_scale": 0.5})"), "drop.json"),
                      Catch::Contains("belongs to the freefall method"));
    CHECK_THROWS_WITH(parse_scene(scene_text(R"({"method": "fre_fall"})"), "drop.json"),
                      Catch::Contains("solver.method") && Catch::Contains("\"freefall\""));
    CHECK_THROWS_WITH(parse_scene(scene_text(R"({"method": "nothing"})"), "drop.json"),
                      Catch::Contains("\"impulse\", \"penalty\", \"freefall\""));
    CHECK_THROWS_AS(register_contact_method(free_fall_row()), std::logic_error);
  }
}

}  // namespace boxpile
