#include "boxpile/sim/solver/contact_method.hpp"

#include <stdexcept>

#include "boxpile/sim/solver/impulse_method.hpp"
#include "boxpile/sim/solver/penalty_method.hpp"

namespace boxpile {

std::unique_ptr<ContactMethod> make_contact_method(const Scene& scene, const std::vector<RigidBody>& bodies) {
  switch (scene.solver.method) {
    case ContactSolver::Impulse:
      return std::make_unique<ImpulseMethod>(bodies.size());
    case ContactSolver::Penalty: {
      const PenaltyParameters p = derive_penalty_parameters(scene);
      if (const std::string problem = penalty_parameters_problem(scene, p); !problem.empty())
        throw std::invalid_argument(scene.source + ": solver: " + problem);
      return std::make_unique<PenaltyMethod>(p, bodies.size());
    }
  }
  throw std::invalid_argument("unknown solver method");
}

}  // namespace boxpile
