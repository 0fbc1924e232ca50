// `boxpile accuracy`: what accuracy costs in time, measured against a truth (docs/accuracy.md).
// Per scene and engine, the error at a series of time steps (and iteration scales), its cost (µs
// of Engine::step() per simulated second, the least of the repetitions, interleaved), and the
// fitted order of convergence. The truth is the scene's own ("analytic", sim/scene.hpp's
// SceneTruth), or the same engine converged at finer steps with its iterations raised,
// Richardson-extrapolated where the order allows ("converged"), or each engine's own finest cell
// ("self").
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/accuracy/outcomes.hpp"
#include "boxpile/validation/accuracy/truth_meter.hpp"

namespace boxpile {

enum class TruthKind { Analytic, Converged, Self };
std::string_view truth_kind_name(TruthKind kind);

struct AccuracySettings {
  std::vector<std::string> engines;
  // The time steps, s (the scene's own time.dt is not used).
  std::vector<double> steps = {1.0 / 60.0, 1.0 / 120.0, 1.0 / 240.0, 1.0 / 480.0};
  // Each engine's iteration settings (iteration_settings) multiplied by each scale; 1: as given.
  std::vector<int> iteration_scales = {1};
  // Unset: "analytic" for a scene that states a truth, else "converged".
  std::optional<TruthKind> truth;
  std::map<std::string, nlohmann::json> engine_settings;  // {engine: {key: value}} (--set)
  int repetitions = 3;  // timed runs per cell, interleaved; the least counts
  // Outcome statistics over perturbed starts per scene, at the scene's own time step (none when
  // outcomes.starts is 0): for chaotic scenes, where the distribution of outcomes is the truth.
  OutcomeSettings outcomes;
  std::function<void(std::string_view what)> progress;  // before each run
};

// The truth a converged answer gives: every moving body's final position, with its uncertainty.
struct ConvergedTruth {
  std::vector<Vec3> positions;  // per body in scene order (fixed bodies: their start)
  double uncertainty = 0.0;     // m: the largest distance the answer may be off
  std::optional<double> order;  // the order seen between the reference steps, when it allowed Richardson
  bool extrapolated = false;
  std::vector<double> steps;    // s: the reference steps
  nlohmann::json settings;      // the iteration settings the references ran with
};

struct AccuracyCell {
  double dt = 0.0;
  int iteration_scale = 1;
  nlohmann::json settings = nlohmann::json::object();  // the engine settings it ran with (beyond defaults)
  long steps = 0;
  double error = 0.0;      // m: the largest distance of a body's final position from the truth's
  TruthMeasures measures;  // every measure against an analytic truth
  double us_per_simulated_second = 0.0;
  bool finite = true;      // false: a state went non-finite (error is then infinite)
};

struct AccuracyEngine {
  std::string engine;
  // The slope of log(error) against log(dt) over the cells of iteration scale 1 with an error
  // above rounding (at least two); unset when fewer.
  std::optional<double> order;
  // Against an analytic truth: the order of each measure the truth states (TruthMeasures'
  // names: position, velocity, orientation, trajectory, rebound), fitted alike.
  std::map<std::string, std::optional<double>> orders;
  std::vector<AccuracyCell> cells;
  std::optional<ConvergedTruth> converged;  // truth "converged": this engine's
};

struct AccuracyScene {
  std::string path;
  std::string name;
  TruthKind truth = TruthKind::Analytic;
  std::vector<AccuracyEngine> engines;
  std::optional<OutcomeStatistics> outcomes;  // when settings.outcomes.starts > 0
};

struct AccuracyResult {
  std::vector<AccuracyScene> scenes;
  AccuracySettings settings;
  nlohmann::json machine;
  double wall_seconds = 0.0;
};

// `settings` with the time step `dt` (s) written under the setting every engine shares
// (time_step_setting(), "dt"): the one place a cell's step is set. The registry writes it into
// the scene for every engine, as it does for a `--set ENGINE.dt=` anywhere else.
nlohmann::json settings_at_step(const nlohmann::json& settings, double dt);

// The settings of `engine` that count iterations or passes (an integer setting whose key ends in
// "iterations" or "passes", read by the scene's method, running at 1 or more), each multiplied by
// `scale` within its range, over `settings`; `settings` itself when scale is 1.
nlohmann::json iteration_settings(std::string_view engine, const Scene& scene, const nlohmann::json& settings,
                                  int scale);

// The least-squares slope of log(y) against log(x) over the points with y above `floor`; unset
// for fewer than two.
std::optional<double> fitted_order(const std::vector<double>& x, const std::vector<double>& y, double floor = 1e-12);

// Runs every scene in every engine (InputError for "analytic" on a scene without a truth).
AccuracyResult run_accuracy(const std::vector<Scene>& scenes, const AccuracySettings& settings);

inline constexpr const char* kAccuracyJson = "accuracy.json";
inline constexpr const char* kAccuracyMarkdown = "accuracy.md";

nlohmann::json accuracy_json(const AccuracyResult& result);
// accuracy.json, accuracy.md and the plots (error against dt, error against cost) into `dir`;
// what went wrong with the plots goes to `notes`.
void write_accuracy_report(const AccuracyResult& result, const std::filesystem::path& dir,
                           std::vector<std::string>& notes);
// The terminal summary: per scene and engine, the order and the error at each step.
std::string accuracy_summary(const AccuracyResult& result);

}  // namespace boxpile
