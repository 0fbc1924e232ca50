// Turning DART's contact points into the project's convention (midpoint position, normal from B
// toward A, depth > 0 when penetrating). No DART types: the engine and the query detectors pass
// the raw point, normal and depth. Internal to boxpile::reference.
#pragma once

#include "boxpile/reference/convention.hpp"
#include "boxpile/reference/dart/dart_settings.hpp"
#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile::reference_detail {

// Where a detector puts a contact's point (measured on a unit cube 0.01 m deep into a box, and
// checked by the conformance suite for every detector that has a row there).
enum class DartPointRule {
  FacePoint,  // dart, ode, fcl (meshes): a face contact's point lies on one box's surface, depth
              // inside the other (ODE's dBoxBox convention); an edge-edge point is the midpoint
  Midpoint,   // fcl_primitive: the midpoint already
};

constexpr DartPointRule dart_point_rule(DartDetector d) {
  return d == DartDetector::FclPrimitive ? DartPointRule::Midpoint : DartPointRule::FacePoint;
}

// A face contact's point lies either on the reference face or on the other box's surface `depth`
// inside it, and which one differs between detectors and even between the points of one set
// (DART's port of dBoxBox puts them on A's face where ODE's puts them on B's). The reference
// face's plane along n tells: a point on it moves depth/2 toward the other box, a point `depth`
// past it moves depth/2 back. The reference face is B's when n is one of B's axes (its plane at
// the top of B along n), else A's (at the bottom of A along n).
inline Vec3 dart_face_midpoint(const OrientedBox& a, const OrientedBox& b, const Vec3& p, const Vec3& n,
                               double depth) {
  const double height = n.dot(p);
  if (parallel_to_an_axis(b, n)) {
    const double face = n.dot(b.center) + b.radius_along(n);  // B's reference face
    const bool on_face = std::abs(height - face) <= std::abs(height - (face - depth));
    return on_face ? Vec3(p - 0.5 * depth * n) : Vec3(p + 0.5 * depth * n);
  }
  const double face = n.dot(a.center) - a.radius_along(n);  // A's reference face
  const bool on_face = std::abs(height - face) <= std::abs(height - (face + depth));
  return on_face ? Vec3(p + 0.5 * depth * n) : Vec3(p - 0.5 * depth * n);
}

// A box-box contact (normal n already from B toward A) in our convention.
inline Contact dart_box_box_contact(DartDetector detector, const OrientedBox& a, const OrientedBox& b,
                                    const Vec3& p, const Vec3& n, double depth) {
  const FeatureKind kind = box_box_kind(a, b, n);
  const bool face_point = dart_point_rule(detector) == DartPointRule::FacePoint && kind != FeatureKind::EdgeEdge;
  return {face_point ? dart_face_midpoint(a, b, p, n, depth) : p, n, depth, kind_only(kind)};
}

// A box-plane contact (ODE's dBoxPlane through DART, the only detector given a plane): the box's
// vertex below the plane, moved depth/2 along n toward the plane.
inline Contact dart_box_plane_contact(const Vec3& p, const Vec3& n, double depth) {
  return {p + 0.5 * depth * n, n, depth, kind_only(FeatureKind::Plane)};
}

}  // namespace boxpile::reference_detail

namespace boxpile::reference_detail {

// The ground for a detector that cannot take a half-space (DART's own has no plane shape; FCL's
// mesh mode turns a plane into a degenerate box mesh with bogus contacts; FCL's analytic
// half-space gives one point per box): a box whose top face is the plane. Its half extent, m: the
// largest box the loader accepts (kMaxHalfExtent), so that every scene's boxes fit on it near
// `near`. Larger costs depth precision: the depths against a box of 1e4 m were off by up to
// 2.3e-9 m (8 of 20,000 random poses beyond the suite's 1e-9 m), against 1e3 m by far less.
inline constexpr double kDartGroundHalfExtent = limits::kMaxHalfExtent;

// Only ODE's detector takes the ground as a plane (dCreatePlane: up to 4 points, exact).
constexpr bool dart_detector_takes_planes(DartDetector d) { return d == DartDetector::Ode; }

// The ground box below `plane`, centred under `near` (the point of interest projected on it).
inline OrientedBox dart_ground_box(const HalfSpace& plane, const Vec3& near) {
  const Vec3 n = plane.normal.normalized();
  const Vec3 on_plane = near - (n.dot(near) - plane.offset) * n;
  const Mat3 axes = Quat::FromTwoVectors(Vec3::UnitZ(), n).toRotationMatrix();
  return {on_plane - kDartGroundHalfExtent * n, axes, Vec3::Constant(kDartGroundHalfExtent)};
}

}  // namespace boxpile::reference_detail
