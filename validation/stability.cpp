#include "boxpile/validation/stability.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/run_loop.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The work of a cell for the time-left estimate: steps times bodies (contacts grow with bodies).
double work_of(const Scene& scene) {
  return static_cast<double>(step_count(scene.time)) * static_cast<double>(scene.bodies.size() + 1);
}

}  // namespace

int StabilityResult::own_failures() const {
  return static_cast<int>(
      std::count_if(cells.begin(), cells.end(), [](const StabilityCell& c) { return c.engine == "own" && !c.passed; }));
}

nlohmann::json StabilitySettings::settings_of(const std::string& engine) const {
  const auto it = engine_settings.find(engine);
  return it == engine_settings.end() ? nlohmann::json::object() : it->second;
}

StabilityCell run_stability_cell(const Scene& scene_file, std::string_view engine_name, const StabilitySettings& settings,
                                 const std::function<void(double)>& progress) {
  StabilityCell cell;
  cell.scene = scene_file.name;
  cell.engine = std::string(engine_name);
  const nlohmann::json given = settings.settings_of(std::string(engine_name));
  const std::unique_ptr<Engine> engine = make_engine(engine_name, scene_file, given);
  cell.settings = resolved_settings(engine_name, scene_file, given);
  // What the engine runs (its time step, and our solver's settings): the steps and the rulers.
  const Scene scene = scene_with_settings(engine_name, scene_file, given);
  const long steps = step_count(scene.time);
  const long every = steps_per_frame(scene.time.dt, settings.frame_rate);
  // Progress at most about a hundred times per cell.
  const long progress_every = std::max(1L, steps / 100);

  RunMonitor monitor(scene);
  RunHooks hooks;
  hooks.step = [&](const StepView& v) {
    monitor.observe(v.step, v.states);
    if (progress && v.step > 0 && (v.step % progress_every == 0 || v.step == steps))
      progress(static_cast<double>(v.step) / static_cast<double>(steps));
  };
  hooks.frame = [&](const StepView& v) {
    cell.t.push_back(v.t);
    cell.energy.push_back(monitor.energy());
    cell.kinetic.push_back(monitor.kinetic());
  };
  const RunLoopResult loop = run_loop(*engine, scene.time.dt, steps, every, hooks);
  cell.steps = loop.steps;
  cell.wall_seconds = loop.wall_seconds;
  cell.us_per_step = cell.steps > 0 ? 1e6 * loop.engine_seconds / static_cast<double>(cell.steps) : 0.0;
  if (loop.stopped) monitor.stopped_non_finite();
  cell.measures = monitor.measures();
  cell.checks = monitor.evaluate();
  cell.passed = all_passed(cell.checks);
  return cell;
}

StabilityResult run_stability(const std::vector<Scene>& scenes, const StabilitySettings& settings) {
  StabilityResult result;
  for (const std::string& name : settings.engines) {
    check_engine_name(name);
    if (std::find(result.engines.begin(), result.engines.end(), name) == result.engines.end())
      result.engines.push_back(name);
  }
  result.scenes = scenes;

  // Work per engine is measured separately: ODE and Bullet step much faster than ours.
  double total_work = 0.0;
  for (const Scene& s : scenes) total_work += work_of(s);
  std::vector<double> work_done(result.engines.size(), 0.0), seconds_spent(result.engines.size(), 0.0);
  const Clock::time_point run_start = Clock::now();
  const int total = static_cast<int>(scenes.size() * result.engines.size());
  int index = 0;
  for (const Scene& scene : scenes) {
    for (std::size_t e = 0; e < result.engines.size(); ++e) {
      const std::string& engine = result.engines[e];
      const Clock::time_point cell_start = Clock::now();
      auto report = [&](double fraction) {
        if (!settings.progress) return;
        const double elapsed = std::chrono::duration<double>(Clock::now() - run_start).count();
        const double in_cell = std::chrono::duration<double>(Clock::now() - cell_start).count();
        // Each engine's seconds per unit of work so far (this cell's part included) times the work
        // it has left; an engine not yet timed is assumed as fast as the slowest timed one.
        double remaining = 0.0, slowest = 0.0;
        for (std::size_t k = 0; k < result.engines.size(); ++k) {
          const double done = work_done[k] + (k == e ? fraction * work_of(scene) : 0.0);
          const double spent = seconds_spent[k] + (k == e ? in_cell : 0.0);
          if (done > 0.0) slowest = std::max(slowest, spent / done);
        }
        for (std::size_t k = 0; k < result.engines.size(); ++k) {
          const double done = work_done[k] + (k == e ? fraction * work_of(scene) : 0.0);
          const double spent = seconds_spent[k] + (k == e ? in_cell : 0.0);
          const double rate = done > 0.0 && spent > 0.0 ? spent / done : slowest;
          remaining += rate * (total_work - done);
        }
        settings.progress({scene.name, engine, index, total, fraction, elapsed, remaining});
      };
      result.cells.push_back(run_stability_cell(scene, engine, settings, report));
      work_done[e] += work_of(scene);
      seconds_spent[e] += std::chrono::duration<double>(Clock::now() - cell_start).count();
      ++index;
    }
  }
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - run_start).count();
  return result;
}

std::vector<std::string> catalogue_files(const std::vector<std::string>& paths) {
  std::vector<std::string> files;
  for (const std::string& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<std::string> in_dir;
      for (const fs::directory_entry& entry : fs::directory_iterator(p)) {
        if (entry.is_regular_file() && entry.path().extension() == ".json") in_dir.push_back(entry.path().string());
      }
      if (in_dir.empty()) throw InputError(p, "", "no scene files (*.json) in this directory");
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else if (fs::exists(p, ec)) {
      files.push_back(p);
    } else {
      throw InputError(p, "", "cannot open: No such file or directory");
    }
  }
  return files;
}

}  // namespace boxpile
