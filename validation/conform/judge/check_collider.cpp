#include "boxpile/validation/conform/judge/check_collider.hpp"

#include <algorithm>
#include <filesystem>

namespace boxpile {
namespace {

QueryBox query_box(const OrientedBox& b) {
  QueryBox q;
  q.half_extents = b.half;
  q.pose.position = b.center;
  q.pose.orientation = Quat(b.axes).normalized();
  return q;
}

double query_depth(const ContactQuery& q) {
  const OrientedBox a = q.a.box();
  return q.b ? true_depth(a, q.b->box()) : true_depth(a, *q.plane);
}

double scale_of(const ContactQuery& q) {
  const OrientedBox a = q.a.box();
  return q.b ? query_scale(a, q.b->box()) : query_scale(a, *q.plane);
}

QueryTally& tally_of(std::vector<std::pair<std::string, QueryTally>>& tallies, const std::string& name) {
  for (auto& [n, t] : tallies) {
    if (n == name) return t;
  }
  return tallies.emplace_back(name, QueryTally{}).second;
}

void count_in(QueryTally& t, bool answered, const std::vector<FailureKind>& kinds, bool reversed) {
  ++t.queries;
  if (answered) ++t.answered;
  if (kinds.empty()) return;
  ++t.failing;
  if (reversed) ++t.reversed;
  for (const FailureKind k : kinds) ++t.counts[k];
}

// Keeps the worst `keep` failures of each kind, in query order.
void prune(std::vector<FailedCase>& failures, int keep) {
  std::vector<bool> kept(failures.size(), false);
  std::vector<std::size_t> order(failures.size());
  for (const FailureKind k : all_failure_kinds()) {
    order.clear();
    for (std::size_t i = 0; i < failures.size(); ++i) {
      if (failures[i].relative_error(k) >= 0.0) order.push_back(i);
    }
    const std::size_t n = std::min(order.size(), static_cast<std::size_t>(keep));
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n), order.end(),
                      [&](std::size_t x, std::size_t y) {
                        const double ex = failures[x].relative_error(k), ey = failures[y].relative_error(k);
                        return ex != ey ? ex > ey : x < y;
                      });
    for (std::size_t j = 0; j < n; ++j) kept[order[j]] = true;
  }
  std::size_t out = 0;
  for (std::size_t i = 0; i < failures.size(); ++i) {
    if (!kept[i]) continue;
    if (out != i) failures[out] = std::move(failures[i]);
    ++out;
  }
  failures.resize(out);
}

// The kept failures may grow to this many times their final number between two prunings.
constexpr std::size_t kPruneSlack = 4;

// Asks the collider (twice for box-box when swapping), judges, counts, and records a failure.
void judge_one(const Collider& collider, const ContactQuery& query, const std::string& regime,
               const CheckOptions& options, CheckResult& result) {
  const Manifold answer = collider(query);
  std::optional<Manifold> swapped;
  if (options.swap && query.b) swapped = collider(swapped_query(query));
  const int index = result.queries++;
  const double scale = scale_of(query);
  const JudgeTolerances tol = options.tolerances.at_scale(scale);
  const double depth = query_depth(query);
  if (depth > tol.touching) ++result.touching;
  if (depth < -tol.touching) ++result.apart;
  std::vector<Finding> findings = judge_query(query, answer, swapped, options.tolerances);
  std::vector<FailureKind> kinds;
  for (const Finding& f : findings) {
    if (std::find(kinds.begin(), kinds.end(), f.kind) == kinds.end()) kinds.push_back(f.kind);
  }
  const ContactKind contact = contact_kind_of(query, options.tolerances);
  const bool answered = !answer.empty() && depth >= -tol.touching;
  Symptom symptom;
  if (!findings.empty()) symptom = symptom_of(query, answer, findings, contact, options.tolerances);
  count_in(tally_of(result.by_regime, regime), answered, kinds, symptom.reversed);
  count_in(result.by_contact[contact], answered, kinds, symptom.reversed);
  if (findings.empty()) return;
  ++result.failing;
  for (const FailureKind k : kinds) ++result.counts[k];
  result.symptoms.push_back(symptom);
  FailedCase failed{query.name, regime, query, answer, swapped, std::move(findings), index, scale, symptom};
  if (options.on_failure) options.on_failure(failed);
  if (options.keep <= 0) return;
  result.failures.push_back(std::move(failed));
  const std::size_t bound = kPruneSlack * all_failure_kinds().size() * static_cast<std::size_t>(options.keep);
  if (result.failures.size() > bound) prune(result.failures, options.keep);
}

}  // namespace

double FailedCase::relative_error(FailureKind k) const {
  double worst = -1.0;
  for (const Finding& f : findings) {
    if (f.kind == k) worst = std::max(worst, f.unit == ErrorUnit::Metre ? f.error / scale : f.error);
  }
  return worst;
}

int QueryTally::count(FailureKind k) const {
  const auto it = counts.find(k);
  return it == counts.end() ? 0 : it->second;
}

int CheckResult::saved(FailureKind k) const {
  return static_cast<int>(
      std::count_if(failures.begin(), failures.end(), [k](const FailedCase& c) { return c.relative_error(k) >= 0.0; }));
}

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
    const double e = c.relative_error(k);
    if (e > worst_error) {
      worst_error = e;
      worst_case = &c;
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
  const OrientedBox a = query.a.box();
  if (query.plane) return judge_box_plane(a, *query.plane, answer, tol);
  return judge_box_box(a, query.b->box(), answer, swapped, tol);
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
  result.keep = std::max(options.keep, 0);
  const int samples = options.regimes.empty() ? 0 : options.samples;
  const int total = static_cast<int>(options.cases.size()) + samples;
  auto progress = [&] {
    if (options.progress) options.progress(result.queries, total);
  };
  for (const ContactQuery& c : options.cases) {
    judge_one(collider, c, "case", options, result);
    progress();
  }
  std::mt19937_64 rng(options.seed);
  for (int k = 0; k < samples; ++k) {
    const Regime regime = options.regimes[static_cast<std::size_t>(k) % options.regimes.size()];
    const std::string name =
        std::string(regime_name(regime)) + "_" + std::to_string(options.seed) + "_" + std::to_string(k);
    judge_one(collider, query_of(random_pair(regime, rng), name), std::string(regime_name(regime)), options, result);
    progress();
  }
  if (result.keep > 0) prune(result.failures, result.keep);
  return result;
}

}  // namespace boxpile
