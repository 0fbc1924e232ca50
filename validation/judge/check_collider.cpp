#include "boxpile/validation/judge/check_collider.hpp"

#include <algorithm>
#include <filesystem>

namespace boxpile {
namespace {

OrientedBox box_of(const QueryBox& q) { return OrientedBox::from(q.pose, q.half_extents); }

QueryBox query_box(const OrientedBox& b) {
  QueryBox q;
  q.half_extents = b.half;
  q.pose.position = b.center;
  q.pose.orientation = Quat(b.axes).normalized();
  return q;
}

double query_depth(const ContactQuery& q) {
  const OrientedBox a = box_of(q.a);
  return q.b ? true_depth(a, box_of(*q.b)) : true_depth(a, *q.plane);
}

// Asks the collider (twice for box-box when swapping), judges, and records a failure.
void judge_one(const Collider& collider, const ContactQuery& query, const std::string& regime,
               const CheckOptions& options, CheckResult& result) {
  const Manifold answer = collider(query);
  std::optional<Manifold> swapped;
  if (options.swap && query.b) swapped = collider(swapped_query(query));
  ++result.queries;
  const double depth = query_depth(query);
  if (depth > options.tolerances.touching) ++result.touching;
  if (depth < -options.tolerances.touching) ++result.apart;
  std::vector<Finding> findings = judge_query(query, answer, swapped, options.tolerances);
  if (findings.empty()) return;
  std::vector<FailureKind> kinds;
  for (const Finding& f : findings) {
    if (std::find(kinds.begin(), kinds.end(), f.kind) == kinds.end()) kinds.push_back(f.kind);
  }
  for (const FailureKind k : kinds) ++result.counts[k];
  result.failures.push_back({query.name, regime, query, answer, swapped, std::move(findings)});
}

}  // namespace

int CheckResult::count(FailureKind k) const {
  const auto it = counts.find(k);
  return it == counts.end() ? 0 : it->second;
}

double CheckResult::allowed(FailureKind k) const {
  const auto it = gates.find(k);
  return it == gates.end() ? 0.0 : it->second * queries;
}

bool CheckResult::within_gates() const {
  return std::all_of(counts.begin(), counts.end(), [&](const auto& kv) { return kv.second <= allowed(kv.first); });
}

const FailedCase* CheckResult::worst(FailureKind k) const {
  const FailedCase* worst_case = nullptr;
  double worst_error = -1.0;
  for (const FailedCase& c : failures) {
    for (const Finding& f : c.findings) {
      if (f.kind == k && f.error > worst_error) {
        worst_error = f.error;
        worst_case = &c;
      }
    }
  }
  return worst_case;
}

ContactQuery query_of(const BoxPair& pair, const std::string& name) {
  ContactQuery q;
  q.name = name;
  q.source = name;
  q.a = query_box(pair.a);
  q.b = query_box(pair.b);
  return q;
}

ContactQuery swapped_query(const ContactQuery& query) {
  ContactQuery q = query;
  q.a = *query.b;
  q.b = query.a;
  q.answers.clear();
  return q;
}

std::vector<Finding> judge_query(const ContactQuery& query, const Manifold& answer,
                                 const std::optional<Manifold>& swapped, const JudgeTolerances& tol) {
  const OrientedBox a = box_of(query.a);
  if (query.plane) return judge_box_plane(a, *query.plane, answer, tol);
  return judge_box_box(a, box_of(*query.b), answer, swapped, tol);
}

std::vector<ContactQuery> load_cases(const std::string& folder, std::size_t max_bytes) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(folder)) throw InputError(folder, "", "is not a folder of contact queries");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<ContactQuery> cases;
  for (const fs::path& f : files) {
    ContactQuery q = load_query(f.string(), max_bytes);
    if (q.name.empty()) q.name = f.stem().string();
    cases.push_back(std::move(q));
  }
  return cases;
}

CheckResult check_collider(const Collider& collider, const CheckOptions& options) {
  CheckResult result;
  result.gates = options.gates;
  for (const ContactQuery& c : options.cases) judge_one(collider, c, "case", options, result);
  if (options.regimes.empty()) return result;
  std::mt19937_64 rng(options.seed);
  for (int k = 0; k < options.samples; ++k) {
    const Regime regime = options.regimes[static_cast<std::size_t>(k) % options.regimes.size()];
    const std::string name =
        std::string(regime_name(regime)) + "_" + std::to_string(options.seed) + "_" + std::to_string(k);
    judge_one(collider, query_of(random_pair(regime, rng), name), std::string(regime_name(regime)), options, result);
  }
  return result;
}

}  // namespace boxpile
