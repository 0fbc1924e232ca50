#include "boxpile/validation/stability_report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/format_number.hpp"
#include "boxpile/validation/report_directory.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string fmt(double x, const char* format = "%.3g") {
  return std::isnan(x) ? "nan" : format_number(x, format);
}

// JSON has no NaN or infinity: such a value is written as null.
json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json measures_json(const RunMeasures& m) {
  json j = {{"finite", m.finite},
            {"energy_start", number(m.energy_start)},
            {"energy_rise", number(m.energy_rise)},
            {"energy_rise_t", number(m.energy_rise_t)},
            {"energy_change", number(m.energy_change)},
            {"kinetic_end", number(m.kinetic_end)},
            {"kinetic_end_max_body", number(m.kinetic_end_max_body)},
            {"largest_move", number(m.largest_move)},
            {"moved_at_step", m.moved_at_step ? json(*m.moved_at_step) : json(nullptr)},
            {"height_error", number(m.height_error)},
            {"drift", number(m.drift)},
            {"deepest_penetration", number(m.deepest_penetration)},
            {"max_spin", number(m.max_spin)},
            {"rebound", m.rebound ? number(*m.rebound) : json(nullptr)},
            {"smallest_edge", number(m.smallest_edge)}};
  return j;
}

std::string plot_stem(const StabilityCell& c) { return c.scene + "_" + c.engine; }

// What our engine did: "passes every scene" or "fails N scene(s)".
std::string own_verdict(const StabilityResult& r) {
  const int failed = r.own_failures();
  return failed == 0 ? "passes every scene" : "fails " + std::to_string(failed) + " scene(s)";
}

}  // namespace

std::string cell_text(const StabilityCell& cell) {
  const SceneCheckResult* deciding = deciding_check(cell.checks);
  std::string s = cell.passed ? "pass" : "**FAIL**";
  if (deciding) s += ": " + describe(*deciding);
  int failures = 0;
  for (const SceneCheckResult& r : cell.checks) failures += r.passed ? 0 : 1;
  if (failures > 1) s += " (+" + std::to_string(failures - 1) + " more)";
  return s;
}

json stability_json(const StabilityResult& r) {
  json cells = json::array();
  for (const StabilityCell& c : r.cells) {
    json checks = json::array();
    for (const SceneCheckResult& k : c.checks) {
      checks.push_back({{"name", k.name}, {"value", number(k.value)}, {"limit", number(k.limit)},
                        {"relation", k.at_least ? ">=" : "<="}, {"unit", k.unit}, {"passed", k.passed}});
    }
    cells.push_back({{"scene", c.scene},
                     {"engine", c.engine},
                     {"settings", c.settings},
                     {"passed", c.passed},
                     {"checks", checks},
                     {"measures", measures_json(c.measures)},
                     {"steps", c.steps},
                     {"us_per_step", number(c.us_per_step)},
                     {"wall_seconds", number(c.wall_seconds)}});
  }
  json scenes = json::array();
  for (const Scene& s : r.scenes) {
    scenes.push_back({{"name", s.name}, {"file", s.source}, {"note", s.note}, {"bodies", s.bodies.size()},
                      {"dt", s.time.dt}, {"duration", s.time.duration}});
  }
  return {{"engines", r.engines}, {"scenes", scenes}, {"cells", cells}, {"own_passed", r.own_passed()},
          {"wall_seconds", r.wall_seconds}};
}

std::vector<PlotSpec> stability_plots(const StabilityResult& r) {
  std::vector<PlotSpec> plots;
  for (const StabilityCell& c : r.cells) {
    if (c.passed || c.t.empty()) continue;
    PlotSpec energy;
    energy.name = plot_stem(c) + "_energy";
    energy.title = c.scene + " in " + c.engine + ": total energy minus its start";
    energy.xlabel = "t (s)";
    energy.ylabel = "E - E0 (J)";
    PlotSeries e{c.engine, c.t, {}, PlotSeries::Style::Line, engine_colour(c.engine)};
    for (double v : c.energy) e.y.push_back(v - c.energy.front());
    energy.series.push_back(std::move(e));
    energy.hline = 0.0;
    energy.hline_title = "start";
    plots.push_back(std::move(energy));

    PlotSpec kinetic;
    kinetic.name = plot_stem(c) + "_kinetic";
    kinetic.title = c.scene + " in " + c.engine + ": kinetic energy";
    kinetic.xlabel = "t (s)";
    kinetic.ylabel = "kinetic energy (J)";
    kinetic.log_y = true;
    kinetic.series.push_back({c.engine, c.t, c.kinetic, PlotSeries::Style::Line, engine_colour(c.engine)});
    plots.push_back(std::move(kinetic));
  }
  return plots;
}

std::string stability_markdown(const StabilityResult& r, const std::vector<std::string>& plots,
                               const std::vector<std::string>& notes) {
  std::ostringstream md;
  md << "# Stability of the hard scenes\n\n";
  md << "Our engine " << own_verdict(r) << ". Each cell shows the check that decided it: the first failing one, or the one closest to its limit. "
        "A reference engine's failure is a finding, not an error of boxpile.\n\n";
  md << "| scene | bodies |";
  for (const std::string& e : r.engines) md << ' ' << e << " |";
  md << "\n|---|---|";
  for (std::size_t k = 0; k < r.engines.size(); ++k) md << "---|";
  md << '\n';
  for (const Scene& s : r.scenes) {
    md << "| " << s.name << " | " << s.bodies.size() << " |";
    for (const std::string& e : r.engines) {
      for (const StabilityCell& c : r.cells)
        if (c.scene == s.name && c.engine == e) md << ' ' << cell_text(c) << " |";
    }
    md << '\n';
  }
  md << "\n## Failures per engine\n\n| engine | failing scenes | µs per step (mean over the cells) |\n|---|---|---|\n";
  for (const std::string& e : r.engines) {
    int failed = 0, cells = 0;
    double us = 0.0;
    for (const StabilityCell& c : r.cells) {
      if (c.engine != e) continue;
      ++cells;
      failed += c.passed ? 0 : 1;
      us += c.us_per_step;
    }
    md << "| " << e << " | " << failed << " of " << cells << " | " << fmt(cells ? us / cells : 0.0, "%.0f") << " |\n";
  }
  md << "\n## Where a structure first moved\n\nThe step at which a body first moved farther than the scene's "
        "rest limit (`moved_at_step`; \"-\" when none did).\n\n| scene |";
  for (const std::string& e : r.engines) md << ' ' << e << " |";
  md << "\n|---|";
  for (std::size_t k = 0; k < r.engines.size(); ++k) md << "---|";
  md << '\n';
  for (const Scene& s : r.scenes) {
    if (!s.checks.rest) continue;
    md << "| " << s.name << " |";
    for (const std::string& e : r.engines) {
      for (const StabilityCell& c : r.cells) {
        if (c.scene != s.name || c.engine != e) continue;
        md << ' ' << (c.measures.moved_at_step ? std::to_string(*c.measures.moved_at_step) : std::string("-")) << " |";
      }
    }
    md << '\n';
  }
  if (!plots.empty()) {
    md << "\n## Failing cells\n\n";
    for (const std::string& p : plots) md << "![" << p << "](" << p << ".svg)\n\n";
  }
  md << "\n## Scenes\n\n";
  for (const Scene& s : r.scenes) md << "- **" << s.name << "** (`" << s.source << "`): " << s.note << '\n';
  md << "\nRun time: " << fmt(r.wall_seconds, "%.1f") << " s.\n";
  if (!notes.empty()) {
    md << "\n## Notes\n\n";
    for (const std::string& n : notes) md << "- " << n << '\n';
  }
  return md.str();
}

std::string stability_summary(const StabilityResult& r) {
  std::ostringstream os;
  for (const StabilityCell& c : r.cells) {
    if (c.passed) continue;
    os << (c.engine == "own" ? "FAIL " : "finding ") << c.scene << " in " << c.engine << ": " << cell_text(c) << '\n';
  }
  os << "our engine " << own_verdict(r) << '\n';
  return os.str();
}

void write_stability_report(const StabilityResult& r, const fs::path& dir, std::vector<std::string>& notes) {
  write_report_file(dir / kStabilityJson, stability_json(r).dump(1) + '\n');
  const std::vector<std::string> rendered = write_plots(dir, stability_plots(r), notes);
  write_report_file(dir / kStabilityMarkdown, stability_markdown(r, rendered, notes));
}

}  // namespace boxpile
