// What kind of contact a query is, decided from the boxes alone, so that a collider's failures can
// be counted by the geometry they fail on: two faces, a face and an edge, two edges, a vertex on a
// face, a box on a plane, or boxes apart.
#pragma once

#include <span>
#include <string_view>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/conform/judge/judge.hpp"

namespace boxpile {

enum class ContactKind {
  FaceFace,  // the least axis is a face normal, and three or more of the other box's vertices lie below that face
  FaceEdge,  // ... two of them (an edge)
  Vertex,    // ... one (a vertex on a face)
  EdgeEdge,  // the least axis is an edge cross product, every face axis deeper beyond the face-bias band
  BoxPlane,  // a box against a plane
  Apart,     // the boxes are apart by more than the touching tolerance
};
std::span<const ContactKind> all_contact_kinds();
std::string_view contact_kind_name(ContactKind k);

// The kind of the pair: the axis of least penetration (a face normal preferred within the face-bias
// band, as judge_normal() allows), and for a face the number of the other box's vertices that
// penetrate it. `tol` as the judge's (its touching tolerance decides Apart).
ContactKind contact_kind(const OrientedBox& a, const OrientedBox& b, const JudgeTolerances& tol = {});

}  // namespace boxpile
