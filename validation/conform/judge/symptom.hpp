// What a failing answer tells about the collider beyond its findings, in a few numbers: the
// contact kind of the query, whether the normal is reversed, the depth against the truth, the
// deepest point's place along the normal. Kept for every failure (saved or not), so that
// systematic.hpp can recognise one mistake made everywhere.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/validation/conform/judge/contact_kind.hpp"
#include "boxpile/validation/conform/judge/judge.hpp"

namespace boxpile {

// A length the answer gave beside the one it should have given, m.
struct AnsweredTruth {
  double answered = 0.0;
  double truth = 0.0;
};

struct Symptom {
  ContactKind contact = ContactKind::Apart;
  std::uint8_t kinds = 0;  // bit k: a finding of FailureKind k
  // The deepest contact's normal is wrong and its reverse right.
  bool reversed = false;
  // A depth finding: the deepest depth against the penetration along its normal (the deepest
  // vertex's, on a plane).
  std::optional<AnsweredTruth> depth;
  // An outside finding with a right normal: the deepest point's offset along the normal from the
  // midway plane between the two surfaces (answered), and the overlap along the normal (truth).
  std::optional<AnsweredTruth> position;

  bool has(FailureKind k) const { return kinds >> static_cast<int>(k) & 1; }
};

Symptom symptom_of(const ContactQuery& query, const Manifold& answer, const std::vector<Finding>& findings,
                   ContactKind contact, const JudgeTolerances& tol);

// The kind of a query's contact (box_plane for a plane).
ContactKind contact_kind_of(const ContactQuery& query, const JudgeTolerances& tol);

}  // namespace boxpile
