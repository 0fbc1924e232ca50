#include "sim/solver/contact_method.hpp"

#include "sim/solver/impulse_method.hpp"

namespace boxpile {

std::unique_ptr<ContactMethod> make_contact_method(const Scene& scene, const std::vector<RigidBody>& bodies) {
  switch (scene.solver.method) {
    case ContactSolver::Impulse:
    case ContactSolver::Penalty:  // the penalty method is not built yet: it runs the impulse method
      return std::make_unique<ImpulseMethod>(bodies.size());
  }
  return nullptr;
}

}  // namespace boxpile
