#include "boxpile/sim/body.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

namespace boxpile {

Material combine_materials(const Material& a, const Material& b) {
  Material m;
  m.friction = std::sqrt(a.friction * b.friction);
  m.restitution = std::max(a.restitution, b.restitution);
  if (a.static_friction || b.static_friction) m.static_friction = std::sqrt(a.static_mu() * b.static_mu());
  return m;
}

namespace {

double box_volume(const Vec3& half_extents) {
  return 8.0 * half_extents.x() * half_extents.y() * half_extents.z();
}

// Inertia of a solid box of mass m about its centre, in its own axes. With edge lengths
// a, b, c = 2 h: I = m/12 diag(b^2 + c^2, a^2 + c^2, a^2 + b^2) = m/3 diag(hy^2 + hz^2, ...)
// (Baraff, "An Introduction to Physically Based Modeling: Rigid Body Simulation I", SIGGRAPH
// course notes, the inertia of a block).
Mat3 box_inertia(double m, const Vec3& h) {
  const Vec3 sq = h.cwiseProduct(h);
  return (m / 3.0 * Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y())).asDiagonal();
}

}  // namespace

MassProperties compute_mass_properties(const std::vector<BoxShape>& boxes, double mass) {
  assert(!boxes.empty());
  double volume = 0.0;
  Vec3 moment = Vec3::Zero();
  for (const BoxShape& box : boxes) {
    const double vk = box_volume(box.half_extents);
    volume += vk;
    moment += vk * box.offset;
  }
  assert(volume > 0.0);

  MassProperties props;
  props.mass = mass;
  // Uniform density, so the centre of mass is the centroid of the volume, c = sum V_k c_k / V.
  // Weighting by volume rather than mass keeps it defined for a fixed body given no mass.
  props.center_of_mass = moment / volume;

  // Box k carries m_k = m V_k / V. Its inertia about its centre, in body axes, is R_k I_k R_k^T
  // (a change of basis of the tensor); moved to the common centre of mass by the parallel-axis
  // (Huygens-Steiner) theorem, I = I_c + m_k (|d|^2 E - d d^T), d = c_k - c.
  // Overlapping boxes count their shared volume twice: the compound's density is per box.
  for (const BoxShape& box : boxes) {
    const double mk = mass * box_volume(box.half_extents) / volume;
    const Mat3 rk = box.orientation.normalized().toRotationMatrix();
    const Vec3 d = box.offset - props.center_of_mass;
    props.inertia += rk * box_inertia(mk, box.half_extents) * rk.transpose() +
                     mk * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  return props;
}

void RigidBody::update_derived() {
  // Integrating q lets |q| drift from 1; renormalising keeps R a rotation (Baraff's notes,
  // "quaternions vs. rotation matrices").
  q.normalize();
  R = q.toRotationMatrix();
  // The body-frame tensor seen in world axes: I = R I_body R^T, so I^-1 = R I_body^-1 R^T
  // (Baraff's notes, "the inertia tensor").
  inv_inertia_world = R * inv_inertia_body * R.transpose();
  v = inv_mass * P;
  omega = inv_inertia_world * L;
}

void RigidBody::set_velocity(const Vec3& linear, const Vec3& angular) {
  // A fixed body has infinite mass: it never moves, whatever it is asked to do.
  if (fixed) {
    P.setZero();
    L.setZero();
  } else {
    // P = m v, L = I omega with I = R I_body R^T.
    P = mass * linear;
    L = R * inertia_body * R.transpose() * angular;
  }
  v = inv_mass * P;
  omega = inv_inertia_world * L;
}

Pose RigidBody::shape_pose(int k) const {
  assert(k >= 0 && k < static_cast<int>(shapes.size()));
  const BoxShape& s = shapes[static_cast<std::size_t>(k)];
  return pose() * Pose{s.offset, s.orientation};
}

RigidBody make_body(std::string name, const std::vector<BoxShape>& boxes, double mass,
                    const Pose& frame, const Vec3& velocity, const Vec3& angular_velocity,
                    const Material& material, bool fixed) {
  assert(!boxes.empty() && static_cast<int>(boxes.size()) <= kMaxBoxesPerBody);
  const MassProperties props = compute_mass_properties(boxes, mass);

  RigidBody body;
  body.name = std::move(name);
  body.material = material;
  body.fixed = fixed;

  // The body axes are the scene frame's axes; only the origin moves, to the centre of mass c.
  // Shapes are re-expressed about c, and the frame origin sits at -c in those coordinates.
  body.shapes = boxes;
  for (BoxShape& s : body.shapes) s.offset -= props.center_of_mass;
  body.frame_offset = -props.center_of_mass;

  // Fixed bodies keep the mass they were given (0 when none) for reports, but have infinite
  // mass in the dynamics: zero inverse mass and inverse inertia.
  body.mass = props.mass;
  body.inertia_body = props.inertia;
  if (!fixed) {
    assert(mass > 0.0);
    body.inv_mass = 1.0 / mass;
    body.inv_inertia_body = props.inertia.inverse();
  }

  body.q = frame.orientation.normalized();
  body.x = frame.position + body.q * props.center_of_mass;
  body.update_derived();
  body.set_velocity(velocity, angular_velocity);
  return body;
}

double smallest_edge(const RigidBody& body) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const BoxShape& box : body.shapes) smallest = std::min(smallest, 2.0 * box.half_extents.minCoeff());
  return smallest;
}

}  // namespace boxpile
