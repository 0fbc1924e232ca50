// The boxpile subcommands. Each registers its options on the CLI11 app and returns the exit code.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "boxpile/validation/cli/run_limits.hpp"
#include "boxpile/validation/cli/starts_options.hpp"
#include "boxpile/validation/scene/scene_generator.hpp"

namespace boxpile::cli {

// Exit codes: 0 success; 1 a run that went wrong (a non-finite state, our engine failing a check,
// anything unexpected); 2 bad input (a scene, a query, a flag, an unusable output location, an
// error inside ODE); 130 interrupted (the shell's 128 + SIGINT). kExitCodesHelp says it for --help.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInterrupted = 130;
inline constexpr const char* kExitCodesHelp =
    "Exit codes: 0 success; 1 a run that went wrong (a non-finite state, an engine failing); 2 bad input "
    "(scene, query, flag, unusable output location, an error inside ODE); 130 interrupted.";

// `boxpile contacts QUERY.json [--reduce] [--engines LIST] [--format table|json]`: the contact
// sets of one query from the registered detectors (and any answers saved in the file), with a
// diff of each against ours; a table on a terminal, JSON when piped or asked.
// `boxpile contacts --serve [--engine NAME]`: the line protocol of `boxpile conform` on stdin and
// stdout, answered by one detector.
struct ContactsOptions {
  std::string query;
  bool reduce = false;
  std::vector<std::string> engines;  // empty: the default set
  std::string format;                // "table" or "json"; empty: table on a terminal
  bool serve = false;
  std::string engine = "own";        // the detector that answers under --serve
  std::size_t max_input_bytes = limits::kDefaultMaxInputBytes;
};
void add_contacts_command(CLI::App& app, ContactsOptions& options);
int run_contacts(const ContactsOptions& options);

// `boxpile conform --collider CMD [--samples N] [--seed S] [--cases DIR] [--regimes LIST]
// [--timeout S] [--tolerance float32|float64|VALUE] [--keep N] [--progress] [--out DIR]`: judges
// an outside collider through the line protocol (docs/conform.md). Exit 0 within the gates, 1 not,
// 2 on bad input or a collider that dies, hangs or answers garbage.
struct ConformOptions {
  std::string collider;
  int samples = 1000;
  std::uint64_t seed = 1;
  std::string cases;                 // empty: the installed fixtures/contacts; "none": no cases
  std::vector<std::string> regimes;  // empty: all
  double timeout = 10.0;             // s per answer
  bool no_swap = false;
  std::string tolerance = "float64"; // float32, float64 or a relative tolerance
  int keep = 0;                      // failures saved per kind; add_conform_command sets kDefaultKeep
  bool progress = false;             // progress on stderr even when it is no terminal
  std::string report = "boxpile-conform";
  std::size_t max_input_bytes = limits::kDefaultMaxInputBytes;
};
void add_conform_command(CLI::App& app, ConformOptions& options);
int run_conform_command(const ConformOptions& options);

// `boxpile run SCENE.json --engine NAME [--dt DT] [--duration T] [--every K] [--out FILE.json]`:
// steps the scene in one engine; writes the recorded frames to FILE.json, or prints a summary.
// `--set [ENGINE.]KEY=VALUE` (repeatable) sets any setting of the engine (`boxpile settings`);
// `--iterations N` is a spelling of `--set iterations=N`, capped by --max-iterations.
struct RunOptions {
  std::string scene;
  std::string engine;
  std::optional<double> dt;        // s; the scene's when absent
  std::optional<double> duration;  // s; the scene's when absent
  int every = 10;                  // steps between recorded frames
  std::optional<std::string> out;  // absent: print a summary instead
  std::optional<int> iterations;   // --set iterations=N: ODE QuickStep's or Bullet's passes
  std::vector<std::string> set;    // "[ENGINE.]KEY=VALUE": any setting of the engine (boxpile settings)
  std::optional<int> threads;        // --threads: our engine's solver.threads; the scene's when absent
  bool profile = false;            // print where the steps' time went, stage by stage (ours)
  RunLimits limits;
};
void add_run_command(CLI::App& app, RunOptions& options);
int run_run(const RunOptions& options);

// `boxpile compare SCENE.json [--engines LIST] [--dt DT] [--duration T] [--report DIR]`: runs the
// scene in each engine and writes a report directory (report.json, report.md, SVG plots); prints
// a summary table. `boxpile` with no command runs it on the default scene.
struct CompareOptions {
  std::string scene;
  std::vector<std::string> engines;  // empty: the registry's compare list
  std::optional<double> dt;          // s; the scene's when absent
  std::optional<double> duration;    // s; the scene's when absent
  std::vector<std::string> set;      // "ENGINE.KEY=VALUE" (the prefix optional when one engine runs)
  std::optional<int> threads;        // --threads: our engine's solver.threads; the scene's when absent
  std::string report = "boxpile-report";
  RunLimits limits;
  StartsOptions starts;  // outcome statistics over perturbed starts
};
void add_compare_command(CLI::App& app, CompareOptions& options);
int run_compare_command(const CompareOptions& options);
// `boxpile view RUN.json|DIR [--out FILE]`: writes a replay page for a run file or a report
// directory (docs/viewer.md).
struct ViewOptions {
  std::string input;
  std::string out;  // empty: beside the input
  std::size_t max_input_bytes = limits::kDefaultMaxInputBytes;
};
void add_view_command(CLI::App& app, ViewOptions& options);
int run_view(const ViewOptions& options);

// The scene and report directory of `boxpile` with no command.
CompareOptions default_compare_options();

// `boxpile sweep GRID.json [--report DIR] [--shard I/N] [--jobs J]`: every cell of a grid (scenes,
// time steps, engines and their settings), cost against error, Pareto fronts; writes a report
// directory (sweep.json, sweep.csv, sweep.md, SVG plots). `boxpile sweep-merge DIR... --report OUT`
// merges the reports of shards. docs/sweeps.md.
struct SweepOptions {
  std::string grid;
  std::string report = "boxpile-sweep";
  std::string shard = "1/1";
  int jobs = 1;
  std::vector<std::string> merge_inputs;  // sweep-merge: shard report directories
  RunLimits limits;
};
void add_sweep_command(CLI::App& app, SweepOptions& options);
int run_sweep_command(const SweepOptions& options);
int run_sweep_merge_command(const SweepOptions& options);
// `boxpile settings`: every engine's sweepable settings as Markdown tables.
int run_settings_command();
// `boxpile stability [--engines LIST] [--scenes FILE|DIR ...] [--report DIR]`: the catalogue of
// hard scenes in each engine, every run judged by its scene's checks; a report directory.
struct StabilityOptions {
  std::vector<std::string> engines;  // empty: the registry's stability list
  std::vector<std::string> scenes;   // empty: the catalogue (fixtures/hard/)
  std::vector<std::string> set;      // "ENGINE.KEY=VALUE" (the prefix optional when one engine runs)
  std::optional<int> threads;        // --threads: our engine's solver.threads; the scene's when absent
  std::string report = "boxpile-stability";
  RunLimits limits;
  bool tune = false;          // --tune
  double tune_budget = 60.0;  // --tune-budget, s per cell
  double cell_time_limit = 0.0;  // --cell-time-limit, s of stepping per cell (0: none)
  std::string shard = "1/1";     // --shard I/N
  std::vector<std::string> merge_inputs;  // stability-merge: the shards' report directories
};
void add_stability_command(CLI::App& app, StabilityOptions& options);
int run_stability_command(const StabilityOptions& options);
// `boxpile stability-merge DIR... [--out DIR]`: the shards of one stability run as one report.
int run_stability_merge_command(const StabilityOptions& options);

// `boxpile scene KIND [--base N] [--width N] [--height N] [--nx N] [--ny N] [--layers N] [--count N]
// [--gap M] [--seed S] [--size M] [--mass KG] [--out FILE]`: a scene file of a pyramid, wall,
// tower, grid, heap or dominoes (validation/scene/scene_generator.hpp), checked by the loader, on stdout
// or into FILE.
struct SceneOptions {
  std::string kind;
  SceneSizes sizes;
  std::optional<std::string> out;  // absent: stdout
  const CLI::App* command = nullptr;  // to tell which size flags were given
};
void add_scene_command(CLI::App& app, SceneOptions& options);
int run_scene_command(const SceneOptions& options);

}  // namespace boxpile::cli
