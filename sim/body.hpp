// Rigid bodies: one box or a rigid compound of boxes, with the state of the course material
// (position, orientation quaternion, linear momentum P, angular momentum L) and derived velocities.
#pragma once

#include <optional>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "boxpile/sim/math.hpp"

namespace boxpile {

// One box of a body, placed in the body frame.
struct BoxShape {
  Vec3 half_extents = Vec3::Constant(0.5);  // m, each > 0
  Vec3 offset = Vec3::Zero();               // m, box centre in the body frame
  Quat orientation = Quat::Identity();      // box axes in the body frame
};

// Contact material. Combined per pair by the rules in docs/scene-format.md.
struct Material {
  double friction = 0.5;     // Coulomb coefficient mu, dimensionless (the dynamic one)
  double restitution = 0.0;  // Newton coefficient e in [0, 1]
  // Static Coulomb coefficient mu_s >= mu, read by the penalty method's friction springs; unset:
  // the same as `friction`. ODE, Bullet and the impulse method have one mu (`friction`).
  std::optional<double> static_friction;

  double static_mu() const { return static_friction.value_or(friction); }
};

// Pair materials: friction is the geometric mean sqrt(mu_a mu_b) (zero if either is
// frictionless), restitution the larger of the two, static friction the geometric mean of the
// static coefficients (set when either material sets it) (docs/scene-format.md).
Material combine_materials(const Material& a, const Material& b);

// Mass properties of a set of boxes of uniform density, about their common centre of mass.
struct MassProperties {
  double mass = 0.0;                     // kg
  Vec3 center_of_mass = Vec3::Zero();    // m, in the body frame
  Mat3 inertia = Mat3::Zero();           // kg m^2, body axes, about the centre of mass
};

// Mass spread over the boxes by volume; each box's inertia moved to the common centre of mass by
// the parallel-axis theorem, I = sum_k R_k I_k R_k^T + m_k (|d_k|^2 E - d_k d_k^T).
MassProperties compute_mass_properties(const std::vector<BoxShape>& boxes, double mass);

// The maximum number of boxes in one compound body (keeps per-step storage fixed-size).
inline constexpr int kMaxBoxesPerBody = 16;

// A body as the simulator holds it. The dynamic state refers to the centre of mass; `shapes`
// are placed relative to the centre of mass, and `frame_offset` is where the body frame of the
// scene file sits in centre-of-mass coordinates, so that every engine reports the same point.
struct RigidBody {
  std::string name;
  std::vector<BoxShape> shapes;  // relative to the centre of mass; set up once, never resized
  Vec3 frame_offset = Vec3::Zero();
  Material material;
  bool fixed = false;

  // Constant mass properties (zero inverse for fixed bodies: infinite mass).
  double mass = 0.0;
  double inv_mass = 0.0;
  Mat3 inertia_body = Mat3::Zero();
  Mat3 inv_inertia_body = Mat3::Zero();

  // State.
  Vec3 x = Vec3::Zero();            // centre of mass, world
  Quat q = Quat::Identity();        // orientation, body to world
  Vec3 P = Vec3::Zero();            // linear momentum
  Vec3 L = Vec3::Zero();            // angular momentum, world

  // Derived from the state by update_derived().
  Mat3 R = Mat3::Identity();
  Mat3 inv_inertia_world = Mat3::Zero();
  Vec3 v = Vec3::Zero();
  Vec3 omega = Vec3::Zero();

  // R = q, I^-1 = R I_body^-1 R^T, v = P / m, omega = I^-1 L.
  void update_derived();
  // Sets P and L from velocities (after update_derived() has set the world inertia).
  void set_velocity(const Vec3& linear, const Vec3& angular);
  Pose pose() const { return {x, q}; }
  // The scene-file body frame: origin and orientation as the user wrote them.
  Pose frame_pose() const { return {x + q * frame_offset, q}; }
  // World placement of shape k.
  Pose shape_pose(int k) const;
  // Velocity of the material point at world position p.
  Vec3 velocity_at(const Vec3& p) const { return v + omega.cross(p - x); }
};

// Builds a body from the scene description: computes mass properties, moves the shapes to the
// centre of mass and sets the derived quantities. A fixed body gets infinite mass.
RigidBody make_body(std::string name, const std::vector<BoxShape>& boxes, double mass,
                    const Pose& frame, const Vec3& velocity, const Vec3& angular_velocity,
                    const Material& material, bool fixed);

}  // namespace boxpile
