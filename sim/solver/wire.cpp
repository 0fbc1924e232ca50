#include "boxpile/sim/solver/wire.hpp"

#include <algorithm>

#include "boxpile/sim/solver/impulse.hpp"

namespace boxpile {

std::vector<WireJoint> make_wire_joints(const Scene& scene, const std::vector<RigidBody>& bodies) {
  std::vector<WireJoint> joints;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const auto& wire = scene.bodies[i].wire;
    if (!wire) continue;
    WireJoint j;
    j.body = static_cast<int>(i);
    j.from = wire->from;
    j.length = (wire->to - wire->from).norm();
    j.direction = (wire->to - wire->from) / j.length;
    // The anchor is given in the scene's body frame; the body frame origin sits at frame_offset
    // in centre-of-mass coordinates, and both frames share their axes.
    j.anchor = wire->anchor + bodies[i].frame_offset;
    joints.push_back(j);
  }
  return joints;
}

void enforce_wire_velocity(RigidBody& body, const WireJoint& wire) {
  if (body.fixed) return;
  const Vec3 r = body.R * wire.anchor;
  const Vec3 vp = body.velocity_at(body.x + r);
  const Mat3 K = collision_matrix_share(body, r);
  const double s = wire.along(body);
  const double v_along = wire.direction.dot(vp);
  Vec3 j;
  if ((s <= 0.0 && v_along < 0.0) || (s >= wire.length && v_along > 0.0)) {
    j = K.ldlt().solve(-vp);  // at an end and leaving it: the anchor stops
  } else {
    const Vec3 t1 = wire.direction.unitOrthogonal();
    const Vec3 t2 = wire.direction.cross(t1);
    Eigen::Matrix<double, 3, 2> T;
    T << t1, t2;
    const Eigen::Vector2d lambda = (T.transpose() * K * T).ldlt().solve(-T.transpose() * vp);
    j = T * lambda;
  }
  body.P += j;
  body.L += r.cross(j);
  body.v = body.inv_mass * body.P;
  body.omega = body.inv_inertia_world * body.L;
}

void project_onto_wire(RigidBody& body, const WireJoint& wire) {
  if (body.fixed) return;
  const Vec3 p = wire.anchor_world(body);
  const double s = std::clamp(wire.direction.dot(p - wire.from), 0.0, wire.length);
  body.x += wire.from + s * wire.direction - p;
}

void enforce_wires(std::vector<RigidBody>& bodies, const std::vector<WireJoint>& wires) {
  for (const WireJoint& w : wires) enforce_wire_velocity(bodies[w.body], w);
}

void project_wires(std::vector<RigidBody>& bodies, const std::vector<WireJoint>& wires) {
  for (const WireJoint& w : wires) {
    project_onto_wire(bodies[w.body], w);
    bodies[w.body].update_derived();
  }
}

}  // namespace boxpile
