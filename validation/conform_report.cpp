#include "boxpile/validation/conform_report.hpp"

#include <algorithm>
#include <optional>
#include <sstream>

#include "boxpile/validation/detectors.hpp"
#include "boxpile/validation/json_output.hpp"
#include "boxpile/validation/report_directory.hpp"

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

// "own right, ode right, bullet depth": each registered detector's verdict on a failing query.
std::string detectors_text(const std::vector<DetectorFindings>& judged) {
  std::string text;
  for (const DetectorFindings& d : judged) {
    std::string kinds;
    for (const Finding& f : d.findings) {
      if (!kinds.empty()) kinds += '+';
      kinds += failure_name(f.kind);
    }
    text += (text.empty() ? "" : ", ") + d.detector + " " + (kinds.empty() ? "right" : kinds);
  }
  return text;
}

nlohmann::json detectors_json(const std::vector<DetectorFindings>& judged) {
  nlohmann::json out = nlohmann::json::object();
  for (const DetectorFindings& d : judged) {
    nlohmann::json kinds = nlohmann::json::array();
    for (const Finding& f : d.findings) kinds.push_back({{"kind", failure_name(f.kind)}, {"why", f.why}});
    out[d.detector] = kinds;
  }
  return out;
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
          {"tolerances",
           {{"normal", t.normal}, {"depth", t.depth}, {"region", t.region}, {"unit", t.unit}, {"touching", t.touching}}}};
}

nlohmann::json counts_json(const CheckResult& r) {
  nlohmann::json kinds = nlohmann::json::object();
  for (const FailureKind k : all_failure_kinds()) {
    kinds[std::string(failure_name(k))] = {{"count", r.count(k)}, {"allowed", r.allowed(k)}};
  }
  return kinds;
}

nlohmann::json failures_json(const ConformRun& run) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k < run.result.failures.size(); ++k) {
    const FailedCase& c = run.result.failures[k];
    nlohmann::json entry = {
        {"name", c.name}, {"regime", c.regime}, {"file", failure_file(c)}, {"findings", findings_json(c)}};
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
     << " queries (" << r.touching << " with the boxes overlapping), " << r.failures.size() << " failing, in "
     << run.seconds << " s.\n\n";
}

void write_md_settings(std::ostream& md, const ConformRun& run) {
  md << "Fixed cases: " << (run.cases.empty() ? "none" : "`" + run.cases + "`") << "; random pairs: "
     << run.options.samples << " (seed " << run.options.seed << ", regimes";
  for (const Regime reg : run.options.regimes) md << ' ' << regime_name(reg);
  md << "); swapped queries: " << (run.options.swap ? "asked" : "not asked") << ".\n\n";
}

void write_md_counts(std::ostream& md, const CheckResult& r) {
  md << "## Failures by kind\n\n| kind | failing queries | allowed |\n|---|---:|---:|\n";
  for (const FailureKind k : all_failure_kinds()) {
    md << "| " << failure_name(k) << " | " << r.count(k) << " | " << r.allowed(k) << " |\n";
  }
  md << '\n';
}

void write_md_worst(std::ostream& md, const ConformRun& run) {
  const CheckResult& r = run.result;
  md << "## The worst of each kind\n\n";
  bool any = false;
  for (const FailureKind k : all_failure_kinds()) {
    const FailedCase* c = r.worst(k);
    if (!c) continue;
    any = true;
    md << "- **" << failure_name(k) << "**: `" << failure_file(*c) << "` (" << c->regime << "): " << findings_text(*c);
    const auto index = static_cast<std::size_t>(c - r.failures.data());
    if (index < run.detectors.size()) md << ". The detectors on it: " << detectors_text(run.detectors[index]);
    md << "\n";
  }
  if (!any) md << "None: every answer was right.\n";
  md << "\nEach failing query is saved under `failures/` with the collider's answer; "
        "`boxpile contacts failures/NAME.json` shows it beside ours, ODE's and Bullet's.\n";
}

// How many of the failing queries each registered detector gets wrong too, in table order: a
// collider's failure where the references fail as well is a hard case rather than a plain mistake.
std::vector<std::pair<std::string, int>> detectors_wrong(const ConformRun& run) {
  std::vector<std::pair<std::string, int>> wrong;
  for (const std::vector<DetectorFindings>& judged : run.detectors) {
    for (const DetectorFindings& d : judged) {
      auto it = std::find_if(wrong.begin(), wrong.end(), [&](const auto& w) { return w.first == d.detector; });
      if (it == wrong.end()) it = wrong.insert(wrong.end(), {d.detector, 0});
      if (!d.findings.empty()) ++it->second;
    }
  }
  return wrong;
}

void write_md_detectors(std::ostream& md, const ConformRun& run) {
  if (run.detectors.empty()) return;
  const std::vector<std::pair<std::string, int>> wrong = detectors_wrong(run);
  md << "\n## The registered detectors on the failing queries\n\n"
        "Each failing query put to every registered detector and judged the same way.\n\n"
        "| detector | also wrong |\n|---|---:|\n";
  for (const auto& [detector, n] : wrong) md << "| " << detector << " | " << n << " of " << run.detectors.size() << " |\n";
}

}  // namespace

void judge_detectors(ConformRun& run) {
  run.detectors.clear();
  for (const FailedCase& c : run.result.failures) {
    std::vector<DetectorFindings>& judged = run.detectors.emplace_back();
    const bool box_box = c.query.b.has_value();
    for (const DetectorInfo& d : detectors()) {
      if (d.box_plane_only && box_box) continue;
      const Manifold answer = d.detect(c.query, DetectOptions{});
      std::optional<Manifold> swapped;
      if (box_box && run.options.swap) swapped = d.detect(swapped_query(c.query), DetectOptions{});
      judged.push_back({std::string(d.name), judge_query(c.query, answer, swapped, run.options.tolerances)});
    }
  }
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
  const nlohmann::json doc = {{"settings", settings_json(run)},
                              {"queries", r.queries},
                              {"touching", r.touching},
                              {"within_gates", r.within_gates()},
                              {"failures_by_kind", counts_json(r)},
                              {"failures", failures_json(run)},
                              {"seconds", run.seconds}};
  write_report_file(dir / kConformJson, doc.dump(2) + '\n');
  std::ostringstream md;
  write_md_heading(md, run);
  write_md_settings(md, run);
  write_md_counts(md, r);
  write_md_worst(md, run);
  write_md_detectors(md, run);
  write_report_file(dir / kConformMarkdown, md.str());
}

std::string conform_summary(const ConformRun& run) {
  const CheckResult& r = run.result;
  std::ostringstream s;
  s << run.collider << ": " << r.queries << " queries, " << r.failures.size() << " failing\n";
  for (const FailureKind k : all_failure_kinds()) {
    if (r.count(k) == 0) continue;
    s << "  " << failure_name(k) << ": " << r.count(k) << " (allowed " << r.allowed(k) << ")\n";
  }
  if (!run.detectors.empty()) {
    const char* separator = "  also wrong on these queries: ";
    for (const auto& [detector, n] : detectors_wrong(run)) {
      s << separator << detector << ' ' << n;
      separator = ", ";
    }
    s << '\n';
  }
  s << (r.within_gates() ? "within the gates\n" : "NOT within the gates\n");
  return s.str();
}

}  // namespace boxpile
