#include "boxpile/validation/sweep/sweep.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "boxpile/sim/solver/impulse_method.hpp"
#include "boxpile/sim/solver/step_context.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/core/run_loop.hpp"

namespace boxpile {
namespace {

// Sums our solver's per-pass residuals over the steps of a run.
class ConvergenceMeter {
 public:
  explicit ConvergenceMeter(const SolverSettings& s)
      : collision_(static_cast<std::size_t>(s.collision_passes), 0.0),
        contact_(static_cast<std::size_t>(s.contact_passes), 0.0),
        shock_(static_cast<std::size_t>(s.shock_passes), 0.0) {}

  void add(const ImpulseStepStats& st) {
    if (st.collision_passes_used > 0) {
      accumulate(collision_, st.collision_residual.data(), st.collision_passes_used);
      ++collision_steps_;
    }
    if (st.contact_passes_used > 0) {
      accumulate(contact_, st.contact_residual.data(), st.contact_passes_used);
      ++contact_steps_;
      after_shock_ += st.residual_after_shock;
      if (st.shock_pass_count > 0) {
        accumulate(shock_, st.shock_change.data(), st.shock_pass_count);
        ++shock_steps_;
      }
      shock_passes_ += st.shock_passes_used;
    }
  }

  // Whether the run's engine steps with the impulse method (whose record this is).
  void applies_to_run() { applies_ = true; }
  bool applies() const { return applies_; }

  Convergence mean() const {
    Convergence c;
    c.collision = divided(collision_, collision_steps_);
    c.contact = divided(contact_, contact_steps_);
    c.shock = divided(shock_, shock_steps_);
    c.after_shock = contact_steps_ > 0 ? after_shock_ / static_cast<double>(contact_steps_) : 0.0;
    c.shock_passes = contact_steps_ > 0 ? shock_passes_ / static_cast<double>(contact_steps_) : 0.0;
    return c;
  }

 private:
  // Passes after the last one used count with the residual the loop stopped at.
  static void accumulate(std::vector<double>& sum, const double* residual, int used) {
    for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += residual[std::min<std::size_t>(k, static_cast<std::size_t>(used) - 1)];
  }
  static std::vector<double> divided(std::vector<double> sum, long n) {
    for (double& x : sum) x = n > 0 ? x / static_cast<double>(n) : 0.0;
    return sum;
  }

  std::vector<double> collision_, contact_, shock_;
  long collision_steps_ = 0, contact_steps_ = 0, shock_steps_ = 0;
  double after_shock_ = 0.0, shock_passes_ = 0.0;
  bool applies_ = false;
};

// One run of the cell: the seconds spent in Engine::step() alone (the engine's own, when it reports them). The measured run (given a
// monitor) feeds the catalogue's monitor every state, and our solver's statistics to `meter`
// when given; reading them is outside the timed steps.
double cell_run(const EngineConfig& config, const std::string& engine, long steps, RunMonitor* monitor,
                ConvergenceMeter* meter) {
  const std::unique_ptr<Engine> e = make_engine(engine, config.scene, config.settings);
  e->report_contacts(false);  // the measures read the states alone
  RunHooks hooks;
  if (monitor) {
    hooks.step = [&](const StepView& v) {
      monitor->observe(v.step, v.states);
      if (!meter) return;
      if (const auto* m = dynamic_cast<const ImpulseMethod*>(v.engine.solver_method())) {
        meter->applies_to_run();
        if (v.step > 0) meter->add(m->last_step_stats());
      }
    };
  }
  const RunLoopResult loop = run_loop(*e, config.scene.time.dt, steps, steps, hooks);
  if (monitor && loop.stopped) monitor->stopped_non_finite();
  return loop.engine_seconds;
}

std::string first_line_with(const std::string& file, const std::string& prefix) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) {
      const std::size_t colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "";
}

nlohmann::json convergence_json(const Convergence& c) {
  return {{"collision", c.collision}, {"contact", c.contact}, {"shock", c.shock}, {"after_shock", c.after_shock},
          {"shock_passes", c.shock_passes}};
}

}  // namespace

EngineConfig cell_config(const SweepGrid& grid, const CellSpec& cell) {
  EngineConfig config{grid.scenes[static_cast<std::size_t>(cell.scene)].scene, {}};
  config.scene.time.dt = cell.dt;
  apply_settings(cell.engine, cell.settings, config);
  // Our engine's settings are the scene's: the rulers below read the scene it runs.
  config.scene = scene_with_settings(cell.engine, config.scene, config.settings);
  return config;
}

CellResult run_cell(const SweepGrid& grid, const CellSpec& cell) {
  const GridScene& gs = grid.scenes[static_cast<std::size_t>(cell.scene)];
  const EngineConfig config = cell_config(grid, cell);

  CellResult r;
  r.spec = cell;
  r.scene = gs.path;
  r.scene_name = config.scene.name;
  r.steps = step_count(config.scene.time);

  // The per-pass residuals are the impulse method's own record: a run whose engine steps with it
  // has them.
  RunMonitor monitor(config.scene);
  ConvergenceMeter meter(config.scene.solver);
  double least = cell_run(config, cell.engine, r.steps, &monitor, &meter);
  r.measures = cell_measures(config.scene, monitor.measures(), monitor.evaluate());
  if (meter.applies()) r.convergence = meter.mean();
  for (r.timed_runs = 1; r.timed_runs < grid.repetitions; ++r.timed_runs) {
    least = std::min(least, cell_run(config, cell.engine, r.steps, nullptr, nullptr));
  }
  r.us_per_step = r.steps > 0 ? 1e6 * least / static_cast<double>(r.steps) : 0.0;
  r.us_per_simulated_second = r.us_per_step / cell.dt;
  return r;
}

nlohmann::json cell_json(const CellResult& c) {
  nlohmann::json checks = nlohmann::json::array();
  for (const SceneCheckResult& k : c.measures.checks) {
    checks.push_back({{"name", k.name}, {"value", k.value}, {"limit", k.limit}, {"at_least", k.at_least},
                      {"passed", k.passed}, {"unit", k.unit}, {"key", k.key}});
  }
  nlohmann::json j = {{"index", c.spec.index},
                      {"scene", c.scene},
                      {"scene_name", c.scene_name},
                      {"engine", c.spec.engine},
                      {"settings", c.spec.settings},
                      {"dt", c.spec.dt},
                      {"steps", c.steps},
                      {"timed_runs", c.timed_runs},
                      {"jobs", c.jobs},
                      {"us_per_step", c.us_per_step},
                      {"us_per_simulated_second", c.us_per_simulated_second},
                      {"error", c.measures.error},
                      {"stable", c.measures.stable},
                      {"passed", c.measures.passed},
                      {"checks", checks}};
  if (c.convergence) j["convergence"] = convergence_json(*c.convergence);
  return j;
}

CellResult cell_from_json(const nlohmann::json& j) {
  CellResult c;
  c.spec.index = j.at("index").get<int>();
  c.spec.engine = j.at("engine").get<std::string>();
  c.spec.settings = j.at("settings");
  c.spec.dt = j.at("dt").get<double>();
  c.scene = j.at("scene").get<std::string>();
  // Reports written before cells carried the scene's name: its file name stands for it.
  c.scene_name = j.contains("scene_name") ? j.at("scene_name").get<std::string>()
                                          : std::filesystem::path(c.scene).stem().string();
  c.steps = j.at("steps").get<long>();
  c.timed_runs = j.at("timed_runs").get<int>();
  c.jobs = j.value("jobs", 1);
  c.us_per_step = j.at("us_per_step").get<double>();
  c.us_per_simulated_second = j.at("us_per_simulated_second").get<double>();
  c.measures.error = j.at("error");
  c.measures.stable = j.at("stable").get<bool>();
  c.measures.passed = j.at("passed").get<bool>();
  for (const nlohmann::json& k : j.at("checks")) {
    c.measures.checks.push_back({k.at("name").get<std::string>(),
                                 k.at("value").is_null() ? std::nan("") : k.at("value").get<double>(),
                                 k.at("limit").get<double>(), k.at("at_least").get<bool>(), k.at("passed").get<bool>(),
                                 k.at("unit").get<std::string>(), k.value("key", std::string()), std::string()});
  }
  if (j.contains("convergence")) {
    const nlohmann::json& v = j.at("convergence");
    c.convergence = Convergence{v.at("collision").get<std::vector<double>>(), v.at("contact").get<std::vector<double>>(),
                                v.at("shock").get<std::vector<double>>(), v.at("after_shock").get<double>(),
                                v.at("shock_passes").get<double>()};
  }
  return c;
}

nlohmann::json describe_machine() {
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  double load[3] = {0, 0, 0};
  std::ifstream loadavg("/proc/loadavg");
  loadavg >> load[0] >> load[1] >> load[2];
  return {{"cpu", first_line_with("/proc/cpuinfo", "model name")},
          {"cores", std::thread::hardware_concurrency()},
          {"host", host},
          {"load_average", {load[0], load[1], load[2]}}};
}

}  // namespace boxpile
