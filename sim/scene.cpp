#include "sim/scene.hpp"

namespace boxpile {

std::vector<RigidBody> make_bodies(const Scene& scene) {
  std::vector<RigidBody> bodies;
  bodies.reserve(scene.bodies.size());
  for (const BodyDesc& d : scene.bodies) {
    bodies.push_back(make_body(d.name, d.boxes, d.mass, d.frame, d.velocity, d.angular_velocity,
                               d.material.value_or(scene.material), d.fixed));
  }
  return bodies;
}

}  // namespace boxpile
