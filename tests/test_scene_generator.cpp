#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/scene/scene_generator.hpp"

using namespace boxpile;

namespace {

// The scene loaded by the loader (which refuses overlapping boxes) and its highest box top.
struct Built {
  Scene scene;
  double top = 0.0;
};
Built build(std::string_view kind, const SceneSizes& sizes) {
  Built b{parse_scene(generate_scene(kind, sizes).dump(), std::string(kind)), 0.0};
  for (const BodyDesc& body : b.scene.bodies) {
    // Axis-aligned boxes: the top is the centre plus the half extent along z.
    b.top = std::max(b.top, body.frame.position.z() + body.boxes.at(0).half_extents.z());
  }
  return b;
}

}  // namespace

TEST_CASE("generated scenes have their box counts and heights, and load without overlaps", "[scene]") {
  SceneSizes s;
  s.base = 10;
  Built pyramid = build("pyramid", s);
  CHECK(pyramid.scene.bodies.size() == 55);
  CHECK(pyramid.top == Approx(10.0).margin(1e-12));
  s = {};
  s.width = 4;
  s.height = 3;
  s.size = 0.5;
  Built wall = build("wall", s);
  CHECK(wall.scene.bodies.size() == 12);
  CHECK(wall.top == Approx(1.5).margin(1e-12));
  s = {};
  s.height = 7;
  Built tower = build("tower", s);
  CHECK(tower.scene.bodies.size() == 7);
  CHECK(tower.top == Approx(7.0).margin(1e-12));
  s = {};
  s.nx = 3;
  s.ny = 4;
  s.layers = 2;
  s.gap = 0.25;
  Built grid = build("grid", s);
  CHECK(grid.scene.bodies.size() == 24);
  CHECK(grid.top == Approx(2 * 1.0 + 0.25).margin(1e-12));
  s = {};
  s.count = 30;
  Built heap = build("heap", s);  // random orientations: the loader's overlap check is the test
  CHECK(heap.scene.bodies.size() == 30);
  s = {};
  s.count = 12;
  Built dominoes = build("dominoes", s);
  CHECK(dominoes.scene.bodies.size() == 12);
  CHECK(dominoes.top == Approx(1.0).margin(1e-12));
  // Every box rests on or above the ground (the lowest touches it, none below).
  for (const Built* b : {&pyramid, &wall, &tower, &grid, &dominoes}) {
    double lowest = 1e9;
    for (const BodyDesc& body : b->scene.bodies)
      lowest = std::min(lowest, body.frame.position.z() - body.boxes.at(0).half_extents.z());
    CHECK(lowest == Approx(0.0).margin(1e-12));
  }
  CHECK_THROWS_AS(generate_scene("castle", {}), SceneGeneratorError);
  s = {};
  s.size = 1e-3;
  CHECK_THROWS_WITH(generate_scene("tower", s), Catch::Contains("--size"));
}

TEST_CASE("a generated tower stands and a generated pyramid holds in our engine", "[scene]") {
  SceneSizes s;
  s.height = 5;
  for (std::string_view kind : {"tower", "pyramid"}) {
    Scene scene = parse_scene(generate_scene(kind, s).dump(), std::string(kind));
    const auto engine = make_engine("own", scene);
    for (int k = 0; k < 240; ++k) engine->step();  // 1 s
    std::vector<BodyState> states;
    engine->body_states(states);
    REQUIRE(states.size() == scene.bodies.size());
    for (std::size_t b = 0; b < states.size(); ++b) {
      INFO(kind << " body " << b);
      CHECK((states[b].position - scene.bodies[b].frame.position).norm() < 1e-2);
    }
  }
}
