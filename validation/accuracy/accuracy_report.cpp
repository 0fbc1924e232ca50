// accuracy.json, accuracy.md and the plots of `boxpile accuracy` (docs/accuracy.md).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/accuracy/accuracy.hpp"
#include "boxpile/validation/core/format_number.hpp"
#include "boxpile/validation/core/plots.hpp"
#include "boxpile/validation/core/report_directory.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Style = PlotSeries::Style;

// Errors of exactly 0 are drawn at this on the logarithmic axes.
constexpr double kAccuracyLogFloor = 1e-14;

// JSON has no NaN or infinity: such a value is written as null.
json finite_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }
json optional_json(const std::optional<double>& x) { return x ? finite_or_null(*x) : json(nullptr); }

std::string number_text(double x, const char* format = "%.3g") {
  if (std::isinf(x)) return "non-finite";
  return std::isnan(x) ? "—" : format_number(x, format);
}
std::string number_text(const std::optional<double>& x, const char* format = "%.3g") { return x ? number_text(*x, format) : "—"; }

// A file stem for a scene name: letters, digits, '_' and '-'.
std::string scene_stem(const std::string& name) {
  std::string stem = name;
  for (char& ch : stem) {
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-') ch = '_';
  }
  return stem;
}

json truth_measures_json(const TruthMeasures& m) {
  return {{"position", optional_json(m.position)},
          {"velocity", optional_json(m.velocity)},
          {"orientation", optional_json(m.orientation)},
          {"trajectory", optional_json(m.trajectory)},
          {"rebound", optional_json(m.rebound)}};
}

json converged_json(const ConvergedTruth& t) {
  json positions = json::array();
  for (const Vec3& p : t.positions) positions.push_back({p.x(), p.y(), p.z()});
  return {{"positions", positions},
          {"uncertainty", t.uncertainty},
          {"order", optional_json(t.order)},
          {"extrapolated", t.extrapolated},
          {"steps", t.steps},
          {"settings", t.settings}};
}

std::vector<PlotSpec> accuracy_plots(const AccuracyResult& r) {
  std::vector<PlotSpec> plots;
  for (const AccuracyScene& s : r.scenes) {
    const std::string stem = scene_stem(s.name);
    PlotSpec by_dt, by_cost;
    by_dt.name = "error_dt_" + stem;
    by_dt.title = s.name + ": error against the time step (truth: " + std::string(truth_kind_name(s.truth)) + ")";
    by_dt.xlabel = "dt (s)";
    by_cost.name = "error_cost_" + stem;
    by_cost.title = s.name + ": error against cost";
    by_cost.xlabel = "µs per simulated second";
    for (PlotSpec* p : {&by_dt, &by_cost}) {
      p->ylabel = "error (m)";
      p->log_x = p->log_y = true;
      p->log_floor = kAccuracyLogFloor;
    }
    for (const AccuracyEngine& e : s.engines) {
      for (int scale : r.settings.iteration_scales) {
        const std::string title = e.engine + (scale == 1 ? "" : " iterations x" + std::to_string(scale));
        PlotSeries d{title, {}, {}, Style::LinePoints, engine_colour(e.engine)};
        if (scale != r.settings.iteration_scales.front()) d.style = Style::Dashed;
        PlotSeries c = d;
        for (const AccuracyCell& cell : e.cells) {
          if (cell.iteration_scale != scale || !std::isfinite(cell.error)) continue;
          d.x.push_back(cell.dt);
          d.y.push_back(cell.error);
          c.x.push_back(cell.us_per_simulated_second);
          c.y.push_back(cell.error);
        }
        by_dt.series.push_back(std::move(d));
        by_cost.series.push_back(std::move(c));
      }
    }
    plots.push_back(std::move(by_dt));
    plots.push_back(std::move(by_cost));
  }
  return plots;
}

std::string accuracy_markdown(const AccuracyResult& r, const std::vector<std::string>& rendered,
                              const std::vector<std::string>& notes) {
  std::ostringstream md;
  md << "# Accuracy against cost\n\n"
     << "Each cell: the scene at one time step in one engine; error = the largest distance of a body's final "
        "position from the truth's (m); cost = µs of Engine::step() per simulated second, the least of "
     << r.settings.repetitions << " runs interleaved over the engines and cells. Order: the slope of log(error) "
        "against log(dt). Machine: "
     << r.machine.value("cpu", std::string("?")) << ", load " << r.machine.value("load_average", json(nullptr)).dump()
     << ". docs/accuracy.md says how to read it.\n\n";
  for (const AccuracyScene& s : r.scenes) {
    md << "## " << s.name << "\n\n`" << s.path << "`, truth: **" << truth_kind_name(s.truth) << "**\n\n";
    md << "| engine | order | dt (s) | iterations | error (m) | velocity (m/s) | orientation (rad) | trajectory (m) | "
          "µs per simulated s |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const AccuracyEngine& e : s.engines) {
      for (const AccuracyCell& c : e.cells) {
        md << "| " << e.engine << " | " << number_text(e.order, "%.2f") << " | " << number_text(c.dt, "%.6g") << " | x"
           << c.iteration_scale << " | " << number_text(c.error) << " | " << number_text(c.measures.velocity) << " | "
           << number_text(c.measures.orientation) << " | " << number_text(c.measures.trajectory) << " | "
           << number_text(c.us_per_simulated_second, "%.0f") << " |\n";
      }
    }
    md << '\n';
    for (const AccuracyEngine& e : s.engines) {
      if (e.orders.empty()) continue;
      md << "- " << e.engine << "'s order by measure:";
      for (const auto& [name, order] : e.orders) md << ' ' << name << ' ' << number_text(order, "%.2f");
      md << '\n';
    }
    for (const AccuracyEngine& e : s.engines) {
      if (!e.converged) continue;
      md << "- " << e.engine << "'s converged answer: steps";
      for (double h : e.converged->steps) md << ' ' << number_text(h, "%.4g");
      md << " s, settings " << e.converged->settings.dump() << "; "
         << (e.converged->extrapolated ? "Richardson-extrapolated at order " + number_text(e.converged->order, "%.2f")
                                       : std::string("not extrapolated (the references do not converge at a steady order)"))
         << ", uncertainty " << number_text(e.converged->uncertainty) << " m\n";
    }
    const std::string stem = scene_stem(s.name);
    for (const std::string& name : {"error_dt_" + stem, "error_cost_" + stem}) {
      if (std::find(rendered.begin(), rendered.end(), name) != rendered.end()) md << "\n![" << name << "](" << name << ".svg)\n";
    }
    md << '\n';
    if (s.outcomes) md << outcomes_markdown(*s.outcomes);
  }
  for (const std::string& n : notes) md << "Note: " << n << "\n\n";
  return md.str();
}

}  // namespace

json accuracy_json(const AccuracyResult& r) {
  json scenes = json::array();
  for (const AccuracyScene& s : r.scenes) {
    json engines = json::array();
    for (const AccuracyEngine& e : s.engines) {
      json cells = json::array();
      for (const AccuracyCell& c : e.cells) {
        json cell = {{"dt", c.dt},
                     {"settings", c.settings},
                     {"error", finite_or_null(c.error)},
                     {"us_per_sim_s", c.us_per_simulated_second},
                     {"iteration_scale", c.iteration_scale},
                     {"steps", c.steps},
                     {"finite", c.finite}};
        if (s.truth == TruthKind::Analytic) cell["measures"] = truth_measures_json(c.measures);
        cells.push_back(std::move(cell));
      }
      json ej = {{"engine", e.engine}, {"order", optional_json(e.order)}, {"cells", cells}};
      if (!e.orders.empty()) {
        json orders = json::object();
        for (const auto& [name, order] : e.orders) orders[name] = optional_json(order);
        ej["orders"] = orders;
      }
      if (e.converged) ej["converged"] = converged_json(*e.converged);
      engines.push_back(std::move(ej));
    }
    scenes.push_back({{"scene", s.path},
                      {"name", s.name},
                      {"truth", truth_kind_name(s.truth)},
                      {"engines", engines},
                      {"outcomes", s.outcomes ? outcomes_json(*s.outcomes) : json(nullptr)}});
  }
  return {{"scenes", scenes},
          {"repetitions", r.settings.repetitions},
          {"machine", r.machine},
          {"wall_seconds", r.wall_seconds}};
}

void write_accuracy_report(const AccuracyResult& r, const fs::path& d, std::vector<std::string>& notes) {
  write_report_file(d / kAccuracyJson, accuracy_json(r).dump(1) + '\n');
  const std::vector<std::string> rendered = write_plots(d, accuracy_plots(r), notes);
  write_report_file(d / kAccuracyMarkdown, accuracy_markdown(r, rendered, notes));
}

std::string accuracy_summary(const AccuracyResult& r) {
  std::ostringstream out;
  for (const AccuracyScene& s : r.scenes) {
    out << s.name << " (truth: " << truth_kind_name(s.truth) << ")\n";
    for (const AccuracyEngine& e : s.engines) {
      char head[64];
      std::snprintf(head, sizeof head, "  %-12s order %-5s error", e.engine.c_str(), number_text(e.order, "%.2f").c_str());
      out << head;
      for (const AccuracyCell& c : e.cells) out << ' ' << number_text(c.error, "%.2e");
      out << " m\n";
    }
    if (s.outcomes) {
      for (const OutcomePair& p : s.outcomes->pairs) {
        out << "  outcomes over " << s.outcomes->settings.starts << " starts, " << p.a << " vs " << p.b << ": " << p.verdict() << '\n';
      }
    }
  }
  return out.str();
}

}  // namespace boxpile
