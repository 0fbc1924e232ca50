// Judging anyone's box-box and box-plane collider: fixed cases and seeded random pose pairs go
// through the collider, the brute-force judge (judge.hpp) decides what is wrong with each answer,
// and the counts by kind are held to gates, as boxpile's own conformance suite does. The C++ face
// of `boxpile conform` (docs/conform.md), for a user's own test:
//
//   const boxpile::CheckResult r = boxpile::check_collider(my_collider, {.samples = 2000});
//   REQUIRE(r.within_gates());
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/validation/conform/judge/judge.hpp"
#include "boxpile/validation/conform/judge/pose_sampler.hpp"
#include "boxpile/validation/conform/judge/symptom.hpp"

namespace boxpile {

// A collider: the contact set of one query, in boxpile's convention.
using Collider = std::function<Manifold(const ContactQuery&)>;

// Allowed failures per kind, as a fraction of the judged queries; a kind not listed allows none.
using Gates = std::map<FailureKind, double>;

// Failures kept whole (query, answers, findings) per failure kind, the worst first: enough to
// look at, few enough that a collider wrong everywhere does not fill a disk. The rest are counted.
inline constexpr int kDefaultKeep = 100;

struct FailedCase;

struct CheckOptions {
  int samples = 1000;         // random pairs, drawn from the regimes in turn
  std::uint64_t seed = 1;     // the same seed gives the same pairs
  std::vector<Regime> regimes{all_regimes().begin(), all_regimes().end()};
  std::vector<ContactQuery> cases;  // judged before the samples (load_cases(): a folder of them)
  bool swap = true;           // also ask each box-box query with A and B swapped
  JudgeTolerances tolerances;
  Gates gates;
  int keep = kDefaultKeep;  // failures kept whole per failure kind (CheckResult::failures)
  // Called after each judged query with the queries done and the total, if set.
  std::function<void(int done, int total)> progress;
  // Called with every failure as it is found (kept or not), if set.
  std::function<void(const FailedCase&)> on_failure;
};

// A query whose answer the judge found wrong.
struct FailedCase {
  std::string name;    // the case's name, or "<regime>_<seed>_<k>" for a sample
  std::string regime;  // "case" for a fixed case
  ContactQuery query;
  Manifold answer;
  std::optional<Manifold> swapped;  // the answer for (B, A)
  std::vector<Finding> findings;
  int index = 0;         // the query's place in the run (cases first, then the samples)
  double scale = 1.0;    // query_scale(), m: errors in metres are ranked relative to it
  Symptom symptom;

  // The largest error of kind k relative to the query (lengths over the scale), -1 if none.
  double relative_error(FailureKind k) const;
};

// Queries and failures of one part of a run: a regime, or a contact kind.
struct QueryTally {
  int queries = 0;
  int answered = 0;  // queries with overlapping (or touching) boxes answered with a contact
  int failing = 0;
  int reversed = 0;  // failing with the deepest normal reversed
  std::map<FailureKind, int> counts;

  int count(FailureKind k) const;
};

struct CheckResult {
  int queries = 0;  // judged queries (a swapped ask belongs to its query)
  int touching = 0;  // queries whose boxes truly overlap by more than the touching tolerance
  int apart = 0;     // queries whose boxes are truly apart by more than the touching tolerance
  int failing = 0;   // queries with any finding
  std::map<FailureKind, int> counts;  // queries failing each kind
  // The worst `keep` failures of each kind (relative_error()), in query order; the rest are
  // counted in `counts`, the tallies and `symptoms` only.
  std::vector<FailedCase> failures;
  std::vector<Symptom> symptoms;  // of every failure, in query order
  std::vector<std::pair<std::string, QueryTally>> by_regime;  // "case" first, then the regimes in their order
  std::map<ContactKind, QueryTally> by_contact;
  Gates gates;
  int keep = kDefaultKeep;

  int count(FailureKind k) const;
  // The failures of kind k allowed by the gate.
  double allowed(FailureKind k) const;
  bool within_gates() const;
  // The kept failed case with the largest relative error of kind k, if any.
  const FailedCase* worst(FailureKind k) const;
  // How many failures of kind k are kept whole in `failures`.
  int saved(FailureKind k) const;
};

CheckResult check_collider(const Collider& collider, const CheckOptions& options = {});

// The query of a pose pair, with exact quaternions of the boxes' axes.
ContactQuery query_of(const BoxPair& pair, const std::string& name);
// The same query with A and B exchanged (box-box only).
ContactQuery swapped_query(const ContactQuery& query);
// What is wrong with `answer` (and the swapped answer, for box-box) for the query.
std::vector<Finding> judge_query(const ContactQuery& query, const Manifold& answer,
                                 const std::optional<Manifold>& swapped, const JudgeTolerances& tol = {});
// Every *.json query in a folder, by file name; InputError for a file that is no query.
std::vector<ContactQuery> load_cases(const std::string& folder, std::size_t max_bytes = limits::kDefaultMaxInputBytes);

}  // namespace boxpile
