// What each registered reference detector is known to get wrong, measured in the conformance
// suite (tests/test_conformance.cpp, docs/reference-engines.md): one row per bias, naming the
// detector (validation/contacts/detectors.hpp). `boxpile conform` puts every failing query to the
// references; a reference "also wrong" only within its own known bias does not vouch that the
// query is hard, so the report counts it apart.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/validation/conform/judge/judge.hpp"

namespace boxpile {

// Bullet's port of dBoxBox adds this to every |C_ij| before the edge-axis tests (its fudge2), so
// its edge-edge depth exceeds the true one by kBulletEdgeFudge (a_i1 + a_i2 + b_j1 + b_j2) /
// |Ai x Bj|. ODE 0.16 has no such term (fixture crossing_edges).
inline constexpr double kBulletEdgeFudge = 1e-5;

// The depth Bullet's fudge2 adds along normal n: the term of the edge pair whose cross product is
// n (0 when n is no edge-edge direction of the boxes).
double bullet_edge_fudge(const OrientedBox& a, const OrientedBox& b, const Vec3& n);

// A detector's answer to a query and the judge's finding on it.
struct JudgedAnswer {
  const ContactQuery& query;
  const Manifold& answer;
  const std::optional<Manifold>& swapped;
  const Finding& finding;
  const JudgeTolerances& tol;  // at the query's scale
};

struct KnownBias {
  std::string_view detector;
  std::string_view name;  // a few words, shown in reports
  std::string_view description;
  bool (*explains)(const JudgedAnswer& judged);
};

std::span<const KnownBias> known_biases();

// The known bias of `detector` that explains the finding, if any.
const KnownBias* explaining_bias(std::string_view detector, const JudgedAnswer& judged);

}  // namespace boxpile
