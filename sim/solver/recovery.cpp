#include "boxpile/sim/solver/recovery.hpp"

#include <algorithm>
#include <cmath>

namespace boxpile {

namespace {
// A group's passes stop once no pseudo-impulse changes a point's pseudo-velocity by more than
// this, m/s: what is left moves a body by 4e-9 m in a step of 1/240 s, 0.4% of the smallest
// slop the catalogue uses (1 micrometre, for 1 mm boxes).
constexpr double kRecoveryConverged = 1e-6;
}  // namespace

// The separating pseudo-velocity a contact asks for, beyond what the resolved velocities already
// give it. A contact deeper than the slop asks for beta of its overlap beyond the slop per step,
// plus whatever approach the resolved velocities still leave at it. A shallower one asks only
// that the pair end the step no deeper than the slop: it holds against pseudo-velocities that
// would push its bodies into each other, and covers an approach the velocity stages left (a body
// frozen by shock propagation that drives into the level above it, an impact the collision loop
// had no passes left for). Pseudo-velocities move positions only, so covering an approach adds
// no kinetic energy: the momenta keep it, and the next step's loops resolve it.
double PenetrationRecovery::pseudo_target(const SolverBodies& sb, const SolverContact& c, double beta, double dt) {
  const double un = c.n.dot(sb.relative_velocity(c));
  if (c.depth > c.slop) return beta * (c.depth - c.slop) / dt + std::max(0.0, -un);
  return -(c.slop - c.depth) / dt - un;
}

void PenetrationRecovery::reserve(const StepStorage& storage) {
  pseudo_v_.reserve(storage.bodies);
  pseudo_omega_.reserve(storage.bodies);
  lambda_.reserve(storage.contacts());
  target_.reserve(storage.contacts());
  group_.reserve(storage.contacts());
}

void PenetrationRecovery::run(const ImpulseStep& step, const ShockPropagation* shock) {
  const SolverBodies& sb = step.sb;
  const std::vector<SolverContact>& contacts = step.contacts;
  const double beta = step.settings().penetration_recovery;
  const std::size_t n = sb.bodies.size();
  pseudo_v_.assign(n, Vec3::Zero());
  pseudo_omega_.assign(n, Vec3::Zero());
  lambda_.assign(contacts.size(), 0.0);
  target_.resize(contacts.size());
  bool any_push = false;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    target_[k] = pseudo_target(sb, contacts[k], beta, step.dt());
    any_push = any_push || target_[k] > 0.0;
  }
  if (!any_push) return;  // nothing overlaps beyond the slop or approaches: no pseudo-velocity

  // With shock propagation's levels, from the ground up with every lower level frozen, as the
  // velocities were: a heavy body on top cannot push the bodies under it into the ground. The
  // bodies no level reaches come last, all movable.
  const int top = shock ? shock->top_level() : -1;
  for (int l = 0; l <= top; ++l) solve_group(step, shock->contacts_of_level(l), shock, l);
  group_.clear();
  for (std::size_t k = 0; k < contacts.size(); ++k)
    if (!shock || shock->contact_level(contacts[k]) == ShockPropagation::kUnsupported)
      group_.push_back(static_cast<int>(k));
  solve_group(step, group_, nullptr, 0);
}

void PenetrationRecovery::solve_group(const ImpulseStep& step, std::span<const int> group, const ShockPropagation* shock,
                                      int level) {
  const SolverBodies& sb = step.sb;
  auto moves = [&](int body) {
    return body >= 0 && !sb.get(body).fixed && (!shock || shock->levels()[body] >= level);
  };
  auto point_velocity = [&](int body, const Vec3& r) -> Vec3 {
    return body < 0 ? Vec3::Zero() : Vec3(pseudo_v_[body] + pseudo_omega_[body].cross(r));
  };
  auto push = [&](int body, const Vec3& impulse, const Vec3& r) {
    const RigidBody& b = sb.get(body);
    pseudo_v_[body] += b.inv_mass * impulse;
    pseudo_omega_[body] += b.inv_inertia_world * r.cross(impulse);
  };

  for (int pass = 0; pass < step.settings().recovery_passes; ++pass) {
    double largest_change = 0.0;
    for (const int k : group) {
      const SolverContact& c = step.contacts[k];
      const bool a_moves = moves(c.a), b_moves = moves(c.b);
      const Mat3 K = (a_moves ? c.Ka : Mat3::Zero()) + (b_moves ? c.Kb : Mat3::Zero());
      const double k_nn = c.n.dot(K * c.n);
      if (k_nn <= 0.0) continue;
      // Normal-only: lambda += (target - u_n) / (n . K n), kept >= 0 (pushes only).
      const double un = c.n.dot(point_velocity(c.a, c.ra) - point_velocity(c.b, c.rb));
      const double lambda = std::max(0.0, lambda_[k] + (target_[k] - un) / k_nn);
      const Vec3 impulse = (lambda - lambda_[k]) * c.n;
      largest_change = std::max(largest_change, std::abs(lambda - lambda_[k]) * k_nn);
      lambda_[k] = lambda;
      if (a_moves) push(c.a, impulse, c.ra);
      if (b_moves) push(c.b, -impulse, c.rb);
    }
    if (largest_change < kRecoveryConverged) break;
  }
}

}  // namespace boxpile
