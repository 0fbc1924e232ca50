// The report of a sweep (or of merged shards): sweep.json, sweep.csv, sweep.md and SVG plots
// (fronts, convergence, error against iterations), each plot with its data and gnuplot script.
// docs/sweeps.md says how to read it.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/validation/sweep/sweep.hpp"

namespace boxpile {

// The report's data (fixed keys, and the file that marks a directory as a sweep report) and its
// page for people.
inline constexpr const char* kSweepJson = "sweep.json";
inline constexpr const char* kSweepMarkdown = "sweep.md";

struct SweepReport {
  std::string grid_file;
  nlohmann::json grid;             // the grid document as read
  int grid_cells = 0;              // cells in the whole grid
  std::vector<std::string> shards;  // "I/N" of each shard this report holds ("1/1": the whole grid)
  std::vector<nlohmann::json> machines;  // where each shard ran (describe_machine), with its shard
  std::vector<std::string> notes;  // e.g. cells that ran side by side
  std::vector<CellResult> cells;   // by index
};

// "key=value key=value" of a cell's settings, in key order.
std::string settings_label(const nlohmann::json& settings);
// Scenes and engines in the order of their first cell.
std::vector<std::string> report_scenes(const SweepReport& report);
std::vector<std::string> report_engines(const SweepReport& report);

// Fronts of one scene and error measure: for each engine the indices (into SweepReport::cells)
// of its front, and the front over all engines. Only stable cells with a value take part.
struct SceneFronts {
  std::map<std::string, std::vector<std::size_t>> by_engine;
  std::vector<std::size_t> overall;
};
SceneFronts fronts_of(const SweepReport& report, const std::string& scene, const std::string& measure);

nlohmann::json sweep_json(const SweepReport& report);
// Reads a sweep.json; InputError naming the file for anything missing or malformed.
SweepReport read_sweep_json(const std::string& path, std::size_t max_bytes = limits::kDefaultMaxInputBytes);

// For the terminal: how many cells, how many of them fail a check.
std::string sweep_summary(const SweepReport& report);

// Writes sweep.json, sweep.csv, sweep.md and the plots into `dir`. Plots that gnuplot cannot
// render leave their data and script, and a note in `notes`.
void write_sweep_report(const SweepReport& report, const std::filesystem::path& dir,
                        std::vector<std::string>& notes);

}  // namespace boxpile
