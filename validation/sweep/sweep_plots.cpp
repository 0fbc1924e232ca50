#include "boxpile/validation/sweep/sweep_plots.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/plots.hpp"
#include "boxpile/validation/sweep/sweep_report.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;
using Style = PlotSeries::Style;

// The overall front is drawn in black (no engine's colour).
constexpr const char* kOverallColour = "#000000";
// Error values of exactly 0 are drawn at this on the logarithmic axes.
constexpr double kLogFloor = 1e-14;

// A file stem for a scene path: its file name without extension, letters, digits, '_' and '-'.
std::string stem_of(const std::string& scene) {
  std::string stem = fs::path(scene).stem().string();
  for (char& ch : stem) {
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-') ch = '_';
  }
  return stem;
}

// A scene's name for titles (the path a grid gives may be long and relative).
std::string name_of(const SweepReport& r, const std::string& scene) {
  for (const CellResult& c : r.cells)
    if (c.scene == scene && !c.scene_name.empty()) return c.scene_name;
  return fs::path(scene).stem().string();
}

double error_of(const CellResult& c, const std::string& measure) {
  const nlohmann::json& e = c.measures.error.at(measure);
  return e.is_number() ? e.get<double>() : NAN;
}

PlotSpec log_plot(std::string name, std::string title, std::string xlabel, std::string ylabel, bool log_x) {
  PlotSpec spec;
  spec.name = std::move(name);
  spec.title = std::move(title);
  spec.xlabel = std::move(xlabel);
  spec.ylabel = std::move(ylabel);
  spec.log_x = log_x;
  spec.log_y = true;
  spec.log_floor = kLogFloor;
  return spec;
}

PlotSpec front_plot(const SweepReport& r, const std::string& scene, const std::string& stem, const MeasureDeclaration& m,
                    const std::vector<std::string>& engines) {
  const std::string measure(m.name);
  PlotSpec spec = log_plot("front_" + stem + "_" + measure, name_of(r, scene) + ": " + measure + " against cost",
                           "µs per simulated second", measure + " (" + std::string(m.unit) + ")", true);
  const SceneFronts fronts = fronts_of(r, scene, measure);
  for (const std::string& e : engines) {
    const std::string color = engine_colour(e);
    PlotSeries passing{e, {}, {}, Style::Points, color}, failing{e + " (fails a check)", {}, {}, Style::Crosses, color};
    for (const CellResult& c : r.cells) {
      if (c.scene != scene || c.spec.engine != e || !c.measures.stable) continue;
      const double err = error_of(c, measure);
      if (!std::isfinite(err)) continue;
      PlotSeries& s = c.measures.passed ? passing : failing;
      s.x.push_back(c.us_per_simulated_second);
      s.y.push_back(err);
    }
    PlotSeries front{e + " front", {}, {}, Style::Dashed, color};
    if (const auto it = fronts.by_engine.find(e); it != fronts.by_engine.end()) {
      for (std::size_t i : it->second) {
        front.x.push_back(r.cells[i].us_per_simulated_second);
        front.y.push_back(error_of(r.cells[i], measure));
      }
    }
    spec.series.push_back(std::move(passing));
    spec.series.push_back(std::move(failing));
    spec.series.push_back(std::move(front));
  }
  PlotSeries overall{"front over all engines", {}, {}, Style::Line, kOverallColour};
  for (std::size_t i : fronts.overall) {
    overall.x.push_back(r.cells[i].us_per_simulated_second);
    overall.y.push_back(error_of(r.cells[i], measure));
  }
  spec.series.push_back(std::move(overall));
  return spec;
}

// The cell of our impulse method with the most passes (the first of equals): its convergence.
const CellResult* convergence_cell(const SweepReport& r, const std::string& scene) {
  const CellResult* best = nullptr;
  auto passes = [](const CellResult& c) {
    return c.convergence->collision.size() + c.convergence->contact.size() + c.convergence->shock.size();
  };
  for (const CellResult& c : r.cells) {
    if (c.scene != scene || !c.convergence) continue;
    if (!best || passes(c) > passes(*best)) best = &c;
  }
  return best;
}

PlotSpec convergence_plot(const CellResult& c, const std::string& stem) {
  PlotSpec spec = log_plot("convergence_" + stem,
                           c.scene_name + ": residual after each pass (mean over the run)",
                           "pass", "largest approaching normal velocity (m/s)", false);
  auto series = [](const std::string& title, const std::vector<double>& y, int color) {
    PlotSeries s{title, {}, y, Style::LinePoints, plot_colour(color)};
    for (std::size_t k = 0; k < y.size(); ++k) s.x.push_back(static_cast<double>(k + 1));
    return s;
  };
  spec.series.push_back(series("collision loop", c.convergence->collision, 0));
  spec.series.push_back(series("contact loop", c.convergence->contact, 1));
  spec.series.push_back(series("shock propagation (largest change)", c.convergence->shock, 2));
  spec.hline = std::max(c.convergence->after_shock, kLogFloor);
  spec.hline_title = "after shock";
  return spec;
}

// ODE's and Bullet's error against "iterations": one line per engine and combination of its other
// settings and dt. Empty when no engine sweeps its iterations.
PlotSpec iterations_plot(const SweepReport& r, const std::string& scene, const std::string& stem, const MeasureDeclaration& m) {
  const std::string measure(m.name);
  PlotSpec spec = log_plot("iterations_" + stem + "_" + measure,
                           name_of(r, scene) + ": " + measure + " against solver iterations",
                           "iterations", measure + " (" + std::string(m.unit) + ")", true);
  std::map<std::string, PlotSeries> lines;
  std::vector<std::string> order;
  std::map<std::string, int> lines_of_engine;  // each engine's lines differ in dash type and point
  for (const CellResult& c : r.cells) {
    if (c.scene != scene || !c.spec.settings.contains("iterations") || !c.measures.stable) continue;
    const double err = error_of(c, measure);
    if (!std::isfinite(err)) continue;
    nlohmann::json others = c.spec.settings;
    others.erase("iterations");
    const std::string title = c.spec.engine + (others.empty() ? "" : " " + settings_label(others)) + " dt=" +
                              std::to_string(c.spec.dt).substr(0, 8);
    if (!lines.count(title)) {
      lines[title] = PlotSeries{title, {}, {}, Style::LinePoints, engine_colour(c.spec.engine)};
      lines[title].dash = 1 + lines_of_engine[c.spec.engine]++ % 5;
      order.push_back(title);
    }
    lines[title].x.push_back(c.spec.settings.at("iterations").get<double>());
    lines[title].y.push_back(err);
  }
  for (const std::string& t : order) {
    if (lines[t].x.size() > 1) spec.series.push_back(std::move(lines[t]));
  }
  return spec;
}

}  // namespace

std::vector<std::string> write_sweep_plots(const SweepReport& r, const fs::path& dir, std::vector<std::string>& warnings) {
  std::vector<PlotSpec> specs;
  const std::vector<std::string> engines = report_engines(r);
  const std::vector<std::string> scenes = report_scenes(r);
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    // Two scenes with one file name (different folders) get their position as well.
    std::string stem = stem_of(scenes[s]);
    for (std::size_t t = 0; t < s; ++t) {
      if (stem_of(scenes[t]) == stem) {
        stem += '_';
        stem += std::to_string(s + 1);
      }
    }
    for (const MeasureDeclaration& m : kErrorMeasures) {
      PlotSpec front = front_plot(r, scenes[s], stem, m, engines);
      if (std::any_of(front.series.begin(), front.series.end(), [](const PlotSeries& p) { return !p.x.empty(); })) {
        specs.push_back(std::move(front));
      }
      PlotSpec iterations = iterations_plot(r, scenes[s], stem, m);
      if (!iterations.series.empty()) specs.push_back(std::move(iterations));
    }
    if (const CellResult* c = convergence_cell(r, scenes[s])) specs.push_back(convergence_plot(*c, stem));
  }
  std::vector<std::string> names;
  const bool gnuplot = gnuplot_available();
  if (!gnuplot && !specs.empty()) warnings.push_back("gnuplot not found: plots left as data and scripts (no SVG)");
  for (const PlotSpec& spec : specs) {
    write_plot_files(dir, spec);
    names.push_back(spec.name);
    if (!gnuplot) continue;
    try {
      render_plot(dir, spec.name);
    } catch (const PlotError& e) {
      warnings.push_back(e.what());
    }
  }
  return names;
}

}  // namespace boxpile
