// The seam between the world and the way it resolves contacts. The world owns what every method
// shares (bodies, the contact set, the integrators, the wires) and, for each step, finds the
// contact set and hands it to the method chosen by the scene's `solver.method` (the shape of
// qu3e's q3Island::Solve and of MuJoCo's mj_step, whose integrator is a switch).
#pragma once

#include <memory>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/sim/solver/step_context.hpp"

namespace boxpile {

class ContactMethod {
 public:
  virtual ~ContactMethod() = default;
  // How many steps of dt / n the method takes per scene step; the world finds the contact set
  // before each of them.
  virtual int substeps() const { return 1; }
  // Resolves the contact set of ctx and advances the bodies by ctx.dt.
  virtual void step(StepContext& ctx) = 0;
};

// The method the scene's solver settings name, built for its bodies.
std::unique_ptr<ContactMethod> make_contact_method(const Scene& scene, const std::vector<RigidBody>& bodies);

}  // namespace boxpile
