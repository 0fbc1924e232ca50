#include "boxpile/validation/rulers/state_meter.hpp"

namespace boxpile {

StateMeter::StateMeter(const Scene& scene) : scene_(scene), bodies_(make_bodies(scene)) {}

FrameMetrics StateMeter::measure(const std::vector<BodyState>& states) {
  FrameMetrics m = measure_step(states);
  // A body on a wire hangs: a gap under it is no levitation. measure_levitation skips fixed
  // bodies (still counting them as supports), so wired bodies are marked fixed for this one call.
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (scene_.bodies[i].wire) bodies_[i].fixed = true;
  }
  m.levitation = measure_levitation(bodies_, scene_.ground, scene_.gravity);
  for (std::size_t i = 0; i < bodies_.size(); ++i) bodies_[i].fixed = scene_.bodies[i].fixed;
  return m;
}

FrameMetrics StateMeter::measure_step(const std::vector<BodyState>& states) {
  set_body_states(bodies_, states);
  FrameMetrics m;
  m.energy = measure_energy(bodies_, scene_.effects.gravity ? scene_.gravity : Vec3::Zero());
  m.penetration = measure_penetration(bodies_, scene_.ground);
  return m;
}

}  // namespace boxpile
