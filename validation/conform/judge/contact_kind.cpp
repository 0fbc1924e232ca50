#include "boxpile/validation/conform/judge/contact_kind.hpp"

#include <array>
#include <limits>

#include "boxpile/validation/conform/judge/brute_force.hpp"

namespace boxpile {
namespace {

constexpr std::array<ContactKind, 6> kContactKinds = {ContactKind::FaceFace, ContactKind::FaceEdge, ContactKind::Vertex,
                                               ContactKind::EdgeEdge, ContactKind::BoxPlane, ContactKind::Apart};
constexpr std::array<std::string_view, 6> kContactKindNames = {"face-face", "face-edge", "vertex",
                                                        "edge-edge", "box-plane", "apart"};

// The vertices of `incident` below the face of `reference` whose outward normal is n: deeper than
// the touching tolerance below zero (a grazing face-face pair counts all four).
int vertices_below(const OrientedBox& reference, const OrientedBox& incident, const Vec3& n, double touching) {
  const double surface = reference.center.dot(n) + reference.radius_along(n);
  int below = 0;
  for (int k = 0; k < 8; ++k) {
    if (surface - incident.vertex(k).dot(n) > -touching) ++below;
  }
  return below;
}

}  // namespace

std::span<const ContactKind> all_contact_kinds() { return kContactKinds; }
std::string_view contact_kind_name(ContactKind k) { return kContactKindNames[static_cast<std::size_t>(k)]; }

ContactKind contact_kind(const OrientedBox& a, const OrientedBox& b, const JudgeTolerances& given) {
  const JudgeTolerances tol = given.at_scale(query_scale(a, b));
  const double least = true_depth(a, b);
  if (least < -tol.touching) return ContactKind::Apart;
  // The shallowest face axis, and which box owns it.
  double face_depth = std::numeric_limits<double>::infinity();
  const OrientedBox* reference = &a;
  Vec3 face_axis = Vec3::UnitZ();
  for (const OrientedBox* owner : {&a, &b}) {
    for (int i = 0; i < 3; ++i) {
      const Vec3 u = owner->axes.col(i);
      const double overlap = projected_overlap(a, b, u);
      if (overlap < face_depth) {
        face_depth = overlap;
        reference = owner;
        face_axis = u;
      }
    }
  }
  const double scale = std::max(a.half.maxCoeff(), b.half.maxCoeff());
  const double band = kFaceBiasRelative * least + kFaceBiasAbsolute * scale + tol.touching;
  if (face_depth - least > band) return ContactKind::EdgeEdge;
  const OrientedBox& incident = reference == &a ? b : a;
  // The reference face faces the incident box.
  const Vec3 n = (incident.center - reference->center).dot(face_axis) >= 0 ? face_axis : Vec3(-face_axis);
  const int below = vertices_below(*reference, incident, n, tol.touching + std::max(0.0, -least));
  if (below >= 3) return ContactKind::FaceFace;
  return below == 2 ? ContactKind::FaceEdge : ContactKind::Vertex;
}

}  // namespace boxpile
