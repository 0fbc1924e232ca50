#include "boxpile/validation/conform_report.hpp"

#include <sstream>

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

nlohmann::json failures_json(const CheckResult& r) {
  nlohmann::json out = nlohmann::json::array();
  for (const FailedCase& c : r.failures) {
    out.push_back({{"name", c.name}, {"regime", c.regime}, {"file", failure_file(c)}, {"findings", findings_json(c)}});
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

void write_md_worst(std::ostream& md, const CheckResult& r) {
  md << "## The worst of each kind\n\n";
  bool any = false;
  for (const FailureKind k : all_failure_kinds()) {
    const FailedCase* c = r.worst(k);
    if (!c) continue;
    any = true;
    md << "- **" << failure_name(k) << "**: `" << failure_file(*c) << "` (" << c->regime << "): " << findings_text(*c)
       << "\n";
  }
  if (!any) md << "None: every answer was right.\n";
  md << "\nEach failing query is saved under `failures/` with the collider's answer; "
        "`boxpile contacts failures/NAME.json` shows it beside ours, ODE's and Bullet's.\n";
}

}  // namespace

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
                              {"failures", failures_json(r)},
                              {"seconds", run.seconds}};
  write_report_file(dir / "conform.json", doc.dump(2) + '\n');
  std::ostringstream md;
  write_md_heading(md, run);
  write_md_settings(md, run);
  write_md_counts(md, r);
  write_md_worst(md, r);
  write_report_file(dir / "conform.md", md.str());
}

std::string conform_summary(const ConformRun& run) {
  const CheckResult& r = run.result;
  std::ostringstream s;
  s << run.collider << ": " << r.queries << " queries, " << r.failures.size() << " failing\n";
  for (const FailureKind k : all_failure_kinds()) {
    if (r.count(k) == 0) continue;
    s << "  " << failure_name(k) << ": " << r.count(k) << " (allowed " << r.allowed(k) << ")\n";
  }
  s << (r.within_gates() ? "within the gates\n" : "NOT within the gates\n");
  return s.str();
}

}  // namespace boxpile
