// The brute-force judge of a contact set: is a collider's answer for one box-box or box-plane
// query right in boxpile's convention (position midway between the surfaces, normal from B toward
// A, depth > 0 when penetrating)? Every criterion is decided from the boxes alone, never by
// comparing with another detector: the conformance suite, `boxpile conform` and
// check_collider() all judge through it.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// --- tolerances --------------------------------------------------------------------------------
// Boxes of 0.1-1 m computed in double precision: detectors that agree differ by rounding
// (1e-15 m); these bounds sit far above that and far below any physical difference.
inline constexpr double kJudgeNormalTolerance = 1e-8;  // rad, between normals meant to be equal
inline constexpr double kJudgeDepthTolerance = 1e-9;   // m, between a depth and the true one
// ODE and Bullet find face points through a 2x2 inverse, which loses digits when the incident
// face stands nearly on edge: 1e-7 m covers that.
inline constexpr double kJudgeRegionTolerance = 1e-7;  // m, a point outside a box or region
inline constexpr double kJudgeUnitTolerance = 1e-12;   // |n| - 1
// Within this of zero, the least penetration says "touching": contact and no contact are both
// right.
inline constexpr double kJudgeTouchingTolerance = 1e-9;  // m
// Detectors prefer a face axis to an edge axis up to about 5% of depth (ours: an edge only if 5%
// + 1e-6 scale shallower; ODE and Bullet: a fudge factor of 1.05), so a normal whose penetration
// exceeds the least by up to this band is right.
inline constexpr double kFaceBiasRelative = 1.0 / 0.95 - 1.0;
inline constexpr double kFaceBiasAbsolute = 1e-6 / 0.95;  // times the largest half extent

// A single-precision collider rounds every number it holds to 2^-24 of its size (the unit
// roundoff of IEEE binary32). A depth or a point is a difference of sums of some tens of
// coordinates and products, each rounded once, so its error is some tens of roundoffs of the
// query's scale (its largest coordinate or half extent); the float32 tolerances allow 64 of them
// (3.8e-6 of the scale). Measured: boxpile's own detector with its queries and answers rounded to
// float32 (tests/scripts/collider_wrapper.py) errs by 1e-7 to 2e-7 of the scale at most over
// 5,000 pairs of every regime and the fixtures (docs/conform.md), 19 times below the bound.
inline constexpr double kFloat32Roundoff = 0x1p-24;
inline constexpr double kFloat32RoundingOps = 64;
inline constexpr double kFloat32Relative = kFloat32RoundingOps * kFloat32Roundoff;

// Tolerances a judge applies; the defaults suit a double-precision collider of boxes near unit
// size. `relative` scales them to the query: each length tolerance is at least `relative` times
// the query's scale (query_scale()), the unit and angle tolerances at least `relative` itself;
// float32_tolerances() suits a single-precision collider.
struct JudgeTolerances {
  double normal = kJudgeNormalTolerance;      // rad
  double depth = kJudgeDepthTolerance;        // m
  double region = kJudgeRegionTolerance;      // m
  double unit = kJudgeUnitTolerance;          // |n| - 1
  double touching = kJudgeTouchingTolerance;  // m
  double relative = 0.0;                      // of the query's scale

  // The tolerances for a query of this scale (m): `relative` applied, `relative` itself 0.
  JudgeTolerances at_scale(double scale) const;
};
// The tolerances of a collider computing in single precision.
JudgeTolerances float32_tolerances();

// The size of the numbers a collider handles for this query, m: the largest coordinate of a box's
// centre, the largest half extent, the plane's offset.
double query_scale(const OrientedBox& a, const OrientedBox& b);
double query_scale(const OrientedBox& a, const HalfSpace& plane);

// --- what can be wrong -------------------------------------------------------------------------
enum class FailureKind {
  Missed,   // the boxes overlap by more than the touching tolerance, the answer has no contact
  Phantom,  // the boxes are apart by more than the touching tolerance, the answer says they touch
  Normal,   // a normal not unit, or not the least-penetration direction within the face-bias band
  Depth,    // the deepest depth is not the true penetration along the answer's normal
  Outside,  // a point lies outside box A or B by more than half its depth
  Swap,     // the answer for (B, A) is not the answer for (A, B) with the normal reversed
};
std::span<const FailureKind> all_failure_kinds();
std::string_view failure_name(FailureKind k);

// What a finding's error is measured in: a length, an angle, or a pure number (|n| - 1).
enum class ErrorUnit { Metre, Radian, Ratio };

// One failed criterion: which, by how much (in `unit`), and a sentence.
struct Finding {
  FailureKind kind;
  double error = 0.0;
  std::string why;
  ErrorUnit unit = ErrorUnit::Metre;
};

// --- the brute-force quantities of one pair -----------------------------------------------------
// How much the penetration along n exceeds the least penetration, and whether that is within the
// face-bias band.
struct NormalJudgement {
  double excess = 0.0;  // m
  bool acceptable = false;
};
NormalJudgement judge_normal(const OrientedBox& a, const OrientedBox& b, const Vec3& n,
                             const JudgeTolerances& tol = {});

// The least penetration of A and B over the 15 separating axes, m (negative when apart).
double true_depth(const OrientedBox& a, const OrientedBox& b);
// The depth of the box's deepest vertex below the plane, m (negative when above).
double true_depth(const OrientedBox& a, const HalfSpace& plane);

// --- judging answers ---------------------------------------------------------------------------
// What is wrong with `answer` for boxes A and B; empty when it is right. `swapped`, when given,
// is the same collider's answer for (B, A).
std::vector<Finding> judge_box_box(const OrientedBox& a, const OrientedBox& b, const Manifold& answer,
                                   const std::optional<Manifold>& swapped = {}, const JudgeTolerances& tol = {});
// What is wrong with `answer` for box A against the plane (its normal is the answer's normal).
std::vector<Finding> judge_box_plane(const OrientedBox& a, const HalfSpace& plane, const Manifold& answer,
                                     const JudgeTolerances& tol = {});

}  // namespace boxpile
