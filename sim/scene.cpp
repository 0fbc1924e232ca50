#include "boxpile/sim/scene.hpp"

#include <algorithm>

namespace boxpile {
namespace {

// The least event speed, m/s: far above rounding of velocities, far below any real impact.
constexpr double kEventSpeedMin = 0.01;
// Steps of gravity's velocity gain a resting contact may show as approach without an event.
constexpr double kEventSpeedGravitySteps = 2.0;

}  // namespace

namespace {
// The contact margin and the penetration slop scale with the bodies: at most these fractions of
// the smallest box edge of the pair. An absolute 1 mm margin is as large as a 1 mm box, and an
// absolute 0.1 mm slop is 1.3% of a 7.8 mm plank, more than a penetration check allows (1%);
// for unit boxes both fractions exceed the scene's settings, which then apply as before.
constexpr double kMarginPerEdge = 0.01;
constexpr double kSlopPerEdge = 1e-3;
}  // namespace

void set_impulse_additions(SolverSettings& solver, CollisionSettings& collision, bool on) {
  const SolverSettings ours;  // every addition at our default
  solver.pair_impulses = on;
  solver.accumulated_impulses = on;
  solver.speculative_contacts = on;
  solver.sticking_solves = on;
  solver.contact_batches = on;
  solver.shock_propagation = on;  // the lab text's bonus: a switch of its own
  solver.penetration_recovery = on ? ours.penetration_recovery : 0.0;
  solver.integrator = on ? ours.integrator : PositionIntegrator::ExplicitEuler;
  collision.reuse_contacts = on && CollisionSettings{}.reuse_contacts;
}

double contact_margin_for(const SolverSettings& s, double smallest_edge) {
  return std::min(s.contact_margin, kMarginPerEdge * smallest_edge);
}

double penetration_slop_for(const SolverSettings& s, double smallest_edge) {
  return std::min(s.penetration_slop, kSlopPerEdge * smallest_edge);
}

std::vector<RigidBody> make_bodies(const Scene& scene) {
  std::vector<RigidBody> bodies;
  bodies.reserve(scene.bodies.size());
  for (const BodyDesc& d : scene.bodies) {
    bodies.push_back(make_body(d.name, d.boxes, d.mass, d.frame, d.velocity, d.angular_velocity,
                               d.material.value_or(scene.material), d.fixed));
  }
  return bodies;
}

double collision_event_speed(const Scene& scene, double dt) {
  return std::max(kEventSpeedMin, kEventSpeedGravitySteps * scene.gravity.norm() * dt);
}

Vec3 TruthTrajectory::at(double t) const {
  const double s = until ? std::min(t, *until) : t;
  return start + velocity * s + 0.5 * acceleration * s * s;
}

}  // namespace boxpile
