#include "boxpile/validation/stability/stability.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/run_loop.hpp"

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
  cell.settings = resolved_settings(engine_name, scene_file, given);
  // What the engine runs (its time step, and our solver's settings): the steps and the rulers.
  const Scene scene = scene_with_settings(engine_name, scene_file, given);
  const long steps = step_count(scene.time);
  const long every = steps_per_frame(scene.time.dt, settings.frame_rate);
  // Progress at most about a hundred times per cell.
  const long progress_every = std::max(1L, steps / 100);

  RunMonitor monitor(scene);
  long steps_seen = 0;
  RunHooks hooks;
  hooks.step = [&](const StepView& v) {
    steps_seen = v.step;
    monitor.observe(v.step, v.states);
    if (progress && v.step > 0 && (v.step % progress_every == 0 || v.step == steps))
      progress(static_cast<double>(v.step) / static_cast<double>(steps));
  };
  hooks.frame = [&](const StepView& v) {
    cell.t.push_back(v.t);
    cell.energy.push_back(monitor.energy());
    cell.kinetic.push_back(monitor.kinetic());
  };
  const Clock::time_point start = Clock::now();
  if (settings.cell_time_limit > 0.0) {
    hooks.stop = [&](const StepView&) {
      return std::chrono::duration<double>(Clock::now() - start).count() > settings.cell_time_limit;
    };
  }
  bool unfinished = false;
  try {
    const std::unique_ptr<Engine> engine = make_engine(engine_name, scene_file, given);
    const RunLoopResult loop = run_loop(*engine, scene.time.dt, steps, every, hooks);
    cell.steps = loop.steps;
    cell.out_of_time = unfinished = loop.cut_short;
    cell.wall_seconds = loop.wall_seconds;
    cell.us_per_step = cell.steps > 0 ? 1e6 * loop.engine_seconds / static_cast<double>(cell.steps) : 0.0;
    if (loop.stopped) monitor.stopped_non_finite();
  } catch (const EngineRefused& e) {
    // The engine could not take the scene, or a state it reached: the cell fails, judged on the
    // steps it ran, and the matrix goes on.
    cell.refused = e.what();
    cell.steps = steps_seen;
    cell.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    unfinished = true;
  }
  cell.measures = monitor.measures();
  cell.checks = monitor.evaluate();
  if (unfinished) {
    // The run is unfinished: a failed check of its own, beside the checks of the steps run.
    SceneCheckResult finished;
    finished.name = "finished";
    finished.value = static_cast<double>(cell.steps);
    finished.limit = static_cast<double>(steps);
    finished.at_least = true;
    finished.unit = "steps";
    cell.checks.insert(cell.checks.begin(), finished);
  }
  cell.passed = all_passed(cell.checks);
  return cell;
}

double StabilityCell::us_per_sim_s() const {
  const double dt = settings.contains("dt") && settings["dt"].is_number() ? settings["dt"].get<double>() : 0.0;
  return dt > 0.0 ? us_per_step / dt : 0.0;
}

double miss_factor(const SceneCheckResult& c) {
  if (c.passed) return 0.0;
  const double over = c.at_least ? c.limit / c.value : c.value / c.limit;
  return std::isfinite(over) && over > 0.0 ? std::max(1.0, over) : std::numeric_limits<double>::infinity();
}

double worst_miss(const std::vector<SceneCheckResult>& checks) {
  double worst = 0.0;
  for (const SceneCheckResult& c : checks) worst = std::max(worst, miss_factor(c));
  return worst;
}

namespace {

// The ladder's rungs: dt / 2^k with the solver's passes times 2^k (at most dt0 / 2^kMostRungs).
constexpr int kMostRungs = 8;
// A rung that does not shrink the worst miss below this fraction of the best so far does not count as
// an improvement (rounding of the measures).
constexpr double kImproves = 0.99;

// The first of the engine's settings that counts solver passes, and the sleeping switch.
std::optional<SettingInfo> setting_named(std::string_view engine, std::initializer_list<std::string_view> keys) {
  const std::vector<SettingInfo> all = engine_settings(engine);
  for (std::string_view key : keys)
    for (const SettingInfo& s : all)
      if (s.key == key) return s;
  return std::nullopt;
}

TunedCell tuned_from(const StabilityCell& cell, const nlohmann::json& tried, int attempts) {
  TunedCell t;
  t.passed = cell.passed;
  t.settings = tried;
  t.us_per_sim_s = cell.us_per_sim_s();
  t.checks = cell.checks;
  t.attempts = attempts;
  return t;
}

}  // namespace

TunedCell tune_cell(const Scene& scene, std::string_view engine, const StabilitySettings& settings,
                    const StabilityCell& at_given, const std::function<void(std::string_view)>& attempt) {
  using json = nlohmann::json;
  const Clock::time_point start = Clock::now();
  const std::string name(engine);
  TunedCell best = tuned_from(at_given, json::object(), 1);
  if (at_given.passed) return best;
  double best_miss = worst_miss(at_given.checks);
  const json given = settings.settings_of(name);
  const double dt0 = at_given.settings.at("dt").get<double>();
  // The passes the cell ran with ("own" on a penalty scene runs no contact passes: none then).
  std::optional<SettingInfo> passes = setting_named(engine, {"iterations", "contact_passes"});
  if (passes && !(at_given.settings.contains(passes->key) && at_given.settings[passes->key].is_number_integer())) {
    passes.reset();
  }
  const int passes0 = passes ? at_given.settings[passes->key].get<int>() : 0;
  auto spent = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  // One attempt: the given settings with `tried` over them; true when it passed.
  auto run = [&](const json& tried, const std::string& label) {
    StabilitySettings one = settings;
    json all = given;
    for (const auto& [k, v] : tried.items()) all[k] = v;
    one.engine_settings[name] = all;
    if (attempt) attempt(label);
    const StabilityCell cell = run_stability_cell(scene, engine, one);
    ++best.attempts;
    const double miss = worst_miss(cell.checks);
    const bool better = cell.passed || miss < kImproves * best_miss;
    if (better) {
      const int attempts = best.attempts;
      best = tuned_from(cell, tried, attempts);
      best_miss = miss;
    }
    return better;
  };

  json closest = json::object();
  int flat = 0;
  for (int k = 1; k <= kMostRungs && flat < 2; ++k) {
    if (spent() >= settings.tune_budget) {
      best.out_of_budget = true;
      return best;
    }
    const double scale = std::ldexp(1.0, k);
    const double dt = dt0 / scale;
    if (!(dt > 0.0) || static_cast<double>(step_count(dt, scene.time.duration)) >
                           static_cast<double>(settings.max_steps)) {
      break;
    }
    json tried = {{"dt", dt}};
    std::string label = "dt/" + std::to_string(static_cast<long>(scale));
    if (passes) {
      const int n = static_cast<int>(std::min(passes->max, passes0 * scale));
      tried[passes->key] = n;
      label += ", " + passes->key + " " + std::to_string(n);
    }
    if (run(tried, label)) {
      flat = 0;
      closest = tried;
      if (best.passed) return best;
    } else {
      ++flat;
    }
  }
  // The engine's own knob for resting scenes, on the closest rung.
  if (const std::optional<SettingInfo> sleep = setting_named(engine, {"auto_disable", "sleeping"})) {
    if (spent() >= settings.tune_budget) {
      best.out_of_budget = true;
      return best;
    }
    json tried = closest;
    tried[sleep->key] = true;
    run(tried, (closest.empty() ? std::string("the given settings") : "the closest rung") + ", " + sleep->key);
  }
  return best;
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
        settings.progress({scene.name, engine, index, total, fraction, elapsed, remaining, {}});
      };
      result.cells.push_back(run_stability_cell(scene, engine, settings, report));
      if (settings.tune) {
        StabilityCell& cell = result.cells.back();
        cell.tuned = tune_cell(scene, engine, settings, cell, [&](std::string_view label) {
          if (!settings.progress) return;
          const double elapsed = std::chrono::duration<double>(Clock::now() - run_start).count();
          // Each cell left may take up to its budget; the cells so far took their mean.
          const double mean = elapsed / (index + 1);
          const double left = static_cast<double>(total - index - 1) * std::min(mean, settings.tune_budget);
          settings.progress({scene.name, engine, index, total, 1.0, elapsed, left, label});
        });
      }
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
