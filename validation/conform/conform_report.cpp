#include "boxpile/validation/conform/conform_report.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <sstream>

#include "boxpile/validation/contacts/detectors.hpp"
#include "boxpile/validation/core/json_output.hpp"
#include "boxpile/validation/conform/known_biases.hpp"
#include "boxpile/validation/core/report_directory.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;

// The detector name a saved failure gives the collider's answer.
constexpr const char* kColliderAnswer = "collider";

std::string failure_file(const FailedCase& c) { return "failures/" + c.name + ".json"; }

std::string findings_text(const FailedCase& c) {
  std::string text;
  for (const Finding& f : c.findings) {
    text += (text.empty() ? "" : "; ") + std::string(failure_name(f.kind)) + ": " + f.why;
  }
  return text;
}

nlohmann::json findings_json(const FailedCase& c) {
  nlohmann::json out = nlohmann::json::array();
  for (const Finding& f : c.findings) {
    out.push_back({{"kind", failure_name(f.kind)}, {"error", f.error}, {"why", f.why}});
  }
  return out;
}

// "own right, ode right, bullet depth (known: edge-edge depth + fudge2)": each registered
// detector's verdict on a failing query.
std::string detectors_text(const std::vector<DetectorFindings>& judged) {
  std::string text;
  for (const DetectorFindings& d : judged) {
    std::string kinds, known;
    for (std::size_t k = 0; k < d.findings.size(); ++k) {
      if (!kinds.empty()) kinds += '+';
      kinds += failure_name(d.findings[k].kind);
      if (!d.biases[k].empty() && known.find(d.biases[k]) == std::string::npos) {
        known += (known.empty() ? "" : ", ") + d.biases[k];
      }
    }
    text += (text.empty() ? "" : ", ") + d.detector + " " + (kinds.empty() ? "right" : kinds);
    if (d.within_bias()) text += " (its known bias: " + known + ")";
  }
  return text;
}

nlohmann::json detectors_json(const std::vector<DetectorFindings>& judged) {
  nlohmann::json out = nlohmann::json::object();
  for (const DetectorFindings& d : judged) {
    nlohmann::json kinds = nlohmann::json::array();
    for (std::size_t k = 0; k < d.findings.size(); ++k) {
      nlohmann::json f = {{"kind", failure_name(d.findings[k].kind)}, {"why", d.findings[k].why}};
      if (!d.biases[k].empty()) f["known_bias"] = d.biases[k];
      kinds.push_back(std::move(f));
    }
    out[d.detector] = kinds;
  }
  return out;
}

void tally_detectors(std::vector<DetectorTally>& tallies, const std::vector<DetectorFindings>& judged) {
  for (const DetectorFindings& d : judged) {
    auto it = std::find_if(tallies.begin(), tallies.end(), [&](const DetectorTally& t) { return t.detector == d.detector; });
    if (it == tallies.end()) {
      it = tallies.emplace(tallies.end());
      it->detector = d.detector;
    }
    ++it->judged;
    if (d.within_bias()) {
      ++it->within_bias;
      for (const std::string& b : d.biases) {
        if (!b.empty()) ++it->biases[b];
      }
    } else if (d.wrong()) {
      ++it->wrong;
    }
  }
}

// --- the sections of conform.json --------------------------------------------------------------

nlohmann::json settings_json(const ConformRun& run) {
  nlohmann::json regimes = nlohmann::json::array();
  for (const Regime r : run.options.regimes) regimes.push_back(regime_name(r));
  const JudgeTolerances& t = run.options.tolerances;
  return {{"collider", run.collider},
          {"cases", run.cases},
          {"samples", run.options.samples},
          {"seed", run.options.seed},
          {"regimes", regimes},
          {"swap", run.options.swap},
          {"keep", run.options.keep},
          {"tolerance", run.tolerance},
          {"tolerances",
           {{"normal", t.normal},
            {"depth", t.depth},
            {"region", t.region},
            {"unit", t.unit},
            {"touching", t.touching},
            {"relative", t.relative}}}};
}

nlohmann::json counts_json(const CheckResult& r) {
  nlohmann::json kinds = nlohmann::json::object();
  for (const FailureKind k : all_failure_kinds()) {
    kinds[std::string(failure_name(k))] = {{"count", r.count(k)}, {"allowed", r.allowed(k)}, {"saved", r.saved(k)}};
  }
  return kinds;
}

nlohmann::json tally_json(const QueryTally& t) {
  nlohmann::json kinds = nlohmann::json::object();
  for (const FailureKind k : all_failure_kinds()) kinds[std::string(failure_name(k))] = t.count(k);
  return {{"queries", t.queries}, {"answered", t.answered}, {"failing", t.failing}, {"reversed_normals", t.reversed},
          {"failures_by_kind", kinds}};
}

nlohmann::json tallies_json(const CheckResult& r) {
  nlohmann::json regimes = nlohmann::json::object(), contacts = nlohmann::json::object();
  for (const auto& [name, t] : r.by_regime) regimes[name] = tally_json(t);
  for (const ContactKind k : all_contact_kinds()) {
    const auto it = r.by_contact.find(k);
    if (it != r.by_contact.end()) contacts[std::string(contact_kind_name(k))] = tally_json(it->second);
  }
  return {{"by_regime", regimes}, {"by_contact", contacts}};
}

nlohmann::json systematic_json(const std::vector<SystematicError>& found) {
  nlohmann::json out = nlohmann::json::array();
  for (const SystematicError& e : found) {
    nlohmann::json j = {{"pattern", e.pattern}, {"value", e.value}, {"spread", e.spread},
                        {"count", e.count},     {"of", e.of},       {"text", e.text}};
    if (!e.contact.empty()) j["contact"] = e.contact;
    out.push_back(std::move(j));
  }
  return out;
}

nlohmann::json detector_tallies_json(const std::vector<DetectorTally>& tallies) {
  nlohmann::json out = nlohmann::json::object();
  for (const DetectorTally& t : tallies) {
    out[t.detector] = {{"judged", t.judged}, {"wrong", t.wrong}, {"within_known_bias", t.within_bias},
                       {"known_biases", t.biases}};
  }
  return out;
}

nlohmann::json failures_json(const ConformRun& run) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k < run.result.failures.size(); ++k) {
    const FailedCase& c = run.result.failures[k];
    nlohmann::json entry = {{"name", c.name},
                            {"regime", c.regime},
                            {"contact", contact_kind_name(c.symptom.contact)},
                            {"file", failure_file(c)},
                            {"findings", findings_json(c)}};
    if (k < run.detectors.size()) entry["detectors"] = detectors_json(run.detectors[k]);
    out.push_back(std::move(entry));
  }
  return out;
}

// --- the sections of conform.md ----------------------------------------------------------------

void write_md_heading(std::ostream& md, const ConformRun& run) {
  const CheckResult& r = run.result;
  md << "# boxpile conform\n\n"
     << "Collider: `" << run.collider << "`\n\n"
     << "Verdict: **" << (r.within_gates() ? "within the gates" : "NOT within the gates") << "** — " << r.queries
     << " queries (" << r.touching << " with the boxes overlapping), " << r.failing << " failing, in "
     << run.seconds << " s.\n\n";
}

void write_md_settings(std::ostream& md, const ConformRun& run) {
  const JudgeTolerances& t = run.options.tolerances;
  md << "Fixed cases: " << (run.cases.empty() ? "none" : "`" + run.cases + "`") << "; random pairs: "
     << run.options.samples << " (seed " << run.options.seed << ", regimes";
  for (const Regime reg : run.options.regimes) md << ' ' << regime_name(reg);
  md << "); swapped queries: " << (run.options.swap ? "asked" : "not asked") << "; tolerance " << run.tolerance
     << " (depth " << t.depth << " m, points " << t.region << " m, |n| - 1 " << t.unit;
  if (t.relative > 0) md << ", each at least " << t.relative << " of the query's scale";
  md << ").\n\n";
}

void write_md_systematic(std::ostream& md, const ConformRun& run) {
  if (run.systematic.empty()) return;
  md << "## One mistake, made everywhere\n\n";
  for (const SystematicError& e : run.systematic) md << "- " << e.text << "\n";
  md << '\n';
}

void write_md_counts(std::ostream& md, const CheckResult& r) {
  md << "## Failures by kind\n\n| kind | failing queries | allowed | saved |\n|---|---:|---:|---:|\n";
  for (const FailureKind k : all_failure_kinds()) {
    md << "| " << failure_name(k) << " | " << r.count(k) << " | " << r.allowed(k) << " | " << r.saved(k) << " |\n";
  }
  md << '\n';
  if (r.failing == 0) return;
  md << "The worst " << r.keep << " failures of each kind (by error relative to the query's scale) are saved under "
        "`failures/` (" << r.failures.size() << " files); the others are counted here only.\n\n";
}

void write_md_tally_table(std::ostream& md, const std::string& title, const std::string& column,
                          const std::vector<std::pair<std::string, const QueryTally*>>& rows) {
  md << "## " << title << "\n\n| " << column << " | queries | answered | failing | reversed normals";
  for (const FailureKind k : all_failure_kinds()) md << " | " << failure_name(k);
  md << " |\n|---|---:|---:|---:|---:";
  for (std::size_t k = 0; k < all_failure_kinds().size(); ++k) md << "|---:";
  md << "|\n";
  for (const auto& [name, t] : rows) {
    md << "| " << name << " | " << t->queries << " | " << t->answered << " | " << t->failing << " | " << t->reversed;
    for (const FailureKind k : all_failure_kinds()) md << " | " << t->count(k);
    md << " |\n";
  }
  md << '\n';
}

std::vector<std::pair<std::string, const QueryTally*>> regime_rows(const CheckResult& r) {
  std::vector<std::pair<std::string, const QueryTally*>> rows;
  for (const auto& [name, t] : r.by_regime) rows.emplace_back(name, &t);
  return rows;
}

std::vector<std::pair<std::string, const QueryTally*>> contact_rows(const CheckResult& r) {
  std::vector<std::pair<std::string, const QueryTally*>> rows;
  for (const ContactKind k : all_contact_kinds()) {
    const auto it = r.by_contact.find(k);
    if (it != r.by_contact.end()) rows.emplace_back(std::string(contact_kind_name(k)), &it->second);
  }
  return rows;
}

void write_md_worst(std::ostream& md, const ConformRun& run) {
  const CheckResult& r = run.result;
  md << "## The worst of each kind\n\n";
  bool any = false;
  for (const FailureKind k : all_failure_kinds()) {
    const FailedCase* c = r.worst(k);
    if (!c) continue;
    any = true;
    md << "- **" << failure_name(k) << "**: `" << failure_file(*c) << "` (" << c->regime << ", "
       << contact_kind_name(c->symptom.contact) << "): " << findings_text(*c);
    const auto index = static_cast<std::size_t>(c - r.failures.data());
    if (index < run.detectors.size()) md << ". The detectors on it: " << detectors_text(run.detectors[index]);
    md << "\n";
  }
  if (!any) md << (r.failing == 0 ? "None: every answer was right.\n" : "None saved (`--keep 0`).\n");
  md << "\nEach saved failing query is under `failures/` with the collider's answer; "
        "`boxpile contacts failures/NAME.json` shows it beside ours, ODE's and Bullet's.\n";
}

void write_md_detectors(std::ostream& md, const ConformRun& run) {
  if (run.detector_tallies.empty()) return;
  md << "\n## The registered detectors on the failing queries\n\n"
        "Each failing query put to every registered detector and judged the same way. A detector wrong only "
        "within its known bias (measured in the conformance suite) does not make a query a hard case.\n\n"
        "| detector | also wrong | wrong within its known bias | of |\n|---|---:|---:|---:|\n";
  for (const DetectorTally& t : run.detector_tallies) {
    md << "| " << t.detector << " | " << t.wrong << " | " << t.within_bias;
    std::string names;
    for (const auto& [name, n] : t.biases) names += (names.empty() ? " (" : ", ") + name + ": " + std::to_string(n);
    if (!names.empty()) md << names << ")";
    md << " | " << t.judged << " |\n";
  }
}

std::string tally_line(const std::string& name, const QueryTally& t) {
  return name + " " + std::to_string(t.failing) + "/" + std::to_string(t.queries);
}

}  // namespace

bool DetectorFindings::within_bias() const {
  return !findings.empty() && std::all_of(biases.begin(), biases.end(), [](const std::string& b) { return !b.empty(); });
}

std::vector<DetectorFindings> judge_on_detectors(const ContactQuery& query, const CheckOptions& options) {
  std::vector<DetectorFindings> judged;
  const bool box_box = query.b.has_value();
  const OrientedBox a = OrientedBox::from(query.a.pose, query.a.half_extents);
  const JudgeTolerances tol = options.tolerances.at_scale(
      box_box ? query_scale(a, OrientedBox::from(query.b->pose, query.b->half_extents)) : query_scale(a, *query.plane));
  for (const DetectorInfo& d : detectors()) {
    if (d.box_plane_only && box_box) continue;
    const Manifold answer = d.detect(query, DetectOptions{});
    std::optional<Manifold> swapped;
    if (box_box && options.swap) swapped = d.detect(swapped_query(query), DetectOptions{});
    DetectorFindings found{std::string(d.name), judge_query(query, answer, swapped, options.tolerances), {}};
    for (const Finding& f : found.findings) {
      const KnownBias* bias = explaining_bias(d.name, {query, answer, swapped, f, tol});
      found.biases.emplace_back(bias ? bias->name : "");
    }
    judged.push_back(std::move(found));
  }
  return judged;
}

void judge_detectors(ConformRun& run) {
  run.detectors.clear();
  for (const FailedCase& c : run.result.failures) run.detectors.push_back(judge_on_detectors(c.query, run.options));
}

void run_conform(ConformRun& run, const Collider& collider) {
  const auto start = std::chrono::steady_clock::now();
  run.detector_tallies.clear();
  CheckOptions options = run.options;
  options.on_failure = [&run, &user = run.options.on_failure](const FailedCase& c) {
    tally_detectors(run.detector_tallies, judge_on_detectors(c.query, run.options));
    if (user) user(c);
  };
  run.result = check_collider(collider, options);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  judge_detectors(run);
  run.systematic = find_systematic(run.result, run.options.tolerances);
}

void write_conform_report(const ConformRun& run, const fs::path& dir) {
  const CheckResult& r = run.result;
  fs::create_directories(dir / "failures");
  for (const FailedCase& c : r.failures) {
    ContactQuery saved = c.query;
    saved.note = findings_text(c);
    saved.answers = {{kColliderAnswer, c.answer}};
    write_report_file(dir / failure_file(c), query_json(saved).dump(2) + '\n');
  }
  const nlohmann::json tallies = tallies_json(r);
  const nlohmann::json doc = {{"settings", settings_json(run)},
                              {"queries", r.queries},
                              {"touching", r.touching},
                              {"failing", r.failing},
                              {"within_gates", r.within_gates()},
                              {"failures_by_kind", counts_json(r)},
                              {"by_regime", tallies.at("by_regime")},
                              {"by_contact", tallies.at("by_contact")},
                              {"systematic", systematic_json(run.systematic)},
                              {"detectors_on_failures", detector_tallies_json(run.detector_tallies)},
                              {"saved", r.failures.size()},
                              {"failures", failures_json(run)},
                              {"seconds", run.seconds}};
  write_report_file(dir / kConformJson, doc.dump(2) + '\n');
  std::ostringstream md;
  write_md_heading(md, run);
  write_md_settings(md, run);
  write_md_systematic(md, run);
  write_md_counts(md, r);
  if (r.failing > 0) {
    write_md_tally_table(md, "Failures by regime", "regime", regime_rows(r));
    write_md_tally_table(md, "Failures by contact kind", "contact", contact_rows(r));
  }
  write_md_worst(md, run);
  write_md_detectors(md, run);
  write_report_file(dir / kConformMarkdown, md.str());
}

std::string conform_summary(const ConformRun& run) {
  const CheckResult& r = run.result;
  std::ostringstream s;
  s << run.collider << ": " << r.queries << " queries, " << r.failing << " failing\n";
  for (const FailureKind k : all_failure_kinds()) {
    if (r.count(k) == 0) continue;
    s << "  " << failure_name(k) << ": " << r.count(k) << " (allowed " << r.allowed(k) << ")\n";
  }
  if (r.failing > 0) {
    const char* separator = "  failing by regime: ";
    for (const auto& [name, t] : r.by_regime) {
      s << separator << tally_line(name, t);
      separator = ", ";
    }
    separator = "\n  failing by contact: ";
    for (const auto& [name, t] : contact_rows(r)) {
      s << separator << tally_line(name, *t);
      separator = ", ";
    }
    s << '\n';
  }
  for (const SystematicError& e : run.systematic) s << "  systematic: " << e.text << '\n';
  if (!run.detector_tallies.empty()) {
    const char* separator = "  also wrong on these queries: ";
    for (const DetectorTally& t : run.detector_tallies) {
      s << separator << t.detector << ' ' << t.wrong << " of " << t.judged;
      if (t.within_bias > 0) s << " (" << t.within_bias << " more within its known bias)";
      separator = ", ";
    }
    s << '\n';
  }
  s << (r.within_gates() ? "within the gates\n" : "NOT within the gates\n");
  return s.str();
}

}  // namespace boxpile
