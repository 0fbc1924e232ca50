#include "boxpile/sim/scene.hpp"

#include <algorithm>

namespace boxpile {
namespace {

// The least event speed, m/s: far above rounding of velocities, far below any real impact.
constexpr double kEventSpeedMin = 0.01;
// Steps of gravity's velocity gain a resting contact may show as approach without an event.
constexpr double kEventSpeedGravitySteps = 2.0;

}  // namespace

std::vector<RigidBody> make_bodies(const Scene& scene) {
  std::vector<RigidBody> bodies;
  bodies.reserve(scene.bodies.size());
  for (const BodyDesc& d : scene.bodies) {
    bodies.push_back(make_body(d.name, d.boxes, d.mass, d.frame, d.velocity, d.angular_velocity,
                               d.material.value_or(scene.material), d.fixed));
  }
  return bodies;
}

double collision_event_speed(const Scene& scene, double dt) {
  return std::max(kEventSpeedMin, kEventSpeedGravitySteps * scene.gravity.norm() * dt);
}

}  // namespace boxpile
