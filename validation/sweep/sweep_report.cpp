#include "boxpile/validation/sweep/sweep_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/validation/core/format_number.hpp"
#include "boxpile/validation/sweep/pareto.hpp"
#include "boxpile/validation/core/report_directory.hpp"
#include "boxpile/validation/sweep/sweep_plots.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;

// The accuracy levels of sweep.md: every power of ten between the best and worst front error.
constexpr double kLevelsPerDecade = 1.0;

std::string format(double x, const char* fmt = "%.3g") {
  return std::isfinite(x) ? format_number(x, fmt) : "—";
}

// Cheapest cell of `engine` (any engine when empty) whose error is at most `level`.
std::optional<std::size_t> cheapest_at(const SweepReport& r, const std::vector<std::size_t>& candidates,
                                       const std::string& measure, double level, const std::string& engine) {
  std::optional<std::size_t> best;
  for (std::size_t i : candidates) {
    const CellResult& c = r.cells[i];
    if (!engine.empty() && c.spec.engine != engine) continue;
    const double e = c.measures.error.at(measure).get<double>();
    if (e > level) continue;
    if (!best || c.us_per_simulated_second < r.cells[*best].us_per_simulated_second) best = i;
  }
  return best;
}

// The stable cells of a scene with a value for `measure`.
std::vector<std::size_t> candidates(const SweepReport& r, const std::string& scene, const std::string& measure) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < r.cells.size(); ++i) {
    const CellResult& c = r.cells[i];
    if (c.scene != scene || !c.measures.stable) continue;
    const auto it = c.measures.error.find(measure);
    if (it == c.measures.error.end() || !it->is_number() || !std::isfinite(it->get<double>())) continue;
    out.push_back(i);
  }
  return out;
}

std::string cell_label(const CellResult& c) {
  std::string label = c.spec.engine;
  if (!c.spec.settings.empty()) {
    label += ' ';
    label += settings_label(c.spec.settings);
  }
  return label + " dt=" + format(c.spec.dt, "%.4g");
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char ch : s) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

std::string sweep_csv(const SweepReport& r) {
  std::ostringstream os;
  os << "index,scene,engine,settings,dt,us_per_step,us_per_simulated_second";
  for (const MeasureDeclaration& m : kErrorMeasures) os << ',' << m.name;
  os << ",stable,passed,failed_checks\n";
  for (const CellResult& c : r.cells) {
    os << c.spec.index << ',' << csv_field(c.scene) << ',' << c.spec.engine << ',' << csv_field(settings_label(c.spec.settings))
       << ',' << format(c.spec.dt, "%.17g") << ',' << format(c.us_per_step, "%.6g") << ','
       << format(c.us_per_simulated_second, "%.6g");
    for (const MeasureDeclaration& m : kErrorMeasures) {
      const nlohmann::json& e = c.measures.error.at(std::string(m.name));
      os << ',' << (e.is_number() ? format(e.get<double>(), "%.17g") : "");
    }
    std::string failed;
    for (const SceneCheckResult& k : c.measures.checks) {
      if (!k.passed) failed += (failed.empty() ? "" : " ") + k.name;
    }
    os << ',' << (c.measures.stable ? "true" : "false") << ',' << (c.measures.passed ? "true" : "false") << ','
       << failed << '\n';
  }
  return os.str();
}

// The levels: powers of ten from the smallest front error's decade up to the largest's.
std::vector<double> accuracy_levels(const SweepReport& r, const std::vector<std::size_t>& front, const std::string& measure) {
  double lo = INFINITY, hi = 0.0;
  for (std::size_t i : front) {
    const double e = r.cells[i].measures.error.at(measure).get<double>();
    if (e > 0.0) lo = std::min(lo, e);
    hi = std::max(hi, e);
  }
  std::vector<double> levels;
  if (!(hi > 0.0)) return {0.0};
  if (!std::isfinite(lo)) lo = hi;
  const int top = static_cast<int>(std::ceil(std::log10(hi) * kLevelsPerDecade - 1e-9));
  const int bottom = static_cast<int>(std::ceil(std::log10(lo) * kLevelsPerDecade - 1e-9));
  for (int k = top; k >= bottom; --k) levels.push_back(std::pow(10.0, k / kLevelsPerDecade));
  if (std::any_of(front.begin(), front.end(), [&](std::size_t i) { return r.cells[i].measures.error.at(measure).get<double>() == 0.0; })) {
    levels.push_back(0.0);
  }
  return levels;
}

void md_scene_measure(std::ostringstream& md, const SweepReport& r, const std::string& scene, const MeasureDeclaration& m,
                      const std::vector<std::string>& engines) {
  const std::string measure(m.name);
  const std::vector<std::size_t> cand = candidates(r, scene, measure);
  if (cand.empty()) return;
  const SceneFronts fronts = fronts_of(r, scene, measure);
  md << "\n#### " << m.name << " (" << m.unit << ")\n\n"
     << "Cheapest cell (µs per simulated second) reaching each accuracy level; **bold**: the cheapest engine.\n\n"
     << "| error ≤ |";
  for (const std::string& e : engines) md << ' ' << e << " |";
  md << " cheapest |\n|---|";
  for (std::size_t k = 0; k < engines.size(); ++k) md << "---|";
  md << "---|\n";
  // One row per level; consecutive levels with the same cheapest cells share a row.
  struct Row {
    double loosest = 0.0, tightest = 0.0;
    std::vector<std::optional<std::size_t>> per_engine;
    std::optional<std::size_t> best;
  };
  std::vector<Row> rows;
  for (double level : accuracy_levels(r, fronts.overall, measure)) {
    Row row{level, level, {}, cheapest_at(r, cand, measure, level, "")};
    for (const std::string& e : engines) row.per_engine.push_back(cheapest_at(r, cand, measure, level, e));
    if (!rows.empty() && rows.back().per_engine == row.per_engine && rows.back().best == row.best) {
      rows.back().tightest = level;
    } else {
      rows.push_back(row);
    }
  }
  for (const Row& row : rows) {
    md << "| " << format(row.loosest, "%.0e")
       << (row.tightest != row.loosest ? " … " + format(row.tightest, "%.0e") : std::string()) << " |";
    for (std::size_t k = 0; k < engines.size(); ++k) {
      const std::optional<std::size_t>& c = row.per_engine[k];
      if (!c) {
        md << " — |";
        continue;
      }
      const std::string cost = format(r.cells[*c].us_per_simulated_second, "%.4g");
      md << ' ' << (row.best && r.cells[*row.best].spec.engine == engines[k] ? "**" + cost + "**" : cost) << " |";
    }
    md << ' ' << (row.best ? cell_label(r.cells[*row.best]) : std::string("none")) << " |\n";
  }
  md << "\nThe front over all engines (cheapest first):\n\n| µs/sim s | " << m.name << " | cell | checks |\n|---|---|---|---|\n";
  for (std::size_t i : fronts.overall) {
    const CellResult& c = r.cells[i];
    md << "| " << format(c.us_per_simulated_second, "%.4g") << " | " << format(c.measures.error.at(measure).get<double>())
       << " | " << cell_label(c) << " | " << (c.measures.passed ? "pass" : "fail") << " |\n";
  }
}

std::string sweep_md(const SweepReport& r, const std::vector<std::string>& plots) {
  std::ostringstream md;
  const std::vector<std::string> scenes = report_scenes(r);
  const std::vector<std::string> engines = report_engines(r);
  md << "# Sweep: " << r.grid_file << "\n\n"
     << r.cells.size() << " of the grid's " << r.grid_cells << " cells";
  if (r.shards.size() > 1 || (r.shards.size() == 1 && r.shards[0] != "1/1")) {
    md << " (shards";
    for (const std::string& s : r.shards) md << ' ' << s;
    md << ')';
  }
  md << ". Cost: µs of stepping per simulated second (µs per step / dt), measured in-process, the least of "
     << "the cell's timed runs; errors from one measured run (docs/sweeps.md defines each).\n\n## Machines\n\n";
  for (const nlohmann::json& m : r.machines) {
    md << "- " << m.value("shard", std::string("1/1")) << ": " << m.value("cpu", std::string("?")) << ", "
       << m.value("cores", 0) << " cores, host " << m.value("host", std::string("?")) << ", load average "
       << m.value("load_average", nlohmann::json::array()).dump() << " at the start\n";
  }
  for (const std::string& n : r.notes) md << "- note: " << n << '\n';

  md << "\n## Cells that fail a check\n\n";
  int failing = 0;
  for (const CellResult& c : r.cells) {
    if (c.measures.passed) continue;
    std::string failed;
    for (const SceneCheckResult& k : c.measures.checks) {
      if (!k.passed) failed += (failed.empty() ? "" : ", ") + describe(k);
    }
    md << "- " << c.scene << ": " << cell_label(c) << (c.measures.stable ? "" : " (**unstable**)") << ": " << failed << '\n';
    ++failing;
  }
  if (failing == 0) md << "None.\n";
  md << "\nUnstable cells (a failed check that shows instability: a non-finite state, energy rising past its limit, "
        "resting bodies that kept moving) are left off the fronts; cells that "
        "fail another check stay on them and are marked on the plots (crosses).\n";

  for (const std::string& scene : scenes) {
    md << "\n## " << scene << '\n';
    for (const MeasureDeclaration& m : kErrorMeasures) md_scene_measure(md, r, scene, m, engines);
  }
  md << "\n## Plots\n\n";
  for (const std::string& p : plots) md << "- [" << p << ".svg](" << p << ".svg)\n";
  return md.str();
}

std::vector<std::size_t> indices_of_engine(const std::vector<std::size_t>& cand, const SweepReport& r, const std::string& engine) {
  std::vector<std::size_t> out;
  for (std::size_t i : cand) {
    if (r.cells[i].spec.engine == engine) out.push_back(i);
  }
  return out;
}

std::vector<std::size_t> front_of(const SweepReport& r, const std::vector<std::size_t>& cells, const std::string& measure) {
  std::vector<CostError> points;
  for (std::size_t i : cells) points.push_back({r.cells[i].us_per_simulated_second, r.cells[i].measures.error.at(measure).get<double>()});
  std::vector<std::size_t> front;
  for (std::size_t k : pareto_front(points)) front.push_back(cells[k]);
  return front;
}

}  // namespace

std::string settings_label(const nlohmann::json& settings) {
  std::string s;
  for (const auto& [key, value] : settings.items()) s += (s.empty() ? "" : " ") + key + "=" + value.dump();
  return s;
}

std::vector<std::string> report_scenes(const SweepReport& r) {
  std::vector<std::string> out;
  for (const CellResult& c : r.cells) {
    if (std::find(out.begin(), out.end(), c.scene) == out.end()) out.push_back(c.scene);
  }
  return out;
}

std::vector<std::string> report_engines(const SweepReport& r) {
  std::vector<std::string> out;
  for (const CellResult& c : r.cells) {
    if (std::find(out.begin(), out.end(), c.spec.engine) == out.end()) out.push_back(c.spec.engine);
  }
  return out;
}

SceneFronts fronts_of(const SweepReport& r, const std::string& scene, const std::string& measure) {
  SceneFronts f;
  const std::vector<std::size_t> cand = candidates(r, scene, measure);
  for (const std::string& e : report_engines(r)) {
    const std::vector<std::size_t> mine = indices_of_engine(cand, r, e);
    if (!mine.empty()) f.by_engine[e] = front_of(r, mine, measure);
  }
  f.overall = front_of(r, cand, measure);
  return f;
}

nlohmann::json sweep_json(const SweepReport& r) {
  nlohmann::json cells = nlohmann::json::array();
  for (const CellResult& c : r.cells) cells.push_back(cell_json(c));
  nlohmann::json measures = nlohmann::json::array();
  for (const MeasureDeclaration& m : kErrorMeasures) measures.push_back({{"name", m.name}, {"unit", m.unit}, {"what", m.what}});
  // Fronts by cell index (the grid's numbering), per scene and measure.
  nlohmann::json fronts = nlohmann::json::object();
  auto indices = [&](const std::vector<std::size_t>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (std::size_t i : v) a.push_back(r.cells[i].spec.index);
    return a;
  };
  for (const std::string& scene : report_scenes(r)) {
    for (const MeasureDeclaration& m : kErrorMeasures) {
      const SceneFronts f = fronts_of(r, scene, std::string(m.name));
      if (f.overall.empty()) continue;
      nlohmann::json& entry = fronts[scene][std::string(m.name)];
      entry["all"] = indices(f.overall);
      for (const auto& [engine, front] : f.by_engine) entry[engine] = indices(front);
    }
  }
  return {{"grid_file", r.grid_file}, {"grid", r.grid}, {"grid_cells", r.grid_cells}, {"shards", r.shards},
          {"machines", r.machines}, {"notes", r.notes}, {"error_measures", measures}, {"cells", cells},
          {"fronts", fronts}};
}

SweepReport read_sweep_json(const std::string& path, std::size_t max_bytes) {
  const nlohmann::json j = json_input::parse(json_input::read_text_file(path, max_bytes), path);
  SweepReport r;
  try {
    r.grid_file = j.at("grid_file").get<std::string>();
    r.grid = j.at("grid");
    r.grid_cells = j.at("grid_cells").get<int>();
    r.shards = j.at("shards").get<std::vector<std::string>>();
    for (const nlohmann::json& m : j.at("machines")) r.machines.push_back(m);
    r.notes = j.at("notes").get<std::vector<std::string>>();
    for (const nlohmann::json& c : j.at("cells")) r.cells.push_back(cell_from_json(c));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, "", std::string("not a boxpile sweep report: ") + e.what());
  }
  return r;
}

void write_sweep_report(const SweepReport& r, const fs::path& dir, std::vector<std::string>& notes) {
  write_report_file(dir / kSweepJson, sweep_json(r).dump(1) + '\n');
  write_report_file(dir / "sweep.csv", sweep_csv(r));
  const std::vector<std::string> plots = write_sweep_plots(r, dir, notes);
  write_report_file(dir / kSweepMarkdown, sweep_md(r, plots));
}

std::string sweep_summary(const SweepReport& r) {
  const auto failing = std::count_if(r.cells.begin(), r.cells.end(), [](const CellResult& c) { return !c.measures.passed; });
  std::ostringstream os;
  os << r.cells.size() << " cells, " << failing << " failing a check\n";
  return os.str();
}

}  // namespace boxpile
