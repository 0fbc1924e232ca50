// Measurements taken the same way for every engine, from body states alone: energy,
// penetration and levitation (definitions in docs/metrics.md).
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// The unit direction of `gravity`, -z without gravity (every measure of "up" reads this).
Vec3 down_direction(const Vec3& gravity);
// Two unit directions across `down` (a unit vector), perpendicular to each other and to it.
std::pair<Vec3, Vec3> across_directions(const Vec3& down);

struct Energy {
  double translational = 0.0;  // J, sum 1/2 m |v|^2
  double rotational = 0.0;     // J, sum 1/2 omega . I omega
  double potential = 0.0;      // J, sum -m g . x (zero at the origin)
  double kinetic() const { return translational + rotational; }
  double total() const { return kinetic() + potential; }
};

Energy measure_energy(const std::vector<RigidBody>& bodies, const Vec3& gravity);

// The deepest penetration over every pair of bodies and every body against the ground, by our
// exact separating-axis depth (0 when nothing overlaps).
struct Penetration {
  double depth = 0.0;  // m
  int body_a = -1;
  int body_b = -1;  // kGround for the ground
};
Penetration measure_penetration(const std::vector<RigidBody>& bodies, const std::optional<HalfSpace>& ground);

// The largest gap under a body at rest (speed below `rest_speed` m/s, spin below rest_speed
// per metre of size): the smallest separation between the body and the ground or any body whose
// centre of mass lies lower, when that separation is positive. 0 when no resting body floats.
double measure_levitation(const std::vector<RigidBody>& bodies, const std::optional<HalfSpace>& ground,
                          const Vec3& gravity, double rest_speed = 1e-3);

// Sets our bodies' poses and velocities from another engine's reported states (scene order), so
// that the measurements above apply to ODE and Bullet unchanged.
void set_body_states(std::vector<RigidBody>& bodies, const std::vector<BodyState>& states);

}  // namespace boxpile
