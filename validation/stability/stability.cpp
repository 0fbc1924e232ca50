#include "boxpile/validation/stability/stability.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/reference/process/process_engine.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/run_loop.hpp"
#include "boxpile/validation/stability/tune_moves.hpp"

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
    engine->report_contacts(false);  // the checks read the states alone
    const RunLoopResult loop = run_loop(*engine, scene.time.dt, steps, every, hooks);
    cell.steps = loop.steps;
    cell.out_of_time = unfinished = loop.cut_short;
    cell.wall_seconds = loop.wall_seconds;
    cell.us_per_step = cell.steps > 0 ? 1e6 * loop.engine_seconds / static_cast<double>(cell.steps) : 0.0;
    if (loop.stopped) monitor.stopped_non_finite();
  } catch (const EngineRefused& e) {
    // The engine could not take the scene, or a state it reached: the cell fails, judged on the
    // steps it ran, and the matrix goes on. (An engine that breaks its protocol is an error of
    // the whole command, exit 2, except inside --tune's search: see tune_cell.)
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
// Rungs tried above a passing cell's step: dt * 2, dt * 4.
constexpr int kCoarserRungs = 2;
// A rung that does not shrink the worst miss below this fraction of the best so far does not count as
// an improvement (rounding of the measures).
constexpr double kImproves = 0.99;

// The engine's setting of the first of `keys` it has (the one that counts solver passes, the
// sleeping switch, a tune move's key).
std::optional<SettingInfo> setting_named(std::string_view engine, std::initializer_list<std::string_view> keys) {
  const std::vector<SettingInfo> all = engine_settings(engine);
  for (std::string_view key : keys)
    for (const SettingInfo& s : all)
      if (s.key == key) return s;
  return std::nullopt;
}

// Every key a move sets is one of the engine's settings: a move the engine cannot take is a
// defect of the moves table, not of the user's input.
void check_tune_moves(std::string_view engine, const std::vector<TuneMove>& moves) {
  for (const TuneMove& m : moves)
    for (const auto& item : m.settings.items())
      if (!setting_named(engine, {item.key()}))
        throw std::logic_error("tune move \"" + m.label + "\" of " + std::string(engine) + " sets \"" + item.key() +
                               "\", which is not one of its settings");
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
  double best_miss = worst_miss(at_given.checks);
  const json given = settings.settings_of(name);
  const double dt0 = at_given.settings.at("dt").get<double>();
  const std::vector<TuneMove> moves = tune_moves(engine, scene, dt0);
  check_tune_moves(engine, moves);
  // The passes the cell ran with ("own" on a penalty scene runs no contact passes: none then).
  std::optional<SettingInfo> passes = setting_named(engine, {"iterations", "contact_passes"});
  if (passes && !(at_given.settings.contains(passes->key) && at_given.settings[passes->key].is_number_integer())) {
    passes.reset();
  }
  const int passes0 = passes ? at_given.settings[passes->key].get<int>() : 0;
  auto spent = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  auto out_of_budget = [&] {
    if (spent() < settings.tune_budget) return false;
    best.out_of_budget = true;
    return true;
  };
  // One attempt: the given settings with `tried` over them. It replaces the best so far when it is
  // better: while nothing passed, when it passes or its worst miss shrinks; once something
  // passed, when it passes at less cost.
  auto run = [&](const json& tried, const std::string& label) {
    StabilitySettings one = settings;
    // The budget bounds the search's wall time: an attempt stops where the budget ends (and
    // fails its "finished" check then), however slow the engine is on the scene.
    const double left = std::max(settings.tune_budget - spent(), 1e-3);
    one.cell_time_limit = settings.cell_time_limit > 0.0 ? std::min(settings.cell_time_limit, left) : left;
    json all = given;
    for (const auto& [k, v] : tried.items()) all[k] = v;
    one.engine_settings[name] = all;
    if (attempt) attempt(label);
    StabilityCell cell;
    try {
      cell = run_stability_cell(scene, engine, one);
    } catch (const EngineProtocolError& e) {
      // A process engine that gives no answer within --engine-timeout on a finer rung than the
      // user asked for (MuJoCo 3.14's 385-box pyramid at dt/4 took over 30 s a step) ends that
      // attempt, not the catalogue run.
      cell.refused = e.what();
    }
    // An attempt the engine refused or left unanswered is no candidate, as one past the budget is not.
    const bool no_candidate = cell.out_of_time || !cell.refused.empty();
    ++best.attempts;
    const double miss = worst_miss(cell.checks);
    const bool better = !no_candidate && (best.passed ? cell.passed && cell.us_per_sim_s() < best.us_per_sim_s
                                                      : cell.passed || miss < kImproves * best_miss);
    if (better) {
      const int attempts = best.attempts;
      best = tuned_from(cell, tried, attempts);
      best_miss = miss;
    }
    if (cell.out_of_time) best.out_of_budget = true;
    return std::make_pair(better, cell.passed && !no_candidate);
  };
  auto with = [](json base, const json& more) {
    for (const auto& [k, v] : more.items()) base[k] = v;
    return base;
  };

  if (at_given.passed) {
    // Passing as given: a coarser step (cheaper), then the moves that are cheaper by themselves.
    for (int k = 1; k <= kCoarserRungs; ++k) {
      if (out_of_budget()) return best;
      const double scale = std::ldexp(1.0, k);
      if (!run({{"dt", dt0 * scale}}, "dt*" + std::to_string(static_cast<long>(scale))).second) break;
    }
    for (const TuneMove& m : moves) {
      if (!m.cheaper) continue;
      if (out_of_budget()) return best;
      run(with(best.settings, m.settings), m.label);
    }
    return best;
  }

  // Failing as given: the engine's own knobs one by one, cheapest first, at the given step.
  json base = json::object();
  bool ladder_passes = true;
  for (const TuneMove& m : moves) {
    if (out_of_budget()) return best;
    if (run(m.settings, m.label).first) {
      base = m.settings;
      ladder_passes = m.ladder_passes;
      if (best.passed) return best;
    }
  }
  if (!ladder_passes) passes.reset();

  // Then the ladder, from the best knob found.
  json closest = base;
  int flat = 0;
  for (int k = 1; k <= kMostRungs && flat < 2; ++k) {
    if (out_of_budget()) return best;
    const double scale = std::ldexp(1.0, k);
    const double dt = dt0 / scale;
    if (!(dt > 0.0) || static_cast<double>(step_count(dt, scene.time.duration)) >
                           static_cast<double>(settings.max_steps)) {
      break;
    }
    json tried = with(base, {{"dt", dt}});
    std::string label = "dt/" + std::to_string(static_cast<long>(scale));
    if (passes) {
      const int n = static_cast<int>(std::min(passes->max, passes0 * scale));
      tried[passes->key] = n;
      label += ", " + passes->key + " " + std::to_string(n);
    }
    if (run(tried, label).first) {
      flat = 0;
      closest = tried;
      if (best.passed) return best;
    } else {
      ++flat;
    }
  }
  // The engine's own knob for resting scenes, on the closest rung.
  if (const std::optional<SettingInfo> sleep = setting_named(engine, {"auto_disable", "sleeping"})) {
    if (out_of_budget()) return best;
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

  const Clock::time_point run_start = Clock::now();
  result.cells_total = static_cast<int>(scenes.size() * result.engines.size());
  const Shard& shard = settings.shard;
  if (shard.count > 1) result.shards = {std::to_string(shard.index) + "/" + std::to_string(shard.count)};
  auto in_this_shard = [&](int position) { return position % shard.count == shard.index - 1; };
  // Work per engine is measured separately (ODE and Bullet step much faster than ours), over the
  // cells of this shard.
  const std::size_t engines = result.engines.size();
  std::vector<double> total_work(engines, 0.0), work_done(engines, 0.0), seconds_spent(engines, 0.0);
  int total = 0;
  for (int k = 0; k < result.cells_total; ++k) {
    if (!in_this_shard(k)) continue;
    ++total;
    total_work[static_cast<std::size_t>(k) % engines] += work_of(scenes[static_cast<std::size_t>(k) / engines]);
  }
  int index = 0, position = -1;
  for (const Scene& scene : scenes) {
    for (std::size_t e = 0; e < result.engines.size(); ++e) {
      if (!in_this_shard(++position)) continue;
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
          remaining += rate * (total_work[k] - done);
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
