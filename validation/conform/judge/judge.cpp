#include "boxpile/validation/conform/judge/judge.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "boxpile/validation/conform/judge/brute_force.hpp"
#include "boxpile/validation/conform/judge/printed.hpp"

namespace boxpile {
namespace {

constexpr std::array<FailureKind, 6> kFailureKinds = {FailureKind::Missed, FailureKind::Phantom, FailureKind::Normal,
                                               FailureKind::Depth,  FailureKind::Outside, FailureKind::Swap};
constexpr std::array<std::string_view, 6> kFailureNames = {"missed", "phantom", "normal", "depth", "outside", "swap"};

double angle_between(const Vec3& u, const Vec3& v) {
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

// --- the stages of judging one box-box answer --------------------------------------------------

// Contact where there is none, or none where there is: decided by the least penetration alone.
std::optional<Finding> presence(double depth, const Manifold& answer, const JudgeTolerances& tol) {
  if (answer.empty() && depth > tol.touching) {
    return Finding{FailureKind::Missed, depth, printed("no contact, but the boxes overlap by %.3g m", depth)};
  }
  if (!answer.empty() && depth < -tol.touching) {
    const double claimed = answer.deepest().depth;
    if (claimed > -tol.touching) {
      return Finding{FailureKind::Phantom, claimed - depth,
                     printed("contact of depth %.3g m, but the boxes are %.3g m apart", claimed, -depth)};
    }
  }
  return std::nullopt;
}

// Every normal unit and a least-penetration direction within the face-bias band.
std::optional<Finding> normals(const OrientedBox& a, const OrientedBox& b, const Manifold& answer,
                               const JudgeTolerances& tol) {
  for (const Contact& c : answer) {
    const double unit_error = std::abs(c.normal.norm() - 1.0);
    if (unit_error > tol.unit) {
      return Finding{FailureKind::Normal, unit_error, printed("normal of length %.17g", c.normal.norm()),
                     ErrorUnit::Ratio};
    }
    const NormalJudgement j = judge_normal(a, b, c.normal, tol);
    if (!j.acceptable) {
      return Finding{FailureKind::Normal, j.excess,
                     printed("moving A along the normal needs %.3g m more than the least penetration "
                                 "(a wrong axis, or a normal from A toward B)",
                                 j.excess)};
    }
  }
  return std::nullopt;
}

// The deepest depth is the penetration along that contact's normal.
std::optional<Finding> depth(const OrientedBox& a, const OrientedBox& b, const Manifold& answer,
                             const JudgeTolerances& tol) {
  const Contact& d = answer.deepest();
  const double truth = directional_penetration(a, b, d.normal.normalized(), candidate_axes(a, b));
  const double error = std::abs(d.depth - truth);
  if (error <= tol.depth) return std::nullopt;
  return Finding{FailureKind::Depth, error,
                 printed("deepest depth %.9g m, the penetration along its normal is %.9g m", d.depth, truth)};
}

// A midpoint between the surfaces lies inside each box up to half the depth.
std::optional<Finding> inside(const OrientedBox& box, const char* which, const Manifold& answer,
                              const JudgeTolerances& tol) {
  for (const Contact& c : answer) {
    const double excess = outside_distance(box, c.position) - 0.5 * std::max(c.depth, 0.0);
    if (excess > tol.region) {
      return Finding{FailureKind::Outside, excess,
                     printed("point (%.6g, %.6g, %.6g) lies %.3g m outside box %s", c.position.x(),
                                 c.position.y(), c.position.z(), excess, which)};
    }
  }
  return std::nullopt;
}

// The answer for (B, A) is the same contact seen from the other side: present alike, the
// reversed normal (unless both are right in a tie), the same deepest depth and points.
std::optional<Finding> swap_symmetry(const OrientedBox& a, const OrientedBox& b, double truth,
                                     const Manifold& answer, const Manifold& swapped, const JudgeTolerances& tol) {
  if (answer.empty() != swapped.empty()) {
    if (std::abs(truth) <= tol.touching) return std::nullopt;
    return Finding{FailureKind::Swap, std::abs(truth),
                   printed("%d points for (A, B), %d for (B, A)", answer.size(), swapped.size())};
  }
  if (answer.empty()) return std::nullopt;
  const Contact& forward = answer.deepest();
  const Contact& backward = swapped.deepest();
  const double angle = angle_between(forward.normal, -backward.normal);
  if (angle > tol.normal) {
    const bool both_right = judge_normal(a, b, forward.normal, tol).acceptable &&
                            judge_normal(a, b, -backward.normal, tol).acceptable;
    if (both_right) return std::nullopt;
    return Finding{FailureKind::Swap, angle,
                   printed("the (B, A) normal is %.3g rad from the reversed (A, B) normal", angle), ErrorUnit::Radian};
  }
  const double depth_error = std::abs(forward.depth - backward.depth);
  if (depth_error > tol.depth) {
    return Finding{FailureKind::Swap, depth_error,
                   printed("deepest depth %.9g m for (A, B), %.9g m for (B, A)", forward.depth,
                               backward.depth)};
  }
  const double apart = hausdorff(answer, swapped);
  if (apart > tol.region) {
    return Finding{FailureKind::Swap, apart,
                   printed("the (B, A) points lie up to %.3g m from the (A, B) points", apart)};
  }
  return std::nullopt;
}

void add(std::vector<Finding>& out, std::optional<Finding> f) {
  if (f) out.push_back(std::move(*f));
}

}  // namespace

std::span<const FailureKind> all_failure_kinds() { return kFailureKinds; }
std::string_view failure_name(FailureKind k) { return kFailureNames[static_cast<std::size_t>(k)]; }

JudgeTolerances JudgeTolerances::at_scale(double scale) const {
  JudgeTolerances t = *this;
  const double length = relative * scale;
  t.normal = std::max(normal, relative);
  t.unit = std::max(unit, relative);
  t.depth = std::max(depth, length);
  t.region = std::max(region, length);
  t.touching = std::max(touching, length);
  t.relative = 0.0;
  return t;
}

JudgeTolerances float32_tolerances() {
  JudgeTolerances t;
  t.relative = kFloat32Relative;
  return t;
}

double query_scale(const OrientedBox& a, const OrientedBox& b) {
  return std::max({a.center.cwiseAbs().maxCoeff(), b.center.cwiseAbs().maxCoeff(), a.half.maxCoeff(),
                   b.half.maxCoeff()});
}

double query_scale(const OrientedBox& a, const HalfSpace& plane) {
  return std::max({a.center.cwiseAbs().maxCoeff(), a.half.maxCoeff(), std::abs(plane.offset)});
}

NormalJudgement judge_normal(const OrientedBox& a, const OrientedBox& b, const Vec3& n, const JudgeTolerances& given) {
  const JudgeTolerances tol = given.at_scale(query_scale(a, b));
  const std::vector<Vec3> axes = candidate_axes(a, b);
  const double least = least_penetration(a, b, axes);
  const double scale = std::max(a.half.maxCoeff(), b.half.maxCoeff());
  NormalJudgement j;
  j.excess = directional_penetration(a, b, n, axes) - least;
  j.acceptable = j.excess <= kFaceBiasRelative * least + kFaceBiasAbsolute * scale + tol.touching;
  return j;
}

double true_depth(const OrientedBox& a, const OrientedBox& b) { return least_penetration(a, b, candidate_axes(a, b)); }

double true_depth(const OrientedBox& a, const HalfSpace& plane) {
  double deepest_vertex = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; ++k) deepest_vertex = std::max(deepest_vertex, plane.offset - plane.normal.dot(a.vertex(k)));
  return deepest_vertex;
}

std::vector<Finding> judge_box_box(const OrientedBox& a, const OrientedBox& b, const Manifold& answer,
                                   const std::optional<Manifold>& swapped, const JudgeTolerances& given) {
  const JudgeTolerances tol = given.at_scale(query_scale(a, b));
  std::vector<Finding> findings;
  const double truth = true_depth(a, b);
  add(findings, presence(truth, answer, tol));
  const bool judged_as_contact = findings.empty() && !answer.empty() && truth >= -tol.touching;
  if (judged_as_contact) {
    add(findings, normals(a, b, answer, tol));
    if (findings.empty()) add(findings, depth(a, b, answer, tol));
    add(findings, inside(a, "A", answer, tol));
    add(findings, inside(b, "B", answer, tol));
  }
  if (swapped) add(findings, swap_symmetry(a, b, truth, answer, *swapped, tol));
  return findings;
}

std::vector<Finding> judge_box_plane(const OrientedBox& a, const HalfSpace& plane, const Manifold& answer,
                                     const JudgeTolerances& given) {
  const JudgeTolerances tol = given.at_scale(query_scale(a, plane));
  std::vector<Finding> findings;
  const double truth = true_depth(a, plane);
  add(findings, presence(truth, answer, tol));
  if (!findings.empty() || answer.empty() || truth < -tol.touching) return findings;
  for (const Contact& c : answer) {
    const double angle = angle_between(c.normal, plane.normal);
    const double unit_error = std::abs(c.normal.norm() - 1.0);
    if (angle > tol.normal || unit_error > tol.unit) {
      findings.push_back({FailureKind::Normal, std::max(angle, unit_error),
                          printed("normal %.3g rad from the plane's normal, length %.17g", angle,
                                      c.normal.norm()),
                          ErrorUnit::Radian});
      break;
    }
  }
  const double depth_error = std::abs(answer.deepest().depth - truth);
  if (depth_error > tol.depth) {
    findings.push_back({FailureKind::Depth, depth_error,
                        printed("deepest depth %.9g m, the deepest vertex is %.9g m below the plane",
                                    answer.deepest().depth, truth)});
  }
  add(findings, inside(a, "A", answer, tol));
  for (const Contact& c : answer) {
    // The midpoint lies half the depth below the plane's surface.
    const double excess = plane.normal.dot(c.position) - plane.offset + 0.5 * std::max(c.depth, 0.0);
    if (excess > tol.region) {
      findings.push_back({FailureKind::Outside, excess,
                          printed("point lies %.3g m above its place below the plane", excess)});
      break;
    }
  }
  return findings;
}

}  // namespace boxpile
