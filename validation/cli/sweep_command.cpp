#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/validation/cli/activity.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/progress.hpp"
#include "boxpile/validation/cli/report_command.hpp"
#include "boxpile/validation/core/data_directory.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/core/format_number.hpp"
#include "boxpile/validation/core/output_safety.hpp"
#include "boxpile/validation/sweep/sweep_report.hpp"
#include "boxpile/validation/sweep/sweep.hpp"
#include "boxpile/validation/sweep/sweep_runner.hpp"

namespace boxpile::cli {
namespace {

namespace fs = std::filesystem;

// The grids installed with boxpile, under its data folder.
constexpr const char* kInstalledGrids = "benchmarks/grids";

// One line per finished cell on stderr, with the time left estimated from the cells so far.
void print_progress(const SweepProgress& p) {
  throw_if_interrupted();
  if (p.done == 0) return;
  const double left = p.elapsed / p.done * (p.total - p.done);
  std::string line = "  [" + std::to_string(p.done) + "/" + std::to_string(p.total) + "] " + duration_text(p.elapsed) +
                     " elapsed, about " + duration_text(left) + " left";
  if (p.last) {
    line += ": " + p.last->scene + " " + p.last->spec.engine + " " + settings_label(p.last->spec.settings) +
            " dt=" + format_number(p.last->spec.dt, "%.4g") + ": " + format_number(p.last->us_per_simulated_second, "%.4g") +
            " µs/sim s" + (p.last->measures.passed ? "" : " (fails a check)");
  }
  std::cerr << line << '\n';
}

// The grid file: GRID as given when it exists; a bare name (no folder) that is no file here names
// one of the grids installed with boxpile (P/share/boxpile/benchmarks/grids, with or without
// ".json"). InputError naming GRID and the installed grids otherwise.
std::string find_grid(const std::string& grid) {
  std::error_code ec;
  if (fs::exists(grid, ec) || fs::path(grid).has_parent_path()) return grid;
  const fs::path installed = data_path(kInstalledGrids);
  for (const fs::path& candidate : {installed / grid, installed / (grid + ".json")}) {
    if (fs::is_regular_file(candidate, ec)) return candidate.string();
  }
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(installed, ec)) {
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw InputError(grid, "", "no such grid file, and no installed grid of that name in " + installed.string() +
                                 (known.empty() ? "" : " (installed: " + known + ")"));
}

// A cell's run within the caps of run and compare, before any cell runs: the step count of the
// grid's (or the scene's) dt and duration, and the penalty method's substeps and stability bound
// (`"dt": [1e-9]` or `"duration": 1e9` used to run until killed).
void check_cell_work(const SweepGrid& grid, const CellSpec& cell, const RunLimits& limits) {
  const EngineConfig config = cell_config(grid, cell);
  const Scene& scene = config.scene;
  const bool grid_dt = !grid.dt.empty();
  if (const auto problem = check_time_settings(scene.time.dt, scene.time.duration, limits.max_steps)) {
    const bool on_dt = problem->field == TimeSettingsProblem::Field::Dt;
    const bool from_grid = on_dt ? grid_dt : (grid_dt || grid.duration.has_value());
    const std::string what = problem->what + (problem->over_cap ? " (--max-steps raises it)" : "");
    if (from_grid) throw InputError(grid.source, on_dt || !grid.duration ? "dt" : "duration", what);
    throw InputError(scene.source, on_dt ? "time.dt" : "time.duration", what);
  }
  check_run_work(scene, cell.engine, config.settings, limits, grid_dt, grid.source + ": dt");
}

}  // namespace

void add_sweep_command(CLI::App& app, SweepOptions& options) {
  CLI::App* cmd = app.add_subcommand("sweep", "Run every cell of a grid of engines and settings: cost against error, "
                                              "Pareto fronts (sweep.json, sweep.csv, sweep.md, SVG plots)");
  cmd->add_option("grid", options.grid,
                  "Grid file (JSON, docs/sweeps.md), or the name of an installed grid (accuracy_cost, lab_report, pareto, settled)")
      ->required();
  add_report_option(*cmd, options.report, "sweep");
  cmd->add_option("--shard", options.shard, "Run shard I of N (I/N, 1-based): cells whose position k has k mod N = I-1")
      ->capture_default_str();
  cmd->add_option("--jobs", options.jobs, "Run cells in J parallel processes (their timings then ran side by side)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  add_limit_options(*cmd, options.limits, false);

  app.add_subcommand("settings", "List every setting each engine exposes to a sweep grid, with units (Markdown)");

  CLI::App* merge = app.add_subcommand("sweep-merge", "Merge the reports of a sweep's shards into one report");
  merge->add_option("reports", options.merge_inputs, "Shard report directories (each holding sweep.json)")
      ->required();
  merge->add_option("--out,--report", options.report, "Merged report directory (--report is the same)")->capture_default_str();
  add_input_limit_option(*merge, options.limits.max_input_bytes);
}

int run_sweep_command(const SweepOptions& options) {
  Shard shard;
  try {
    shard = parse_shard(options.shard);
  } catch (const std::invalid_argument& e) {
    throw InputError("command line", "--shard", e.what());
  }
  // Everything is checked before any cell runs: the grid, its scenes, engines and settings, the
  // report directory.
  const std::string grid_file = find_grid(options.grid);
  ReportDirectory dir(options.report, {grid_file}, kSweepJson);
  std::optional<SweepGrid> loaded;
  {
    const Activity loading("loading " + grid_file);
    loaded.emplace(load_grid(grid_file, options.limits.load()));
  }
  const SweepGrid& grid = *loaded;
  const std::vector<CellSpec> all = grid_cells(grid);
  std::vector<CellSpec> cells;
  std::copy_if(all.begin(), all.end(), std::back_inserter(cells), [&](const CellSpec& c) { return in_shard(c, shard); });
  for (const CellSpec& c : cells) check_cell_work(grid, c, options.limits);

  SweepReport report;
  report.grid_file = grid_file;
  report.grid = grid.document;
  report.grid_cells = static_cast<int>(all.size());
  const std::string shard_text = std::to_string(shard.index) + "/" + std::to_string(shard.count);
  report.shards = {shard_text};
  nlohmann::json machine = describe_machine();
  machine["shard"] = shard_text;
  machine["jobs"] = options.jobs;
  report.machines = {machine};
  if (options.jobs > 1) {
    report.notes.push_back("cells ran side by side in " + std::to_string(options.jobs) +
                           " processes: their timings include that competition (shard " + shard_text + ")");
  }

  std::cerr << "boxpile sweep: " << grid_file << ": " << cells.size() << " cells";
  if (shard.count > 1) std::cerr << " (shard " << shard_text << " of " << all.size() << ")";
  std::cerr << ", " << grid.repetitions << " timed runs each" << (options.jobs > 1 ? ", " + std::to_string(options.jobs) + " processes" : "")
            << '\n';
  SweepRunOptions run;
  run.jobs = options.jobs;
  run.work_dir = dir.staging() / "cells";
  run.progress = print_progress;
  const Activity running("running the cells of " + grid_file);
  const auto ran = run_and_report(
      dir,
      [&] {
        report.cells = run_sweep_cells(grid, cells, run);
        return std::move(report);
      },
      write_sweep_report, sweep_summary, kSweepMarkdown);
  return ran ? kExitOk : kExitInterrupted;
}

int run_settings_command() {
  std::cout << settings_markdown();
  return kExitOk;
}

int run_sweep_merge_command(const SweepOptions& options) {
  // The merged report may be none of its inputs (it would replace one before it is read again,
  // or hold one): checked, as every output, against each input's sweep.json.
  std::vector<fs::path> input_files;
  for (const std::string& in : options.merge_inputs) input_files.push_back(fs::path(in) / kSweepJson);
  ReportDirectory dir(options.report, input_files, kSweepJson);
  std::vector<SweepReport> parts;
  for (std::size_t k = 0; k < options.merge_inputs.size(); ++k) {
    const std::string& in = options.merge_inputs[k];
    std::error_code ec;
    if (!fs::is_regular_file(input_files[k], ec)) throw InputError(in, "", "no sweep.json here: not a sweep report");
    parts.push_back(read_sweep_json(input_files[k].string(), options.limits.max_input_bytes));
  }
  SweepReport merged;
  merged.grid_file = parts.front().grid_file;
  merged.grid = parts.front().grid;
  merged.grid_cells = parts.front().grid_cells;
  std::map<int, std::string> owner;  // cell index -> the report that holds it
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const SweepReport& p = parts[k];
    const std::string& name = options.merge_inputs[k];
    if (p.grid != merged.grid || p.grid_cells != merged.grid_cells) {
      throw InputError(name + "/sweep.json", "grid", "a different grid from " + options.merge_inputs[0] + "'s: shards of one sweep only");
    }
    for (const CellResult& c : p.cells) {
      if (const auto it = owner.find(c.spec.index); it != owner.end()) {
        throw InputError(name + "/sweep.json", "cells", "cell " + std::to_string(c.spec.index) + " is also in " + it->second);
      }
      owner[c.spec.index] = name;
      merged.cells.push_back(c);
    }
    merged.shards.insert(merged.shards.end(), p.shards.begin(), p.shards.end());
    merged.machines.insert(merged.machines.end(), p.machines.begin(), p.machines.end());
    merged.notes.insert(merged.notes.end(), p.notes.begin(), p.notes.end());
  }
  if (static_cast<int>(merged.cells.size()) != merged.grid_cells) {
    std::cerr << "boxpile: warning: the merged reports hold " << merged.cells.size() << " of the grid's "
              << merged.grid_cells << " cells (a shard is missing)\n";
  }
  std::sort(merged.cells.begin(), merged.cells.end(),
            [](const CellResult& a, const CellResult& b) { return a.spec.index < b.spec.index; });
  report_to(dir, merged, write_sweep_report, sweep_summary, kSweepMarkdown);
  return kExitOk;
}

}  // namespace boxpile::cli
