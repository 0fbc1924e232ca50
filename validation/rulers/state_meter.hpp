// Measures any engine's body states the same way (energy, penetration, levitation), by posing
// our own bodies at the reported states: ODE, Bullet and our engine get one ruler.
#pragma once

#include <vector>

#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/metrics.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

struct FrameMetrics {
  Energy energy;
  Penetration penetration;
  double levitation = 0.0;  // m
};

class StateMeter {
 public:
  explicit StateMeter(const Scene& scene);
  FrameMetrics measure(const std::vector<BodyState>& states);
  // Energy and penetration only (levitation left 0): for every step of a run. Both measures go
  // through the broadphase (linear in the bodies), but levitation tests the pairs of bodies that
  // float above their neighbours against every body.
  FrameMetrics measure_step(const std::vector<BodyState>& states);

 private:
  const Scene& scene_;
  std::vector<RigidBody> bodies_;
};

}  // namespace boxpile
