// `boxpile sweep`: every cell of a grid run and measured, cost (µs per simulated second, the
// least of the grid's repetitions, measured in-process) against error. docs/sweeps.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/sweep/sweep_grid.hpp"
#include "boxpile/validation/sweep/sweep_measures.hpp"

namespace boxpile {

// Our impulse method's convergence over a run: the residual (largest approaching normal velocity,
// m/s) after each pass of a loop, averaged over the steps in which the loop ran. A pass the loop
// did not need (it had converged) counts with the residual it stopped at.
struct Convergence {
  std::vector<double> collision;  // per collision-loop pass
  std::vector<double> contact;    // per contact-loop pass
  // Per shock-propagation pass: the largest velocity change an impulse made in it (over the
  // levels), m/s: how far the pass still moved the stack.
  std::vector<double> shock;
  double after_shock = 0.0;       // after shock propagation (mean over the steps)
  double shock_passes = 0.0;      // passes shock propagation used per step, summed over levels (mean)
};

struct CellResult {
  CellSpec spec;
  std::string scene;  // the scene's path as the grid names it
  std::string scene_name;  // the scene's own name (its "name"), for titles
  long steps = 0;
  int timed_runs = 0;
  // Cells timed side by side (--jobs): their timings include that competition.
  int jobs = 1;
  double us_per_step = 0.0;               // the least of the timed runs
  double us_per_simulated_second = 0.0;   // us_per_step / dt
  CellMeasures measures;
  std::optional<Convergence> convergence;  // our impulse method only
};

// A cell's scene and engine settings: the grid's scene at the cell's dt with its settings
// applied (what run_cell runs, and what the command line checks against the caps first).
EngineConfig cell_config(const SweepGrid& grid, const CellSpec& cell);

// Runs one cell: one measured run (timed as well), then repetitions - 1 runs timed alone.
CellResult run_cell(const SweepGrid& grid, const CellSpec& cell);

nlohmann::json cell_json(const CellResult& cell);
// The inverse of cell_json (for shard merges and parallel workers); std::invalid_argument (via
// nlohmann's exceptions) when a field is missing.
CellResult cell_from_json(const nlohmann::json& j);

// The machine a sweep ran on: CPU model, cores, load average at the start, host name.
nlohmann::json describe_machine();

}  // namespace boxpile
