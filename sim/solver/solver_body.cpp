#include "boxpile/sim/solver/solver_body.hpp"

namespace boxpile {

void SolverBodyArray::gather(const std::vector<RigidBody>& bodies) {
  body_.resize(bodies.size() + 1);
  body_[0] = SolverBody{};  // the ground: immovable, at rest
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const RigidBody& b = bodies[i];
    SolverBody& s = body_[i + 1];
    s.P = b.P;
    s.L = b.L;
    s.v = b.v;
    s.omega = b.omega;
    s.inv_mass = b.fixed ? 0.0 : b.inv_mass;
    s.inv_inertia = b.fixed ? Mat3::Zero() : b.inv_inertia_world;
  }
}

void SolverBodyArray::scatter(std::vector<RigidBody>& bodies) const {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    RigidBody& b = bodies[i];
    if (b.fixed) continue;
    const SolverBody& s = body_[i + 1];
    b.v = s.v;
    b.omega = s.omega;
    b.P = s.P;
    b.L = s.L;
  }
}

}  // namespace boxpile
