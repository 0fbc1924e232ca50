#include "validation/state_meter.hpp"

namespace boxpile {

StateMeter::StateMeter(const Scene& scene) : scene_(scene), bodies_(make_bodies(scene)) {}

FrameMetrics StateMeter::measure(const std::vector<BodyState>& states) {
  set_body_states(bodies_, states);
  FrameMetrics m;
  m.energy = measure_energy(bodies_, scene_.effects.gravity ? scene_.gravity : Vec3::Zero());
  m.penetration = measure_penetration(bodies_, scene_.ground);
  m.levitation = measure_levitation(bodies_, scene_.ground, scene_.gravity);
  return m;
}

}  // namespace boxpile
