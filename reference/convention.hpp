// Turning a reference engine's contact points into the project's convention (position midway
// between the surfaces, normal from B toward A, depth > 0 when penetrating). Internal to
// boxpile::reference.
#pragma once

#include <cmath>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"

namespace boxpile::reference_detail {

// A face normal from ODE or Bullet is a column of a box's rotation matrix, copied or negated, so
// it matches an axis to rounding; an edge-edge normal is a normalised cross product that is
// parallel to no face axis except by coincidence. This tolerance on 1 - |cos| separates the two.
inline constexpr double kAxisParallelTolerance = 1e-9;

inline bool parallel_to_an_axis(const OrientedBox& box, const Vec3& n) {
  return (box.axes.transpose() * n).cwiseAbs().maxCoeff() > 1.0 - kAxisParallelTolerance;
}

// The kind of a box-box contact judged from its normal alone (ODE and Bullet do not report it):
// a face of A, a face of B, or an edge pair. A normal along an axis of both boxes is reported
// as FaceA; compare kinds with is_face_kind() when that ambiguity matters.
inline FeatureKind box_box_kind(const OrientedBox& a, const OrientedBox& b, const Vec3& n) {
  if (parallel_to_an_axis(a, n)) return FeatureKind::FaceA;
  if (parallel_to_an_axis(b, n)) return FeatureKind::FaceB;
  return FeatureKind::EdgeEdge;
}

// How far p lies outside the box (negative inside): the largest |p_local_i| - h_i.
inline double signed_outside(const OrientedBox& box, const Vec3& p) {
  const Vec3 local = box.axes.transpose() * (p - box.center);
  return (local.cwiseAbs() - box.half).maxCoeff();
}

// ODE's dBoxBox puts a face contact on the incident face: the point lies on the incident box's
// surface, `depth` inside the reference box, and reaching the reference face means moving
// it by `depth` along the reference face's outward normal. With the reference face on A that
// normal is -n (n from B toward A), on B it is +n. When n is an axis of both boxes the point
// itself says which box it lies on.
inline Vec3 ode_face_midpoint(const OrientedBox& a, const OrientedBox& b, const Vec3& p,
                              const Vec3& n, double depth) {
  const bool a_face = parallel_to_an_axis(a, n);
  const bool b_face = parallel_to_an_axis(b, n);
  bool reference_is_a = a_face;
  if (a_face && b_face) reference_is_a = std::abs(signed_outside(b, p)) <= std::abs(signed_outside(a, p));
  return reference_is_a ? Vec3(p - 0.5 * depth * n) : Vec3(p + 0.5 * depth * n);
}

// A reference contact carries only its kind in the feature id: the engines number no features.
inline FeatureId kind_only(FeatureKind kind) { return FeatureId::make(kind, 0, 0, 0); }

}  // namespace boxpile::reference_detail
