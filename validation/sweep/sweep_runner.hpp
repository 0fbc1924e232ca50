// Runs a list of sweep cells, in this process or in parallel worker processes (fork), with
// progress after each cell.
#pragma once

#include <filesystem>
#include <functional>
#include <vector>

#include "boxpile/validation/sweep/sweep.hpp"

namespace boxpile {

struct SweepProgress {
  int done = 0;
  int total = 0;
  double elapsed = 0.0;  // s
  const CellResult* last = nullptr;  // the cell just finished (in-process runs only)
};

struct SweepRunOptions {
  // Worker processes; 1 runs every cell in this process. Workers take cells in turn (cell k of the
  // list goes to worker k mod jobs) and each writes its cells as JSON into `work_dir`.
  int jobs = 1;
  std::filesystem::path work_dir;  // needed when jobs > 1
  // Called after each cell (and, with workers, whenever the count of finished cells changes).
  // It may throw to stop the sweep; workers are then stopped as well.
  std::function<void(const SweepProgress&)> progress;
};

// The results of `cells`, in their order. Throws std::runtime_error when a worker fails.
std::vector<CellResult> run_sweep_cells(const SweepGrid& grid, const std::vector<CellSpec>& cells,
                                        const SweepRunOptions& options);

}  // namespace boxpile
