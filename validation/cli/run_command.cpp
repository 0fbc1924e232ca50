#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/solver/step_context.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/validation/cli/activity.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/interruptible.hpp"
#include "boxpile/validation/cli/progress.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/core/format_number.hpp"
#include "boxpile/validation/core/json_output.hpp"
#include "boxpile/validation/core/output_safety.hpp"
#include "boxpile/sim/world.hpp"
#include "boxpile/validation/core/recording.hpp"
#include "boxpile/validation/core/run_loop.hpp"
#include "boxpile/validation/rulers/state_meter.hpp"
#include "boxpile/validation/stability/scene_checks.hpp"

namespace boxpile::cli {
namespace {

// Up to this many bodies the human summary lists each one; above it, the extremes only.
constexpr std::size_t kSummaryBodyLimit = 10;


// Runs at least this long show their progress on stderr.
constexpr long kProgressMinSteps = 100'000;

std::string format_vec(const Vec3& v) {
  return "(" + format_number(v.x(), "%.6g") + ", " + format_number(v.y(), "%.6g") + ", " +
         format_number(v.z(), "%.6g") + ")";
}

void print_summary(const Scene& scene, std::string_view engine, long steps, double wall,
                   const std::vector<BodyState>& states, std::size_t contacts) {
  const double dt = scene.time.dt;
  std::cout << "scene " << scene.name << " (" << scene.source << "), engine " << engine << '\n'
            << steps << " steps of " << format_number(dt, "%.6g") << " s ("
            << format_number(steps * dt, "%.6g") << " s simulated) in "
            << format_number(wall, "%.3g") << " s wall, " << format_number(steps > 0 ? 1e6 * wall / steps : 0.0, "%.3g")
            << " us/step\n"
            << "contacts in the last step: " << contacts << '\n';
  if (states.size() <= kSummaryBodyLimit) {
    for (const BodyState& s : states) {
      std::cout << "  " << s.name << "  position " << format_vec(s.position) << "  speed "
                << format_number(s.velocity.norm(), "%.3g") << " m/s\n";
    }
    return;
  }
  const auto highest = std::max_element(states.begin(), states.end(), [](const BodyState& a, const BodyState& b) {
    return a.position.z() < b.position.z();
  });
  const auto fastest = std::max_element(states.begin(), states.end(), [](const BodyState& a, const BodyState& b) {
    return a.velocity.norm() < b.velocity.norm();
  });
  std::cout << "  " << states.size() << " bodies; highest " << highest->name << " at z = "
            << format_number(highest->position.z(), "%.6g") << " m; fastest " << fastest->name << " at "
            << format_number(fastest->velocity.norm(), "%.3g") << " m/s\n";
}

// The per-stage profile of the run's steps: microseconds per step and share of the profiled time,
// the stages in the order they run (those that took no time left out).
nlohmann::json profile_json(const StepProfile& profile, long steps) {
  nlohmann::json stages = nlohmann::json::object();
  for (std::size_t k = 0; k < kStageCount; ++k) {
    const double seconds = profile.seconds(static_cast<Stage>(k));
    if (seconds > 0.0) stages[std::string(kStageNames[k])] = seconds / static_cast<double>(std::max(1L, steps));
  }
  return {{"seconds_per_step", stages}, {"total_seconds_per_step", profile.total() / static_cast<double>(std::max(1L, steps))}};
}

void print_profile(const StepProfile& profile, long steps) {
  const double total = profile.total();
  std::cout << "profile (wall clock, per step):\n";
  for (std::size_t k = 0; k < kStageCount; ++k) {
    const double seconds = profile.seconds(static_cast<Stage>(k));
    if (seconds <= 0.0) continue;
    std::printf("  %-18s %10.2f us  %5.1f%%\n", std::string(kStageNames[k]).c_str(),
                1e6 * seconds / static_cast<double>(std::max(1L, steps)), total > 0.0 ? 100.0 * seconds / total : 0.0);
  }
  std::printf("  %-18s %10.2f us\n", "total", 1e6 * total / static_cast<double>(std::max(1L, steps)));
  std::fflush(stdout);
}

// Before its first percent a long run tells its progress line every this many steps (which
// estimates the run's cost after its first second).
constexpr long kEarlyProgressSteps = 64;

}  // namespace

void add_run_command(CLI::App& app, RunOptions& options) {
  CLI::App* cmd = app.add_subcommand("run", "Step a scene in one engine and record the bodies' states");
  cmd->add_option("scene", options.scene, "Scene file (JSON, docs/scene-format.md)")->required();
  cmd->add_option("--engine", options.engine, "Engine: one of " + engine_choices() + " (own: the scene's solver.method)")
      ->required();
  add_time_options(*cmd, options.dt, options.duration);
  add_threads_option(*cmd, options.threads);
  cmd->add_option("--every", options.every, "Record a frame every K steps (and at the start)")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()))  // (PositiveNumber prints DBL_MAX in full)
      ->capture_default_str();
  cmd->add_option("--out", options.out,
                  "Write the frames as JSON to this file (atomically); without it, print a summary");
  cmd->add_option("--iterations", options.iterations,
                  "The same as --set iterations=N: ODE QuickStep's passes (default 20) or Bullet's (default 10)");
  add_set_option(*cmd, options.set);
  cmd->add_flag("--profile", options.profile,
                "Time each stage of our steps (contacts, each solver stage, integration) and print the time per step "
                "of each (and record it with --out); our engine only");
  add_limit_options(*cmd, options.limits, true);
}

int run_run(const RunOptions& options) {
  // Every check before the first step: the output location, the scene, the flags.
  std::optional<OutputFile> out;
  if (options.out) out.emplace(*options.out, std::vector<std::filesystem::path>{options.scene});
  check_engine_name(options.engine);
  if (options.iterations) {
    // A flag the engine has no use for is refused, not ignored.
    check_has_setting(options.engine, "iterations", "--iterations");
    check_iterations(*options.iterations, options.limits);
  }
  std::optional<Scene> loaded;
  {
    const Activity loading("loading " + options.scene);
    loaded.emplace(load_checked_scene(options.scene, options.limits.load()));
  }
  Scene& scene = *loaded;
  apply_time_options(scene, options.dt, options.duration, options.limits);
  apply_threads_option(scene, options.threads);

  std::vector<std::string> words = options.set;
  if (options.iterations) words.push_back("iterations=" + std::to_string(*options.iterations));
  const nlohmann::json settings = parse_set_options(words, {options.engine})[options.engine];
  if (settings.contains("iterations") && settings["iterations"].is_number_integer()) {
    check_iterations(settings["iterations"].get<int>(), options.limits);
  }
  // Our engine's settings are the scene's: the summary and the recording read the scene it runs.
  scene = scene_with_settings(options.engine, scene, settings);
  // After the settings: `--set substeps=100000` multiplies the work.
  check_run_work(scene, options.engine, settings, options.limits, options.dt.has_value());
  const double dt = scene.time.dt;
  const long steps = step_count(scene.time);
  const Activity building("building the " + options.engine + " engine for " + options.scene);
  const std::unique_ptr<Engine> engine = make_engine(options.engine, scene, settings);
  if (options.profile && !engine->enable_profile()) {
    throw UsageError("--profile: engine " + options.engine + " keeps no per-stage profile (only ours does)");
  }
  const Activity running("running " + options.engine + " on " + options.scene);
  const bool record = out.has_value();

  Recorder recorder(scene, options.engine);
  std::vector<nlohmann::json> solver;  // our solver's statistics, per frame
  RunHooks hooks;
  if (record) {
    hooks.frame = [&](const StepView& v) {
      recorder.frame(v);
      // Our solver's record of its work: its contact method's diagnostics (the method's row).
      if (const auto* world = dynamic_cast<const World*>(engine.get())) {
        solver.push_back({{"solver", world->method_diagnostics()}});
      }
    };
  }
  // Long runs show their progress every hundredth of the run (an interrupt is noticed after any
  // step: run_loop polls it).
  ProgressPrinter progress;
  const long progress_every = std::max(1L, steps / 100);
  if (record || steps >= kProgressMinSteps) {
    hooks.step = [&](const StepView& v) {
      if (record) recorder.first_step(v);
      if (steps < kProgressMinSteps) return;
      // Before the first percent too, so that a run of hours says so within its first second.
      const bool early = v.step < progress_every && v.step % kEarlyProgressSteps == 0;
      if (v.step == 0 || (v.step % progress_every != 0 && !early)) return;
      progress({options.engine, "", 0, 1, static_cast<double>(v.step) / static_cast<double>(steps)});
    };
  }
  const std::optional<RunLoopResult> ran =
      run_interruptible([&] { return run_loop(*engine, dt, steps, options.every, hooks); }, record ? "nothing written" : "");
  if (!ran) return kExitInterrupted;
  const RunLoopResult& loop = *ran;
  const std::vector<BodyState>& states = loop.final_states;
  if (loop.stopped) {
    // Nothing after a non-finite state means anything: the run stops there, and writes nothing.
    std::cerr << "boxpile: error: " << options.engine << ": " << loop.stopped->description
              << (record ? "; nothing written\n" : "\n");
  }

  if (engine->messages() > 0) {
    std::cerr << "boxpile: note: " << engine->name() << " reported " << engine->messages() << " message(s); the last: "
              << engine->last_message() << '\n';
  }

  if (record && !loop.stopped) {
    nlohmann::json events = nlohmann::json::array();
    if (const auto* recorded = engine->collision_events()) {
      for (const CollisionEvent& e : *recorded) {
        events.push_back({{"t", e.time}, {"body_a", states[e.body_a].name},
                          {"body_b", e.body_b == kGround ? std::string("ground") : states[e.body_b].name},
                          {"impulse", e.impulse}, {"approach_speed", e.approach_speed}});
      }
    }
    nlohmann::json doc = recording_json(recorder.recording(), solver);
    doc["steps"] = loop.steps;
    doc["wall_seconds"] = loop.wall_seconds;
    doc["final"] = {{"t", loop.final_t}, {"bodies", bodies_json(states)}};
    doc["events"] = std::move(events);
    if (options.profile) doc["profile"] = profile_json(engine->solver_counters()->profile, loop.steps);
    const std::size_t frames = recorder.recording().frames.t.size();
    write_json_file(doc, *out);
    std::cout << "boxpile run: " << options.engine << " on " << scene.name << ", " << loop.steps << " steps, "
              << frames << " frames recorded\nrun: " << std::filesystem::absolute(out->target()).lexically_normal().string()
              << '\n';
  } else {
    std::vector<BodyContact> contacts;
    engine->contacts(contacts);
    print_summary(scene, options.engine, loop.steps, loop.wall_seconds, states, contacts.size());
    StateMeter meter(scene);
    const FrameMetrics m = meter.measure(states);
    std::cout << "energy " << format_number(m.energy.total(), "%.6g") << " J (kinetic "
              << format_number(m.energy.kinetic(), "%.3g")
              << " J), deepest penetration " << format_number(m.penetration.depth, "%.3g") << " m, levitation "
              << format_number(m.levitation, "%.3g") << " m\n";
  }
  if (options.profile && !loop.stopped) print_profile(engine->solver_counters()->profile, loop.steps);
  return loop.stopped ? kExitFailure : kExitOk;
}

}  // namespace boxpile::cli
