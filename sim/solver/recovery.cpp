#include "boxpile/sim/solver/recovery.hpp"

#include <algorithm>

namespace boxpile {

void PenetrationRecovery::reserve(const StepStorage& storage) {
  pseudo_v_.reserve(storage.bodies);
  pseudo_omega_.reserve(storage.bodies);
  lambda_.reserve(storage.contacts());
}

void PenetrationRecovery::run(const ImpulseStep& step) {
  const SolverBodies& sb = step.sb;
  const std::vector<SolverContact>& contacts = step.contacts;
  const SolverSettings& settings = step.world.scene.solver;
  const double beta = settings.penetration_recovery;
  const double slop = settings.penetration_slop;
  const double dt = step.world.dt;
  const int passes = settings.recovery_passes;
  const std::size_t n = sb.bodies.size();
  pseudo_v_.assign(n, Vec3::Zero());
  pseudo_omega_.assign(n, Vec3::Zero());
  lambda_.assign(contacts.size(), 0.0);

  auto point_velocity = [&](int body, const Vec3& r) -> Vec3 {
    return body < 0 ? Vec3::Zero() : Vec3(pseudo_v_[body] + pseudo_omega_[body].cross(r));
  };
  auto push = [&](int body, const Vec3& impulse, const Vec3& r) {
    if (body < 0 || sb.get(body).fixed) return;
    const RigidBody& b = sb.get(body);
    pseudo_v_[body] += b.inv_mass * impulse;
    pseudo_omega_[body] += b.inv_inertia_world * r.cross(impulse);
  };

  for (int pass = 0; pass < passes; ++pass) {
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const SolverContact& c = contacts[k];
      if (c.depth <= slop) continue;
      // Normal-only: lambda += (target - u_n) / (n . (Ka + Kb) n), kept >= 0 (pushes only).
      const double target = beta * (c.depth - slop) / dt;
      const double un = c.n.dot(point_velocity(c.a, c.ra) - point_velocity(c.b, c.rb));
      const double lambda = std::max(0.0, lambda_[k] + (target - un) / c.n.dot((c.Ka + c.Kb) * c.n));
      const Vec3 impulse = (lambda - lambda_[k]) * c.n;
      lambda_[k] = lambda;
      push(c.a, impulse, c.ra);
      push(c.b, -impulse, c.rb);
    }
  }
}

}  // namespace boxpile
