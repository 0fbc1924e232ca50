#include "boxpile/validation/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/detectors.hpp"
#include "boxpile/validation/format_number.hpp"
#include "boxpile/validation/json_output.hpp"
#include "boxpile/validation/replay_data.hpp"
#include "boxpile/validation/replay_page.hpp"
#include "boxpile/validation/report_directory.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Bodies listed per pair of engines under "largest disagreements".
constexpr std::size_t kBodiesListed = 3;

std::string fmt(double x, const char* format = "%.4g") {
  return std::isnan(x) ? "nan" : format_number(x, format);
}

std::string seconds(double t) { return fmt(t, "%.3f") + " s"; }

std::string optional_seconds(const std::optional<double>& t) { return t ? seconds(*t) : std::string("never"); }

json optional_number(const std::optional<double>& x) { return x ? json(*x) : json(nullptr); }

std::string body_name(const Scene& scene, int index) {
  return index == kGround ? std::string("ground") : scene.bodies[static_cast<std::size_t>(index)].name;
}

json diff_json(const ContactDiff& d) {
  return {{"normal_angle", optional_number(d.normal_angle)},
          {"depth_difference", optional_number(d.depth_difference)},
          {"point_distance", optional_number(d.hull_distance)},
          {"hausdorff", optional_number(d.hausdorff)}};
}

// The number of contact points each recorded frame's contact set holds.
json contact_counts(const FrameSeries& frames) {
  json counts = json::array();
  for (const std::vector<BodyContact>& c : frames.contacts) counts.push_back(c.size());
  return counts;
}

json engine_json(const CompareResult& r, const EngineRun& run, const Baseline& baseline) {
  const Scene& scene = r.scene;
  json stacks = json::array();
  for (const StackReport& s : run.stacks) {
    stacks.push_back({{"bodies", s.bodies}, {"height", s.height}, {"ideal", optional_number(s.ideal)},
                      {"error", optional_number(s.error)}});
  }
  json events = json::array();
  for (const ImpactEvent& e : run.events) {
    json ev = {{"t", e.t}, {"body_a", body_name(scene, e.body_a)}, {"body_b", body_name(scene, e.body_b)},
               {"approach_speed", e.approach_speed}, {"kind", impact_kind_name(impact_kind(e))}};
    if (e.impulse) ev["impulse"] = *e.impulse;
    events.push_back(std::move(ev));
  }
  json wires = json::array();
  for (const WireReport& w : run.wires) {
    wires.push_back({{"body", w.body}, {"max_off", w.max_off}, {"max_past_end", w.max_past_end},
                     {"final_along", w.final_along}, {"length", w.length}});
  }
  const RunDifference& d = baseline.divergence;
  return {{"settings", run.settings},
          {"final", {{"t", run.final_t}, {"bodies", bodies_json(run.final_states)}}},
          {"stacks", stacks},
          {"us_per_step", run.us_per_step},
          {"wall_seconds", run.wall_seconds},
          {"steps", run.steps},
          {"max_penetration", run.deepest.depth},
          {"max_penetration_at",
           {{"t", run.deepest_t},
            {"body_a", run.deepest.body_a >= 0 ? json(body_name(scene, run.deepest.body_a)) : json(nullptr)},
            {"body_b", run.deepest.body_a >= 0 ? json(body_name(scene, run.deepest.body_b)) : json(nullptr)}}},
          {"energy",
           {{"initial", run.energy_initial}, {"final", run.energy_final}, {"max", run.energy_max},
            {"max_t", run.energy_max_t}}},
          {"levitation", {{"max", run.levitation_max}, {"final", run.levitation_final}}},
          {"events", events},
          {"wires", wires},
          {"finite", run.finite},
          {"failure", run.failure ? nlohmann::json(*run.failure) : nlohmann::json(nullptr)},
          {"engine_messages", run.engine_messages},
          {"baseline",
           {{"perturbation", r.settings.perturbation},
            {"largest_position_difference", d.largest_position},
            {"largest_position_body", d.largest_position_body},
            {"largest_orientation_difference", d.largest_orientation},
            {"position_passes", optional_number(d.position_passes)},
            {"orientation_passes", optional_number(d.orientation_passes)},
            {"growth_rate", baseline.growth_rate},
            {"max_position", d.max_position}}},
          {"series",
           {{"t", run.recording.frames.t},
            {"energy", run.recording.frames.energy},
            {"penetration", run.recording.frames.penetration},
            {"levitation", run.recording.frames.levitation},
            {"stack_height", run.recording.frames.stack_height},
            {"contacts", contact_counts(run.recording.frames)}}}};
}

json pair_json(const CompareResult& r, const PairComparison& p) {
  const RunDifference& d = p.difference;
  json bodies = json::array();
  for (const BodyDifference& b : d.bodies) {
    bodies.push_back({{"name", b.name},
                      {"position", b.position},
                      {"orientation", b.orientation},
                      {"max_position", b.max_position},
                      {"max_orientation", b.max_orientation},
                      {"position_passes", optional_number(b.position_passes)},
                      {"orientation_passes", optional_number(b.orientation_passes)}});
  }
  return {{"engines", {d.a, d.b}},
          {"position_threshold", r.settings.position_threshold},
          {"orientation_threshold", r.settings.orientation_threshold},
          {"largest_position_difference", d.largest_position},
          {"largest_position_body", d.largest_position_body},
          {"largest_orientation_difference", d.largest_orientation},
          {"largest_orientation_body", d.largest_orientation_body},
          {"position_passes", optional_number(d.position_passes)},
          {"orientation_passes", optional_number(d.orientation_passes)},
          {"chaos_time", optional_number(p.chaos_time)},
          {"verdict", p.verdict},
          {"unstable_engine", p.unstable_engine.empty() ? json(nullptr) : json(p.unstable_engine)},
          {"instability", p.instability.empty() ? json(nullptr) : json(p.instability)},
          {"starts_compared", p.starts_compared ? json(*p.starts_compared) : json(nullptr)},
          {"starts_agreeing", p.starts_agreeing ? json(*p.starts_agreeing) : json(nullptr)},
          {"beyond_chaos", p.beyond_chaos.empty() ? json(nullptr) : json(p.beyond_chaos)},
          {"t", d.t},
          {"max_position", d.max_position},
          {"bodies", bodies}};
}

json contacts_json(const CompareResult& r, const ContactFrameCheck& c) {
  json worst = json::array();
  for (const ContactDisagreement& w : c.worst) {
    const ContactPairCheck& p = w.pair;
    json entry = {{"metric", w.metric},
                  {"reference", w.reference},
                  {"value", w.value},
                  {"body_a", body_name(r.scene, p.body_a)},
                  {"shape_a", p.shape_a},
                  {"body_b", body_name(r.scene, p.body_b)},
                  {"shape_b", p.shape_b}};
    // "points": every detector's count; then each other detector's diff against ours by its name.
    json points = json::object();
    for (const DetectorCheck& d : p.detectors) points[d.detector] = d.points;
    entry["points"] = points;
    for (const DetectorCheck& d : p.detectors) {
      if (d.detector != kOwnDetector) entry[d.detector] = diff_json(d.diff);
    }
    worst.push_back(std::move(entry));
  }
  return {{"engine", c.engine}, {"why", c.why},     {"frame", c.frame},
          {"t", c.t},           {"pairs", c.pairs}, {"count_mismatches", c.count_mismatches},
          {"worst", worst}};
}

// Value of a series at time t, linear between recorded frames.
std::string dt_text(double dt) {
  const double per_second = 1.0 / dt;
  const double rounded = std::round(per_second);
  return fmt(dt, "%.6g") + " s" + (std::abs(per_second - rounded) < 1e-6 ? " (1/" + fmt(rounded, "%.0f") + ")" : "");
}

// Markdown and terminal tables share the rows: a label and one cell per engine.
struct Row {
  std::string label;
  std::vector<std::string> cells;
};

std::vector<Row> engine_rows(const CompareResult& r) {
  std::vector<Row> rows;
  auto add = [&](std::string label, auto cell) {
    Row row{std::move(label), {}};
    for (std::size_t e = 0; e < r.runs.size(); ++e) row.cells.push_back(cell(r.runs[e], r.baselines[e]));
    rows.push_back(std::move(row));
  };
  add("us per step", [](const EngineRun& run, const Baseline&) { return fmt(run.us_per_step, "%.1f"); });
  add("energy at start (J)", [](const EngineRun& run, const Baseline&) { return fmt(run.energy_initial, "%.2f"); });
  add("energy at end (J)", [](const EngineRun& run, const Baseline&) { return fmt(run.energy_final, "%.2f"); });
  add("largest energy (J)", [](const EngineRun& run, const Baseline&) {
    return fmt(run.energy_max, "%.2f") + " at " + seconds(run.energy_max_t);
  });
  add("deepest penetration (m)", [&](const EngineRun& run, const Baseline&) {
    if (run.deepest.body_a < 0) return std::string("0");
    return fmt(run.deepest.depth, "%.2e") + " at " + seconds(run.deepest_t) + " (" +
           body_name(r.scene, run.deepest.body_a) + "/" + body_name(r.scene, run.deepest.body_b) + ")";
  });
  add("largest levitation (m)", [](const EngineRun& run, const Baseline&) { return fmt(run.levitation_max, "%.2e"); });
  add("impacts", [](const EngineRun& run, const Baseline&) { return std::to_string(run.events.size()); });
  add("stacks at the end", [](const EngineRun& run, const Baseline&) { return std::to_string(run.stacks.size()); });
  add("tallest stack (m)", [](const EngineRun& run, const Baseline&) {
    const auto lower = [](const StackReport& a, const StackReport& b) { return a.height < b.height; };
    const auto tallest = std::max_element(run.stacks.begin(), run.stacks.end(), lower);
    if (tallest == run.stacks.end()) return std::string("-");
    std::string s = fmt(tallest->height, "%.5f");
    if (tallest->error) s += " (error " + fmt(*tallest->error, "%.2e") + ")";
    return s;
  });
  if (!r.runs.empty() && !r.runs.front().wires.empty()) {
    add("anchor off the wire (m)", [](const EngineRun& run, const Baseline&) {
      double worst = 0.0;
      for (const WireReport& w : run.wires) worst = std::max(worst, w.max_off);
      return fmt(worst, "%.2e");
    });
    add("anchor past an end (m)", [](const EngineRun& run, const Baseline&) {
      double worst = 0.0;
      for (const WireReport& w : run.wires) worst = std::max(worst, w.max_past_end);
      return fmt(worst, "%.2e");
    });
  }
  add("self-divergence passes " + fmt(r.settings.position_threshold) + " m",
      [](const EngineRun&, const Baseline& b) { return optional_seconds(b.divergence.position_passes); });
  add("self-divergence growth (1/s)", [](const EngineRun&, const Baseline& b) { return fmt(b.growth_rate, "%.3g"); });
  return rows;
}

std::string markdown_table(const std::vector<std::string>& header, const std::vector<Row>& rows) {
  std::ostringstream os;
  os << "|";
  for (const std::string& h : header) os << ' ' << h << " |";
  os << "\n|";
  for (std::size_t i = 0; i < header.size(); ++i) os << (i == 0 ? "---|" : "---:|");
  os << '\n';
  for (const Row& row : rows) {
    os << "| " << row.label << " |";
    for (const std::string& c : row.cells) os << ' ' << c << " |";
    os << '\n';
  }
  return os.str();
}

std::string plain_table(const std::vector<std::string>& header, const std::vector<Row>& rows) {
  std::vector<std::size_t> width(header.size(), 0);
  for (std::size_t i = 0; i < header.size(); ++i) width[i] = header[i].size();
  for (const Row& row : rows) {
    width[0] = std::max(width[0], row.label.size());
    for (std::size_t i = 0; i < row.cells.size(); ++i) width[i + 1] = std::max(width[i + 1], row.cells[i].size());
  }
  std::ostringstream os;
  auto line = [&](const std::string& first, const std::vector<std::string>& rest) {
    os << "  " << first << std::string(width[0] - first.size(), ' ');
    for (std::size_t i = 0; i < rest.size(); ++i) {
      os << "  " << std::string(width[i + 1] - rest[i].size(), ' ') << rest[i];
    }
    os << '\n';
  };
  line(header[0], std::vector<std::string>(header.begin() + 1, header.end()));
  for (const Row& row : rows) line(row.label, row.cells);
  return os.str();
}

std::vector<std::string> engine_header(const CompareResult& r, const std::string& first) {
  std::vector<std::string> header{first};
  for (const EngineRun& run : r.runs) header.push_back(run.engine);
  return header;
}

std::string pair_line(const PairComparison& p, double threshold) {
  const RunDifference& d = p.difference;
  std::string s = d.a + " vs " + d.b + ": largest position difference " + fmt(d.largest_position, "%.3g") + " m (" +
                  d.largest_position_body + "), ";
  s += d.position_passes ? "passes " + fmt(threshold) + " m at " + seconds(*d.position_passes)
                         : "never passes " + fmt(threshold) + " m";
  s += p.chaos_time ? "; engines diverge from themselves by " + seconds(*p.chaos_time)
                    : std::string("; neither diverges from itself that far");
  s += "; verdict: " + p.verdict;
  if (p.verdict == "unstable") s += " (" + p.unstable_engine + ": " + p.instability + ")";
  if (!p.beyond_chaos.empty()) s += " (" + p.beyond_chaos + ")";
  if (p.starts_compared) s += "; agree on " + std::to_string(*p.starts_agreeing) + " of " + std::to_string(*p.starts_compared) + " perturbed starts";
  return s;
}

// An impact kind's mark on the energy plot and its entry in the key.
PlotSeries::Style impact_style(ImpactKind k) {
  return k == ImpactKind::Ground ? PlotSeries::Style::Triangles : PlotSeries::Style::Points;
}
std::string impact_kind_title(ImpactKind k) {
  return k == ImpactKind::Ground ? "impact with the ground" : "impact between bodies";
}

std::string verdict_text(const PairComparison& p) {
  const std::string& verdict = p.verdict;
  const std::string starts = p.starts_compared ? "; agree on " + std::to_string(*p.starts_agreeing) + " of " +
                                                     std::to_string(*p.starts_compared) + " perturbed starts"
                                               : std::string();
  if (verdict == "unstable") return p.unstable_engine + " is unstable (" + p.instability + "), the other is not" + starts;
  if (verdict == "agree") return "agree within the threshold" + starts;
  if (verdict == "chaos") return "differ no sooner than chaos explains" + starts;
  if (!p.beyond_chaos.empty()) return "differ no sooner than chaos would explain, but " + p.beyond_chaos + starts;
  return "differ before chaos explains it" + starts;
}

}  // namespace

namespace {

json findings_json(const std::vector<CompareFinding>& findings) {
  json out = json::array();
  for (const CompareFinding& f : findings)
    out.push_back({{"engine", f.engine}, {"kind", f.kind}, {"what", f.what}, {"t", optional_number(f.t)}});
  return out;
}

// "bullet (penetration, at 0.500 s): goes 1.62 m deep ...": a finding other than a check's.
std::string finding_line(const CompareFinding& f) {
  return f.engine + " (" + f.kind + (f.t ? ", at " + seconds(*f.t) : std::string()) + "): " + f.what;
}

}  // namespace

json report_json(const CompareResult& r) {
  json engines = json::object();
  for (std::size_t e = 0; e < r.runs.size(); ++e) engines[r.runs[e].engine] = engine_json(r, r.runs[e], r.baselines[e]);
  json pairs = json::array();
  for (const PairComparison& p : r.pairs) pairs.push_back(pair_json(r, p));
  json contacts = json::array();
  for (const ContactFrameCheck& c : r.contacts) contacts.push_back(contacts_json(r, c));
  json start_stacks = json::array();
  for (const Stack& s : r.start_stacks) {
    json names = json::array();
    for (int i : s.bodies) names.push_back(body_name(r.scene, i));
    start_stacks.push_back({{"bodies", names}, {"height", s.height}});
  }
  return {{"scene", r.scene.name},
          {"scene_file", r.scene.source},
          {"dt", r.scene.time.dt},
          {"duration", r.scene.time.duration},
          {"steps", r.steps},
          {"settings",
           {{"perturbation", r.settings.perturbation},
            {"frame_rate", r.settings.frame_rate},
            {"position_threshold", r.settings.position_threshold},
            {"orientation_threshold", r.settings.orientation_threshold},
            {"touch_tolerance", r.settings.touch_tolerance}}},
          {"start_stacks", start_stacks},
          {"engines", engines},
          {"pairs", pairs},
          {"contacts", contacts},
          {"outcomes", r.outcomes ? outcomes_json(*r.outcomes) : json(nullptr)},
          {"findings", findings_json(r.findings)}};
}

std::vector<PlotSpec> report_plots(const CompareResult& r) {
  using Style = PlotSeries::Style;
  std::vector<PlotSpec> plots;

  PlotSpec energy{"energy",
                  "Energy: total (solid, impacts marked by kind), translational (dashed), rotational (dotted), "
                  "potential (dash-dot)",
                  "t (s)", "energy (J)", false, 1e-12, std::nullopt, "", {}};
  // The parts and the impacts are drawn alike for every engine: the key names each style once, in
  // grey, beside one entry per engine (its total).
  const std::string key_grey = "#555555";
  energy.key = {{"translational", {}, {}, Style::Dashed, key_grey},
                {"rotational", {}, {}, Style::Dotted, key_grey},
                {"potential", {}, {}, Style::DashDot, key_grey},
                {impact_kind_title(ImpactKind::Ground), {}, {}, impact_style(ImpactKind::Ground), key_grey},
                {impact_kind_title(ImpactKind::Bodies), {}, {}, impact_style(ImpactKind::Bodies), key_grey}};
  PlotSpec penetration{"penetration",
                       "Deepest penetration between any two bodies or a body and the ground, the most of each "
                       "interval between frames",
                       "t (s)", "depth (m)", false, 1e-12, std::nullopt, "", {}};
  PlotSpec stacks{"stack_height", "Height of the tallest stack", "t (s)", "height (m)", false, 1e-12, std::nullopt,
                  "", {}};
  PlotSpec difference{"position_difference",
                      "Largest body position difference: between engines (solid), from a " +
                          fmt(r.settings.perturbation) + " m perturbed start (dashed)",
                      "t (s)", "difference (m)", true, 1e-12, r.settings.position_threshold, "threshold", {}};
  double tallest_start = 0.0;
  for (const Stack& s : r.start_stacks) tallest_start = std::max(tallest_start, s.height);
  if (tallest_start > 0.0) {
    stacks.hline = tallest_start;
    stacks.hline_title = "at the start";
  }

  for (std::size_t e = 0; e < r.runs.size(); ++e) {
    const EngineRun& run = r.runs[e];
    const std::string color = engine_colour(run.engine);
    energy.series.push_back({run.engine, run.recording.frames.t, run.recording.frames.energy, Style::Line, color});
    // Each impact on the engine's total at its time, marked by its kind.
    for (const ImpactKind kind : {ImpactKind::Ground, ImpactKind::Bodies}) {
      PlotSeries impacts{run.engine + " " + impact_kind_title(kind), {}, {}, impact_style(kind), color};
      impacts.in_key = false;
      for (const ImpactEvent& ev : run.events) {
        if (impact_kind(ev) != kind) continue;
        impacts.x.push_back(ev.t);
        impacts.y.push_back(value_at_time(run.recording.frames.t, run.recording.frames.energy, ev.t));
      }
      energy.series.push_back(std::move(impacts));
    }
    const FrameSeries& f = run.recording.frames;
    PlotSeries translational{run.engine + " translational", f.t, {}, Style::Dashed, color},
        rotational{run.engine + " rotational", f.t, f.rotational, Style::Dotted, color},
        potential{run.engine + " potential", f.t, {}, Style::DashDot, color};
    translational.in_key = rotational.in_key = potential.in_key = false;
    for (std::size_t k = 0; k < f.t.size() && k < f.kinetic.size() && k < f.rotational.size() && k < f.energy.size(); ++k) {
      translational.y.push_back(f.kinetic[k] - f.rotational[k]);
      potential.y.push_back(f.energy[k] - f.kinetic[k]);
    }
    energy.series.push_back(std::move(translational));
    energy.series.push_back(std::move(rotational));
    energy.series.push_back(std::move(potential));
    penetration.series.push_back({run.engine, f.t,
                                  run.interval_penetration.size() == f.t.size() ? run.interval_penetration : f.penetration,
                                  Style::Line, color});
    stacks.series.push_back({run.engine, run.recording.frames.t, run.recording.frames.stack_height, Style::Line, color});
  }
  for (std::size_t p = 0; p < r.pairs.size(); ++p) {
    const RunDifference& d = r.pairs[p].difference;
    difference.series.push_back({d.a + " vs " + d.b, d.t, d.max_position, Style::Line, plot_colour(static_cast<int>(p))});
  }
  for (std::size_t e = 0; e < r.baselines.size(); ++e) {
    const RunDifference& d = r.baselines[e].divergence;
    difference.series.push_back({d.b, d.t, d.max_position, Style::Dashed, engine_colour(r.runs[e].engine)});
  }
  plots.push_back(std::move(energy));
  plots.push_back(std::move(penetration));
  plots.push_back(std::move(stacks));
  plots.push_back(std::move(difference));
  return plots;
}

namespace {

// --- report.md, one section per writer ---------------------------------------------------------

void write_md_run(std::ostream& md, const CompareResult& r) {
  const Scene& s = r.scene;
  md << "# boxpile compare: " << s.name << "\n\n";
  if (!s.note.empty()) md << s.note << "\n\n";
  md << "## What was run\n\n"
     << "- scene: `" << s.source << "` (" << s.bodies.size() << " bodies)\n"
     << "- engines: ";
  for (std::size_t e = 0; e < r.runs.size(); ++e) md << (e ? ", " : "") << r.runs[e].engine;
  md << "\n- time step " << dt_text(s.time.dt) << ", " << fmt(s.time.duration) << " s simulated (" << r.steps
     << " steps), frames recorded at " << fmt(r.settings.frame_rate) << " per second\n"
     << "- baseline: each engine run a second time with every free body moved by " << fmt(r.settings.perturbation)
     << " m at the start\n"
     << "- thresholds: position " << fmt(r.settings.position_threshold) << " m, orientation "
     << fmt(r.settings.orientation_threshold) << " rad; bodies within " << fmt(r.settings.touch_tolerance)
     << " m touch\n\n";
  for (const EngineRun& run : r.runs) {
    if (run.failure) md << "**" << run.engine << " failed: " << *run.failure << "; its run stops there.**\n\n";
    if (run.engine_messages > 0) md << run.engine << " printed " << run.engine_messages << " solver message(s).\n\n";
  }

  md << "Watch the runs side by side in [replay.html](replay.html) (open it in a browser; docs/viewer.md "
        "describes it).\n\n";
}

void write_md_findings(std::ostream& md, const CompareResult& r) {
  md << "## Findings\n\n";
  bool any = false;
  for (const CompareFinding& f : r.findings) {
    if (f.kind == "check") continue;
    md << "- **" << f.engine << "** (" << f.kind << (f.t ? ", at " + seconds(*f.t) : std::string()) << "): " << f.what
       << '\n';
    any = true;
  }
  if (!any) md << "- nothing stands out: no engine alone fails a check, leaves the others first, parts from their energy or "
                  "penetrates far past them\n";
  md << "\nThe scene's checks (docs/scene-format.md, \"Checks\"), measured alike in every engine:\n\n";
  for (const EngineRun& run : r.runs) {
    md << "- " << run.engine << ":";
    bool first = true;
    for (const CompareFinding& f : r.findings) {
      if (f.kind != "check" || f.engine != run.engine) continue;
      md << (first ? " " : "; ") << f.what;
      first = false;
    }
    md << (first ? " none\n" : "\n");
  }
  md << "\ndocs/compare.md, \"Findings\", gives each rule and its limits.\n\n";
}

void write_md_engines(std::ostream& md, const CompareResult& r) {
  md << "## Per engine\n\n" << markdown_table(engine_header(r, "metric"), engine_rows(r)) << '\n';
  md << "Energy is measured the same way for every engine from its body states (the scene's bodies "
        "only). Impacts are pairs approaching faster than resting contact explains, found the same way "
        "for every engine from the contact set of each step and the velocities before it.\n\n";
}

void write_md_stacks(std::ostream& md, const CompareResult& r) {
  md << "### Stacks at the end\n\n";
  for (const EngineRun& run : r.runs) {
    md << "- " << run.engine << ": ";
    if (run.stacks.empty()) md << "none";
    for (std::size_t k = 0; k < run.stacks.size(); ++k) {
      const StackReport& st = run.stacks[k];
      md << (k ? "; " : "") << st.bodies.size() << (st.bodies.size() == 1 ? " body, " : " bodies, ")
         << fmt(st.height, "%.5f") << " m";
      if (st.ideal) md << " (ideal " << fmt(*st.ideal, "%.5f") << ", error " << fmt(*st.error, "%.2e") << ")";
    }
    md << '\n';
  }
  md << '\n';
}

void write_md_pairs(std::ostream& md, const CompareResult& r) {
  if (r.pairs.empty()) return;
  md << "## Between engines\n\n"
     << "| engines | largest position difference | largest orientation difference | passes "
     << fmt(r.settings.position_threshold) << " m | engines diverge from themselves | verdict |\n"
     << "|---|---:|---:|---:|---:|---|\n";
  for (const PairComparison& p : r.pairs) {
    const RunDifference& d = p.difference;
    md << "| " << d.a << " vs " << d.b << " | " << fmt(d.largest_position, "%.3g") << " m ("
       << d.largest_position_body
       << ") | " << fmt(d.largest_orientation, "%.3g") << " rad (" << d.largest_orientation_body << ") | "
       << optional_seconds(d.position_passes) << " | " << optional_seconds(p.chaos_time) << " | "
       << verdict_text(p) << " |\n";
  }
  md << "\nA pair *differs* when its position difference passes the threshold earlier than half the time "
        "either engine takes to pass it against its own perturbed run; later than that, chaos "
        "explains it.\n\n";
}

void write_md_outcomes(std::ostream& md, const CompareResult& r) {
  if (r.outcomes) md << outcomes_markdown(*r.outcomes);
}

void write_md_plots(std::ostream& md, const std::vector<std::string>& plots) {
  if (plots.empty()) return;
  md << "## Plots\n\n";
  for (const std::string& p : plots) md << "![" << p << "](" << p << ".svg)\n\n";
  md << "Each plot's data (`NAME.dat`) and gnuplot script (`NAME.gp`) are beside it.\n\n";
}

void write_md_largest(std::ostream& md, const CompareResult& r) {
  md << "## Largest disagreements\n\n";
  for (const PairComparison& p : r.pairs) {
    std::vector<const BodyDifference*> bodies;
    for (const BodyDifference& b : p.difference.bodies) bodies.push_back(&b);
    std::sort(bodies.begin(), bodies.end(),
              [](const BodyDifference* a, const BodyDifference* b) { return a->max_position > b->max_position; });
    md << "- " << p.difference.a << " vs " << p.difference.b << ": ";
    for (std::size_t k = 0; k < std::min(kBodiesListed, bodies.size()); ++k) {
      md << (k ? ", " : "") << bodies[k]->name << " " << fmt(bodies[k]->max_position, "%.3g") << " m (passes at "
         << optional_seconds(bodies[k]->position_passes) << ")";
    }
    md << '\n';
  }
  md << '\n';
}

void write_md_contact_check(std::ostream& md, const Scene& s, const ContactFrameCheck& c) {
  md << "### Contact sets at t = " << seconds(c.t) << " (" << c.why << ", " << c.engine << "'s poses)\n\n"
     << c.pairs << " touching pairs, each through our detector, ODE's and Bullet's; " << c.count_mismatches
     << " give different point counts.\n\n";
  if (c.worst.empty()) {
    md << "No disagreement above rounding (1e-9) in normals, deepest depths or contact regions.\n\n";
    return;
  }
  const std::vector<DetectorCheck>& shown = c.worst.front().pair.detectors;
  md << "| largest | against | value | pair | points";
  for (std::size_t k = 0; k < shown.size(); ++k) md << (k ? " / " : " ") << shown[k].detector;
  md << " |\n|---|---|---:|---|---|\n";
  for (const ContactDisagreement& w : c.worst) {
    const ContactPairCheck& pc = w.pair;
    const bool angle = w.metric == "normal_angle";
    md << "| " << w.metric << " | " << w.reference << " | " << fmt(w.value, "%.3g") << (angle ? " rad" : " m")
       << " | "
       << body_name(s, pc.body_a) << "[" << pc.shape_a << "] / " << body_name(s, pc.body_b);
    if (pc.body_b != kGround) md << "[" << pc.shape_b << "]";
    md << " |";
    for (std::size_t k = 0; k < pc.detectors.size(); ++k) md << (k ? " / " : " ") << pc.detectors[k].points;
    md << " |\n";
  }
  md << '\n';
}

void write_md_contacts(std::ostream& md, const CompareResult& r) {
  if (!r.contacts.empty()) {
    md << "Contact sets below: on one engine's poses, every pair of boxes within "
       << fmt(r.settings.touch_tolerance) << " m (and every box near the ground) through all three detectors, "
       << "each reference against ours: `normal_angle` between the mean normals, `depth_difference` of the "
       << "deepest points, `point_distance` how far the smaller point set lies outside the contact region of "
       << "the larger (0 when one lies within the other's). The largest of each kind is listed.\n\n";
  }
  for (const ContactFrameCheck& c : r.contacts) write_md_contact_check(md, r.scene, c);
}

void write_md_notes(std::ostream& md, const std::vector<std::string>& notes) {
  if (!notes.empty()) {
    md << "## Notes\n\n";
    for (const std::string& n : notes) md << "- " << n << '\n';
    md << '\n';
  }
  md << "How to read this report: docs/compare.md in the boxpile sources. The same figures, and the "
        "series behind the plots, are in report.json.\n";
}

}  // namespace

std::string report_markdown(const CompareResult& r, const std::vector<std::string>& plots,
                            const std::vector<std::string>& notes) {
  std::ostringstream md;
  write_md_run(md, r);
  write_md_findings(md, r);
  write_md_engines(md, r);
  write_md_stacks(md, r);
  write_md_pairs(md, r);
  write_md_outcomes(md, r);
  write_md_plots(md, plots);
  write_md_largest(md, r);
  write_md_contacts(md, r);
  write_md_notes(md, notes);
  return md.str();
}

std::string summary_table(const CompareResult& r) {
  std::ostringstream os;
  os << "scene " << r.scene.name << ": " << r.steps << " steps of " << dt_text(r.scene.time.dt) << '\n'
     << plain_table(engine_header(r, ""), engine_rows(r));
  for (const PairComparison& p : r.pairs) os << "  " << pair_line(p, r.settings.position_threshold) << '\n';
  for (const CompareFinding& f : r.findings)
    if (f.kind != "check") os << "  finding: " << finding_line(f) << '\n';
  for (const EngineRun& run : r.runs) {
    const auto failed = std::count_if(run.checks.begin(), run.checks.end(), [](const SceneCheckResult& c) { return !c.passed; });
    if (failed > 0) os << "  " << run.engine << " fails " << failed << " of the scene's " << run.checks.size() << " checks\n";
  }
  if (r.outcomes) {
    os << "outcomes over " << r.outcomes->settings.starts << " perturbed starts (" << fmt(r.outcomes->settings.perturbation)
       << " m):\n";
    for (const OutcomePair& p : r.outcomes->pairs) os << "  " << p.a << " vs " << p.b << ": " << p.verdict() << '\n';
  }
  return os.str();
}

void write_replay(const CompareResult& r, const json& report, const fs::path& dir, std::vector<std::string>& notes) {
  std::vector<const Recording*> runs;
  for (const EngineRun& run : r.runs) runs.push_back(&run.recording);
  const json data = replay_data(r.scene.name, runs, marks_from_report(report));
  write_report_file(dir / kReplayData, data.dump(2) + '\n');
  try {
    write_report_file(dir / kReplayPage, replay_html(data, load_three_js()));
  } catch (const ThreeJsMissing& e) {
    notes.push_back(std::string(kReplayPage) + " not written: " + e.what() + "; `boxpile view` makes it from " +
                    kReplayData + " once three.js is installed");
  }
}

void write_report(const CompareResult& r, const fs::path& dir, std::vector<std::string>& notes) {
  const json report = report_json(r);
  write_report_file(dir / kReportJson, report.dump(1) + '\n');
  write_replay(r, report, dir, notes);
  const std::vector<std::string> rendered = write_plots(dir, report_plots(r), notes);
  write_report_file(dir / kReportMarkdown, report_markdown(r, rendered, notes));
}

}  // namespace boxpile
