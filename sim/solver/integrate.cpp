#include "boxpile/sim/solver/integrate.hpp"

#include <cmath>

namespace boxpile {

void integrate_momenta(StepContext& ctx) {
  const Scene& scene = ctx.scene;
  const Effects& fx = scene.effects;
  const double dt = ctx.dt;
  // Damping dP/dt = -c P integrated exactly over the step: P *= exp(-c dt), stable for any c dt.
  const double keep_linear = std::exp(-scene.damping.linear * dt);
  const double keep_angular = std::exp(-scene.damping.angular * dt);
  for (RigidBody& b : ctx.bodies) {
    if (b.fixed) continue;
    if (fx.gravity) {
      b.P += b.mass * scene.gravity * dt;
      ++ctx.counters.gravity_applications;
    }
    if (fx.damping) {
      b.P *= keep_linear;
      b.L *= keep_angular;
      ++ctx.counters.damping_applications;
    }
    b.v = b.inv_mass * b.P;
    b.omega = b.inv_inertia_world * b.L;
  }
}

void advance_pose(RigidBody& b, const Vec3& v, const Vec3& w, double dt, bool gyroscopic,
                  WorldCounters& counters) {
  b.x += dt * v;
  // dq/dt = 1/2 (0, omega) q (Baraff's notes, "quaternion derivative"), then renormalised.
  const Quat spin(0.0, w.x(), w.y(), w.z());
  b.q.coeffs() += 0.5 * dt * (spin * b.q).coeffs();
  const Vec3 omega_now = b.omega;
  b.update_derived();
  if (gyroscopic) {
    // L is what is conserved: omega = I(t)^-1 L changes as the body turns.
    ++counters.gyroscopic_updates;
  } else {
    // The lab text neglects the gyroscopic term (spherical inertia): omega is kept, and L is
    // re-expressed with the turned inertia, L = I(t + dt) omega.
    b.L = b.R * b.inertia_body * b.R.transpose() * omega_now;
    b.omega = omega_now;
  }
}

}  // namespace boxpile
