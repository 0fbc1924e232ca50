// A sweep grid (docs/sweeps.md): scenes, time steps, and for each engine the product of its
// settings' values. Loading checks everything (files, engines, settings, values) before any cell
// runs; the cells are listed in one fixed order, so that a shard is the same on every machine.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

struct GridScene {
  std::string path;  // as the grid names it (relative to the grid file)
  Scene scene;       // loaded; duration overridden by the grid's
};

// One engine of a grid: each setting with the values to sweep (the engine's cells are their
// product).
struct GridEngine {
  std::string name;
  std::vector<std::pair<std::string, std::vector<nlohmann::json>>> axes;  // sorted by key
  // The values of the axis `key`; null when the engine sweeps no such setting.
  const std::vector<nlohmann::json>* axis(std::string_view key) const {
    for (const auto& [k, values] : axes)
      if (k == key) return &values;
    return nullptr;
  }
};

struct SweepGrid {
  std::string source;         // the grid file
  nlohmann::json document;    // the grid as read, for the report
  std::vector<GridScene> scenes;
  std::vector<double> dt;     // s; empty: each scene's own
  std::optional<double> duration;  // s; each scene's own when absent
  int repetitions = 3;        // timed runs per cell; the least counts
  std::vector<GridEngine> engines;
};

// Loads and checks a grid; InputError naming the file and the key for anything wrong (a missing
// scene file, an unknown engine or setting, a value out of range).
SweepGrid load_grid(const std::string& path, const LoadLimits& caps = {});

// One cell: a scene in one engine with one value of each setting, at one time step.
struct CellSpec {
  int index = 0;  // position in the grid's order (shards and merges go by it)
  int scene = 0;  // into SweepGrid::scenes
  std::string engine;
  nlohmann::json settings = nlohmann::json::object();  // {key: value}
  double dt = 0.0;  // s
};

// Every cell, in the grid's order: scenes, then engines (by name), then settings (the last key
// varying fastest), then time steps. An engine that sweeps its own "dt" (the time step, every
// engine's setting) takes its cells' time steps from it, and the grid's "dt" is refused beside it.
std::vector<CellSpec> grid_cells(const SweepGrid& grid);

// A deterministic 1/count of the cells: shard `index` (1-based) holds the cells whose position k
// has k mod count = index - 1.
struct Shard {
  int index = 1;
  int count = 1;
};
// "I/N" with 1 <= I <= N; std::invalid_argument otherwise.
Shard parse_shard(const std::string& text);
bool in_shard(const CellSpec& cell, const Shard& shard);

}  // namespace boxpile
