// Small scenes and helpers shared by the tests that build engines directly (the conformance of
// ODE and Bullet, MuJoCo's conventions).
#pragma once

#include <string>
#include <vector>

#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile::test {

// A scene with no bodies yet, dt 1/240 s, the ground half-space z < 0 when `ground`.
inline Scene empty_scene(const Effects& effects, bool ground) {
  Scene scene;
  scene.name = "test";
  scene.effects = effects;
  if (ground) scene.ground = HalfSpace{};
  scene.time.dt = 1.0 / 240.0;
  return scene;
}

// A 1 kg unit cube.
inline BodyDesc unit_box(const std::string& name, const Vec3& position) {
  BodyDesc b;
  b.name = name;
  b.mass = 1.0;
  b.boxes = {BoxShape{}};
  b.frame.position = position;
  return b;
}

// The L of fixtures/scenes/compound_on_ground.json: its inertia has a product term (x z) and its
// centre of mass is away from the body frame.
inline BodyDesc l_compound(const std::string& name, const Vec3& position) {
  BodyDesc b;
  b.name = name;
  b.mass = 3.5;
  b.boxes = {BoxShape{Vec3(1.0, 0.5, 0.25), Vec3::Zero(), Quat::Identity()},
             BoxShape{Vec3(0.25, 0.5, 0.75), Vec3(0.75, 0.0, 1.0), Quat::Identity()}};
  b.frame.position = position;
  return b;
}

inline void run(Engine& e, long steps) {
  for (long k = 0; k < steps; ++k) e.step();
}

inline std::vector<BodyState> states_of(const Engine& e) {
  std::vector<BodyState> s;
  e.body_states(s);
  return s;
}

}  // namespace boxpile::test
