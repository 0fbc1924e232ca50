#include "boxpile/validation/conform/judge/symptom.hpp"

#include <algorithm>
#include <cmath>

#include "boxpile/validation/conform/judge/brute_force.hpp"

namespace boxpile {
namespace {

bool plane_normal_right(const HalfSpace& plane, const Vec3& n, const JudgeTolerances& tol) {
  return std::atan2(n.cross(plane.normal).norm(), n.dot(plane.normal)) <= tol.normal;
}

bool normal_right(const ContactQuery& q, const Vec3& n, const JudgeTolerances& tol) {
  if (q.plane) return plane_normal_right(*q.plane, n.normalized(), tol);
  return judge_normal(q.a.box(), q.b->box(), n.normalized(), tol).acceptable;
}

AnsweredTruth depth_of(const ContactQuery& q, const Contact& c) {
  const OrientedBox a = q.a.box();
  if (q.plane) return {c.depth, true_depth(a, *q.plane)};
  const OrientedBox b = q.b->box();
  return {c.depth, directional_penetration(a, b, c.normal.normalized(), candidate_axes(a, b))};
}

// The midway plane between B's surface and A's along n: B reaches up to its support along n, A
// down to its support along -n (the plane's surface and A's deepest vertex, on a plane).
AnsweredTruth position_of(const ContactQuery& q, const Contact& c) {
  const OrientedBox a = q.a.box();
  const Vec3 n = q.plane ? q.plane->normal : Vec3(c.normal.normalized());
  const double a_low = a.center.dot(n) - a.radius_along(n);
  const double b_high = q.plane ? q.plane->offset : q.b->box().center.dot(n) + q.b->box().radius_along(n);
  return {n.dot(c.position) - 0.5 * (a_low + b_high), b_high - a_low};
}

}  // namespace

ContactKind contact_kind_of(const ContactQuery& query, const JudgeTolerances& tol) {
  if (query.plane) return ContactKind::BoxPlane;
  return contact_kind(query.a.box(), query.b->box(), tol);
}

Symptom symptom_of(const ContactQuery& query, const Manifold& answer, const std::vector<Finding>& findings,
                   ContactKind contact, const JudgeTolerances& tol) {
  Symptom s;
  s.contact = contact;
  for (const Finding& f : findings) s.kinds |= static_cast<std::uint8_t>(1u << static_cast<int>(f.kind));
  if (answer.empty()) return s;
  const Contact& d = answer.deepest();
  const bool right = normal_right(query, d.normal, tol);
  s.reversed = s.has(FailureKind::Normal) && !right && normal_right(query, -d.normal, tol);
  if (s.has(FailureKind::Depth)) s.depth = depth_of(query, d);
  if (s.has(FailureKind::Outside) && right) s.position = position_of(query, d);
  return s;
}

}  // namespace boxpile
