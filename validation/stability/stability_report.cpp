#include "boxpile/validation/stability/stability_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/format_number.hpp"
#include "boxpile/validation/core/report_directory.hpp"

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
// "passes every scene (2)", "fails 3 of 24 hard scenes": one engine's verdict over the scenes it
// ran, which are "the hard scenes" only when they were the whole catalogue.
std::string engine_verdict(const StabilityResult& r, const std::string& engine) {
  int failed = 0, ran = 0;
  for (const StabilityCell& c : r.cells) {
    if (c.engine != engine) continue;
    ++ran;
    failed += c.passed ? 0 : 1;
  }
  const std::string scenes = r.whole_catalogue ? "hard scene" : "scene";
  if (failed == 0) return "passes every " + scenes + " (" + std::to_string(ran) + ")";
  return "fails " + std::to_string(failed) + " of " + std::to_string(ran) + " " + scenes + (ran == 1 ? "" : "s");
}

// "our engine (own) passes every scene (2); ode fails 1 of 2 scenes": every engine that ran.
std::string verdicts(const StabilityResult& r) {
  std::string text;
  for (const std::string& e : r.engines) {
    text += (text.empty() ? "" : "; ") + (e == "own" ? std::string("our engine (own)") : e) + " " + engine_verdict(r, e);
  }
  return text;
}

}  // namespace

std::string cell_text(const StabilityCell& cell) {
  const SceneCheckResult* deciding = deciding_check(cell.checks);
  std::string s = cell.passed ? "pass" : "**FAIL**";
  if (deciding) s += ": " + describe(*deciding);
  int failures = 0;
  for (const SceneCheckResult& r : cell.checks) failures += r.passed ? 0 : 1;
  if (failures > 1) s += " (+" + std::to_string(failures - 1) + " more)";
  if (!cell.refused.empty()) s += "; refused: " + cell.refused;
  return s;
}

namespace {

json checks_json(const std::vector<SceneCheckResult>& checks) {
  json out = json::array();
  for (const SceneCheckResult& k : checks) {
    out.push_back({{"name", k.name}, {"value", number(k.value)}, {"limit", number(k.limit)},
                   {"relation", k.at_least ? ">=" : "<="}, {"unit", k.unit}, {"passed", k.passed}});
  }
  return out;
}

// "dt=0.00208 iterations=40"; empty when nothing was added to the settings given.
std::string settings_text(const json& settings) {
  std::string text;
  for (const auto& [key, value] : settings.items()) {
    text += text.empty() ? "" : " ";
    text += key;
    text += "=";
    text += value.is_number_float() ? fmt(value.get<double>(), "%.6g") : value.dump();
  }
  return text;
}

// The cheapest passing setting of our engine on `scene` (its tuned cost), 0 when none passed.
double own_cost(const StabilityResult& r, const std::string& scene) {
  for (const StabilityCell& c : r.cells)
    if (c.scene == scene && c.engine == "own" && c.tuned && c.tuned->passed) return c.tuned->us_per_sim_s;
  return 0.0;
}

// One cell's tuned result: "pass with dt=... iterations=40, 812 µs/s (3.1x own)", or the closest
// attempt and its worst miss.
std::string tuned_text(const StabilityResult& r, const StabilityCell& c) {
  const TunedCell& t = *c.tuned;
  const std::string tried = settings_text(t.settings);
  std::string text = t.passed ? (tried.empty() ? std::string("passes as run") : "pass with " + tried)
                              : "none passed; closest " + (tried.empty() ? std::string("as run") : tried);
  text += ", " + fmt(t.us_per_sim_s, "%.0f") + " µs/s";
  const double own = own_cost(r, c.scene);
  if (t.passed && own > 0.0 && c.engine != "own") text += " (" + fmt(t.us_per_sim_s / own, "%.2g") + "x own)";
  if (!t.passed) {
    const SceneCheckResult* worst = nullptr;
    for (const SceneCheckResult& k : t.checks)
      if (!worst || miss_factor(k) > miss_factor(*worst)) worst = &k;
    if (worst) text += ": " + describe(*worst) + " (" + fmt(miss_factor(*worst), "%.3g") + " times its limit)";
    if (t.out_of_budget) text += ", budget spent";
  }
  return text + ", " + std::to_string(t.attempts) + " runs";
}

}  // namespace

json stability_json(const StabilityResult& r) {
  json cells = json::array();
  for (const StabilityCell& c : r.cells) {
    const json checks = checks_json(c.checks);
    json tuned = nullptr;
    if (c.tuned) {
      tuned = {{"passed", c.tuned->passed}, {"settings", c.tuned->settings},
               {"us_per_sim_s", number(c.tuned->us_per_sim_s)}, {"checks", checks_json(c.tuned->checks)},
               {"attempts", c.tuned->attempts}, {"out_of_budget", c.tuned->out_of_budget}};
    }
    cells.push_back({{"scene", c.scene},
                     {"engine", c.engine},
                     {"settings", c.settings},
                     {"passed", c.passed},
                     {"checks", checks},
                     {"measures", measures_json(c.measures)},
                     {"steps", c.steps},
                     {"out_of_time", c.out_of_time},
                     {"refused", c.refused.empty() ? json(nullptr) : json(c.refused)},
                     {"us_per_step", number(c.us_per_step)},
                     {"us_per_sim_s", number(c.us_per_sim_s())},
                     {"wall_seconds", number(c.wall_seconds)}});
    if (c.tuned) cells.back()["tuned"] = tuned;
  }
  json scenes = json::array();
  for (const Scene& s : r.scenes) {
    scenes.push_back({{"name", s.name}, {"file", s.source}, {"note", s.note}, {"bodies", s.bodies.size()},
                      {"dt", s.time.dt}, {"duration", s.time.duration}});
  }
  return {{"engines", r.engines}, {"scenes", scenes}, {"cells", cells}, {"own_passed", r.own_passed()},
          {"whole_catalogue", r.whole_catalogue},
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
  if (r.whole_catalogue) {
    md << "# Stability of the hard scenes\n\n";
  } else {
    md << "# Stability of " << r.scenes.size() << " scene" << (r.scenes.size() == 1 ? "" : "s") << "\n\n";
  }
  md << "Verdicts: " << verdicts(r) << ". Each cell shows the check that decided it: the first failing one, or the one closest to its limit. "
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
  if (std::any_of(r.cells.begin(), r.cells.end(), [](const StabilityCell& c) { return c.tuned.has_value(); })) {
    md << "\n## The cheapest passing settings (--tune)\n\nPer cell: the verdict as run, then the cheapest "
          "settings found that pass every check (added to those given; `--set` reproduces them), their cost in µs of "
          "stepping per simulated second and its ratio to our engine's cheapest passing one on the scene; where "
          "none passed within the budget, the closest attempt and its worst check.\n\n"
          "| scene | engine | as run | tuned |\n|---|---|---|---|\n";
    for (const StabilityCell& c : r.cells) {
      if (!c.tuned) continue;
      md << "| " << c.scene << " | " << c.engine << " | " << (c.passed ? "pass" : "FAIL") << ", "
         << fmt(c.us_per_sim_s(), "%.0f") << " µs/s | " << tuned_text(r, c) << " |\n";
    }
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
    if (!c.passed) os << (c.engine == "own" ? "FAIL " : "finding ") << c.scene << " in " << c.engine << ": " << cell_text(c) << '\n';
    if (c.tuned) {
      os << "tuned " << c.scene << " in " << c.engine << " (as run: " << (c.passed ? "pass" : "FAIL") << ", "
         << fmt(c.us_per_sim_s(), "%.0f") << " µs/s): " << tuned_text(r, c) << '\n';
    }
  }
  for (const std::string& e : r.engines) os << (e == "own" ? std::string("our engine (own)") : e) << ' ' << engine_verdict(r, e) << '\n';
  return os.str();
}

void write_stability_report(const StabilityResult& r, const fs::path& dir, std::vector<std::string>& notes) {
  write_report_file(dir / kStabilityJson, stability_json(r).dump(1) + '\n');
  const std::vector<std::string> rendered = write_plots(dir, stability_plots(r), notes);
  write_report_file(dir / kStabilityMarkdown, stability_markdown(r, rendered, notes));
}

}  // namespace boxpile
