#include "boxpile/validation/stability/stability_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/format_number.hpp"
#include "boxpile/validation/core/report_directory.hpp"
#include "boxpile/validation/stability/scene_checks.hpp"

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
            {"speed_end_max", number(m.speed_end_max)},
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
                   {"relation", k.at_least ? ">=" : "<="}, {"unit", k.unit}, {"passed", k.passed},
                   {"key", k.key}, {"reason", k.reason}});
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

// One cell of "What each engine needs to pass": "as run, 0.9x", "stepper=\"world\", 3.1x", or
// "none (rest_move 2.1x its limit)".
std::string needs_text(const StabilityResult& r, const StabilityCell& c) {
  const TunedCell& t = *c.tuned;
  const double own = own_cost(r, c.scene);
  if (!t.passed) {
    const SceneCheckResult* worst = nullptr;
    for (const SceneCheckResult& k : t.checks)
      if (!worst || miss_factor(k) > miss_factor(*worst)) worst = &k;
    std::string text = "none";
    if (worst) text += " (" + worst->name + " " + fmt(miss_factor(*worst), "%.2g") + "x its limit)";
    return text;
  }
  const std::string tried = settings_text(t.settings);
  std::string text = c.passed && tried.empty() ? std::string("as run") : tried;
  if (own > 0.0) text += ", " + fmt(t.us_per_sim_s / own, "%.2g") + "x";
  return text;
}

}  // namespace

std::string checks_markdown(const StabilityResult& r) {
  std::ostringstream md;
  md << "\n## The checks and why\n\nEvery check of every scene with its limit and the reason the scene gives "
        "for it (its `checks.reasons`; \"-\" when it gives none).\n\n| scene | check | limit | why |\n|---|---|---|---|\n";
  for (const Scene& s : r.scenes) {
    const auto cell = std::find_if(r.cells.begin(), r.cells.end(), [&](const StabilityCell& c) {
      return c.scene == s.name && c.checks.size() > 1;  // a cell that got past the finite check
    });
    if (cell == r.cells.end()) continue;
    for (const SceneCheckResult& k : cell->checks) {
      if (k.name == "finite") continue;
      md << "| " << s.name << " | " << k.name << " | " << (k.at_least ? ">= " : "<= ") << fmt(k.limit)
         << (k.unit.empty() ? "" : " " + k.unit) << " | " << (k.reason.empty() ? std::string("-") : k.reason) << " |\n";
    }
  }
  return md.str();
}

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
                      {"dt", s.time.dt}, {"duration", s.time.duration}, {"reasons", read_scene_checks(s).reasons}});
  }
  return {{"engines", r.engines}, {"scenes", scenes}, {"cells", cells}, {"own_passed", r.own_passed()},
          {"whole_catalogue", r.whole_catalogue}, {"shards", r.shards}, {"cells_total", r.cells_total},
          {"wall_seconds", r.wall_seconds}};
}

namespace {

// Back from JSON: null (a NaN or infinity written) reads as NaN.
double number_of(const json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

std::vector<SceneCheckResult> checks_of(const json& checks) {
  std::vector<SceneCheckResult> out;
  for (const json& k : checks) {
    out.push_back({k.at("name").get<std::string>(), number_of(k.at("value")), number_of(k.at("limit")),
                   k.at("relation").get<std::string>() == ">=", k.at("passed").get<bool>(),
                   k.at("unit").get<std::string>(), k.value("key", std::string()), k.value("reason", std::string())});
  }
  return out;
}

RunMeasures measures_of(const json& m) {
  RunMeasures r;
  r.finite = m.at("finite").get<bool>();
  r.energy_start = number_of(m.at("energy_start"));
  r.energy_rise = number_of(m.at("energy_rise"));
  r.energy_rise_t = number_of(m.at("energy_rise_t"));
  r.energy_change = number_of(m.at("energy_change"));
  r.kinetic_end = number_of(m.at("kinetic_end"));
  r.kinetic_end_max_body = number_of(m.at("kinetic_end_max_body"));
  r.speed_end_max = number_of(m.at("speed_end_max"));
  r.largest_move = number_of(m.at("largest_move"));
  if (m.at("moved_at_step").is_number()) r.moved_at_step = m.at("moved_at_step").get<long>();
  r.height_error = number_of(m.at("height_error"));
  r.drift = number_of(m.at("drift"));
  r.deepest_penetration = number_of(m.at("deepest_penetration"));
  r.max_spin = number_of(m.at("max_spin"));
  if (m.at("rebound").is_number()) r.rebound = m.at("rebound").get<double>();
  r.smallest_edge = number_of(m.at("smallest_edge"));
  return r;
}

}  // namespace

StabilityResult stability_from_json(const json& doc, const std::function<Scene(const std::string&)>& load) {
  StabilityResult r;
  r.engines = doc.at("engines").get<std::vector<std::string>>();
  for (const json& s : doc.at("scenes")) r.scenes.push_back(load(s.at("file").get<std::string>()));
  for (const json& c : doc.at("cells")) {
    StabilityCell cell;
    cell.scene = c.at("scene").get<std::string>();
    cell.engine = c.at("engine").get<std::string>();
    cell.settings = c.at("settings");
    cell.passed = c.at("passed").get<bool>();
    cell.checks = checks_of(c.at("checks"));
    cell.measures = measures_of(c.at("measures"));
    cell.steps = c.at("steps").get<long>();
    cell.out_of_time = c.at("out_of_time").get<bool>();
    cell.refused = c.at("refused").is_string() ? c.at("refused").get<std::string>() : std::string();
    cell.us_per_step = number_of(c.at("us_per_step"));
    cell.wall_seconds = number_of(c.at("wall_seconds"));
    if (const auto t = c.find("tuned"); t != c.end() && t->is_object()) {
      TunedCell tuned;
      tuned.passed = t->at("passed").get<bool>();
      tuned.settings = t->at("settings");
      tuned.us_per_sim_s = number_of(t->at("us_per_sim_s"));
      tuned.checks = checks_of(t->at("checks"));
      tuned.attempts = t->at("attempts").get<int>();
      tuned.out_of_budget = t->at("out_of_budget").get<bool>();
      cell.tuned = std::move(tuned);
    }
    r.cells.push_back(std::move(cell));
  }
  r.whole_catalogue = doc.at("whole_catalogue").get<bool>();
  r.shards = doc.value("shards", std::vector<std::string>{});
  r.cells_total = doc.value("cells_total", static_cast<int>(r.cells.size()));
  r.wall_seconds = number_of(doc.at("wall_seconds"));
  return r;
}

StabilityResult merge_stability(const std::vector<StabilityResult>& parts, const std::vector<std::string>& names) {
  if (parts.empty()) throw std::invalid_argument("no reports to merge");
  StabilityResult merged;
  merged.engines = parts.front().engines;
  merged.scenes = parts.front().scenes;
  merged.whole_catalogue = parts.front().whole_catalogue;
  merged.cells_total = parts.front().cells_total;
  auto scene_names = [](const StabilityResult& r) {
    std::vector<std::string> n;
    for (const Scene& s : r.scenes) n.push_back(s.name);
    return n;
  };
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const StabilityResult& p = parts[k];
    if (p.engines != merged.engines || scene_names(p) != scene_names(merged) || p.cells_total != merged.cells_total)
      throw std::invalid_argument(names[k] + ": other engines or scenes than " + names[0] + "'s: shards of one run only");
    if (p.shards.empty()) throw std::invalid_argument(names[k] + ": not a shard (a run without --shard)");
    for (const std::string& s : p.shards) {
      if (std::find(merged.shards.begin(), merged.shards.end(), s) != merged.shards.end())
        throw std::invalid_argument(names[k] + ": shard " + s + " is given twice");
      merged.shards.push_back(s);
    }
    merged.wall_seconds += p.wall_seconds;
  }
  // The cells in the run's own order: scene by scene, the engines in order within each.
  for (const Scene& s : merged.scenes) {
    for (const std::string& e : merged.engines) {
      for (const StabilityResult& p : parts)
        for (const StabilityCell& c : p.cells)
          if (c.scene == s.name && c.engine == e) merged.cells.push_back(c);
    }
  }
  if (static_cast<int>(merged.cells.size()) != merged.cells_total) {
    throw std::invalid_argument("the shards hold " + std::to_string(merged.cells.size()) + " of the run's " +
                                std::to_string(merged.cells_total) + " cells: a shard is missing");
  }
  std::sort(merged.shards.begin(), merged.shards.end());
  return merged;
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
  if (std::any_of(r.cells.begin(), r.cells.end(), [](const StabilityCell& c) { return c.tuned.has_value(); })) {
    md << "\n## What each engine needs to pass\n\nScene by scene: \"as run\" when the defaults pass (or a "
          "coarser step where it passes at less cost), else the settings the search found; then the cost as a "
          "multiple of our engine's cheapest passing one on the scene (µs of stepping per simulated second). "
          "\"none\": nothing passed within the budget, with the closest attempt's worst check and how many times "
          "its limit it was.\n\n| scene |";
    for (const std::string& e : r.engines) md << ' ' << e << " |";
    md << "\n|---|";
    for (std::size_t k = 0; k < r.engines.size(); ++k) md << "---|";
    md << '\n';
    for (const Scene& s : r.scenes) {
      md << "| " << s.name << " |";
      for (const std::string& e : r.engines) {
        const auto c = std::find_if(r.cells.begin(), r.cells.end(),
                                    [&](const StabilityCell& x) { return x.scene == s.name && x.engine == e; });
        md << ' ' << (c == r.cells.end() || !c->tuned ? std::string("-") : needs_text(r, *c)) << " |";
      }
      md << '\n';
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
    if (!read_scene_checks(s).holds("rest")) continue;
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
  md << checks_markdown(r);
  md << "\nRun time: " << fmt(r.wall_seconds, "%.1f") << " s";
  if (!r.shards.empty()) {
    md << ", in " << r.shards.size() << " shard" << (r.shards.size() == 1 ? "" : "s") << " (";
    for (std::size_t k = 0; k < r.shards.size(); ++k) md << (k ? ", " : "") << r.shards[k];
    md << "; their times added; a merged report's plots are in each shard's own report)";
  }
  md << ".\n";
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
