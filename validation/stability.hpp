// `boxpile stability`: every scene of a catalogue (default fixtures/hard/) run in every engine,
// each run judged by the scene's checks (validation/stability_checks.hpp). The report
// (stability.json, stability.md, plots of the failing cells) is in validation/stability_report.hpp;
// docs/stability.md describes both.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <map>
#include <optional>

#include <nlohmann/json.hpp>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/stability_checks.hpp"
#include "boxpile/validation/sweep_grid.hpp"

namespace boxpile {

// Where the catalogue run is, for a progress display with the time left.
struct StabilityProgress {
  std::string_view scene;
  std::string_view engine;
  int index = 0;  // cell, 0-based
  int total = 0;
  double fraction = 0.0;         // of this cell's steps
  double elapsed = 0.0;          // s since the catalogue started
  double remaining = 0.0;        // s, estimated (0 until the first cell has run a while)
  std::string_view tuning;       // with --tune, the attempt running ("dt/4, iterations 80"); empty else
};

struct StabilitySettings {
  // The engines run, in order (the registry's stability list by default).
  std::vector<std::string> engines = default_engines(&DefaultLists::stability);
  // Settings {key: value} per engine, each checked against the engine's table (parse_set_options);
  // an engine left out runs at its defaults.
  std::map<std::string, nlohmann::json> engine_settings;
  // The settings given for `engine` ({} when none).
  nlohmann::json settings_of(const std::string& engine) const;
  double frame_rate = 30.0;  // 1/s: energy and kinetic energy recorded for the plots
  std::function<void(const StabilityProgress&)> progress;
  // `--tune`: after each cell at the given settings, search for the cheapest that passes every
  // check (tune_cell), for at most `tune_budget` s of wall time per cell and runs of at most
  // `max_steps` steps.
  bool tune = false;
  double tune_budget = 60.0;
  // `--cell-time-limit`: s of wall time a cell may step (0: no limit). A cell past it stops there
  // and fails its "finished" check (steps run against the scene's); its other checks judge the
  // steps that ran. For engines whose cost grows too fast for a scene (DART's pivoting LCP on a
  // pile), so that the catalogue still ends and says so.
  double cell_time_limit = 0.0;
  long max_steps = 10'000'000;
  // `--shard I/N`: only the cells whose position k (scene by scene, the engines in order within
  // each) has k mod N = I - 1; `boxpile stability-merge` joins the shards' reports.
  Shard shard;
};

// The cheapest settings `stability --tune` found for one cell.
struct TunedCell {
  bool passed = false;
  // The settings beside the given ones that were run ({} when the given ones pass): given back
  // through `--set ENGINE.KEY=VALUE` they reproduce the verdict.
  nlohmann::json settings = nlohmann::json::object();
  double us_per_sim_s = 0.0;  // µs of stepping per simulated second
  std::vector<SceneCheckResult> checks;
  int attempts = 0;       // runs made, the given settings' included
  bool out_of_budget = false;  // the search stopped at the budget, not at a pass or a dead end
};

// One scene in one engine.
struct StabilityCell {
  std::string scene;
  std::string engine;
  // Every setting's value the engine ran with on this scene, defaults included.
  nlohmann::json settings = nlohmann::json::object();
  bool passed = false;
  std::vector<SceneCheckResult> checks;
  RunMeasures measures;
  long steps = 0;  // steps run (fewer than the scene's when a state became NaN or time ran out)
  bool out_of_time = false;  // stopped at settings.cell_time_limit
  // The engine refused the scene or a state it reached (EngineRefused: MuJoCo's or ODE's error),
  // its message; empty when it ran. Such a cell fails its "finished" check.
  std::string refused;
  double us_per_step = 0.0;
  double wall_seconds = 0.0;  // stepping only
  std::vector<double> t, energy, kinetic;  // recorded frames, s and J
  double us_per_sim_s() const;  // µs of stepping per simulated second
  std::optional<TunedCell> tuned;  // with --tune
};

struct StabilityResult {
  std::vector<std::string> engines;
  std::vector<Scene> scenes;
  std::vector<StabilityCell> cells;  // scene by scene, engines in order within each
  // The scenes were the whole catalogue (fixtures/hard/): only then do the reports speak of "the
  // hard scenes".
  bool whole_catalogue = false;
  double wall_seconds = 0.0;         // the whole run (a merge: the sum of its shards')
  // "I/N" of each shard this result holds (empty for a run without --shard), and how many cells
  // the whole run has (scenes times engines), which a merge must hold all of.
  std::vector<std::string> shards;
  int cells_total = 0;
  // How many cells of our engine ("own") failed; whether none did.
  int own_failures() const;
  bool own_passed() const { return own_failures() == 0; }
};

// Runs one scene in one engine; `progress` gets the fraction of the steps done.
StabilityCell run_stability_cell(const Scene& scene, std::string_view engine, const StabilitySettings& settings,
                                 const std::function<void(double)>& progress = {});

// How far a failed check missed its limit, as a factor >= 1 (value / limit, or limit / value
// for an at-least check; infinite for a check that cannot be compared); 0 for a passed one. The
// worst over a run's checks ranks attempts.
double miss_factor(const SceneCheckResult& check);
double worst_miss(const std::vector<SceneCheckResult>& checks);

// The search of `stability --tune` for one scene and engine, from `at_given` (the cell at the
// given settings). A failing cell: first the engine's own knobs (tune_moves.hpp) one at a time,
// cheapest first, at the given step; then, from the best of them, a ladder, the time step halved
// and the engine's solver passes ("iterations", else "contact_passes") doubled together until
// every check passes, the worst miss stops shrinking for two rungs, the steps pass
// settings.max_steps or the budget is spent; then, if none passed, the engine's sleeping switch
// ("auto_disable", "sleeping") on the closest rung. Returns the first passing attempt (each step
// of the search costs more than the one before) or, when none passed, the closest one. A passing
// cell: a coarser step (dt * 2, dt * 4) and the moves that are cheaper in themselves, kept only
// where they still pass at less cost.
TunedCell tune_cell(const Scene& scene, std::string_view engine, const StabilitySettings& settings,
                    const StabilityCell& at_given, const std::function<void(std::string_view)>& attempt = {});

// Runs every scene in every engine (UnknownEngine for a name not available, before any run);
// the result's whole_catalogue is left to the caller.
StabilityResult run_stability(const std::vector<Scene>& scenes, const StabilitySettings& settings);

// The scene files named by `paths`: a file as it is, a directory's *.json files sorted by name.
// Throws InputError for a path that does not exist or a directory without scenes.
std::vector<std::string> catalogue_files(const std::vector<std::string>& paths);

}  // namespace boxpile
