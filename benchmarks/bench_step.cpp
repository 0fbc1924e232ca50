// Time per step of our engine and the reference engines (ODE QuickStep, Bullet, MuJoCo, DART), each
// at its defaults (DART also with FCL's meshes, DART's own default detector), on the shared scenes
// and, all but DART, on generated ones:
//   step_scene    stack_5, stack_10 and pile_100 from fixtures/scenes, through their whole
//                 duration (5 s at dt 1/240, 1,200 steps): the falling and the resting phase;
//                 pile_100/own_lab_loops is ours with the lab text's two loops alone (our
//                 defaults without shock propagation and penetration recovery): what the method
//                 the lab text prescribes costs before anything of ours is added.
//   step_hard     the hard catalogue's square pyramids of base 6 and 10 and the Jenga tower
//                 (generated_scenes.hpp), through the catalogue's durations (3 s, 1.5 s, 5 s);
//                 ours also as own_sequential (solver.contact_batches off).
//   step_moving   scenes in motion: pile_100 and the bone scene (fixtures/scenes, their whole 5 s,
//                 with our per-stage profile as counters stage_*), a 4 x 4 x 4
//                 cube of boxes rammed by a 40 kg box (2 s), and heaps of 300 and 1,000 randomly
//                 sized and turned boxes falling in layers onto the ground (3 s), built in code
//                 (generated_scenes.hpp); ours also as own_sequential (solver.contact_batches off:
//                 the contact loop one contact at a time) and own_threads_2 (solver.threads 2,
//                 timed by the wall clock: the CPU time counts the calling thread alone).
//   step_scaling  square pyramids of base 4, 6, 8, 10, 14, 20 and 30 (30 to 9,455 boxes), the
//                 first 60 steps (0.25 s): cost against the number of contacts, for the log-log
//                 plot of docs/performance.md (scripts/plot-scaling), with our per-stage profile.
// Ours runs on one thread (solver.threads 1) unless a benchmark's name says otherwise, as ODE,
// Bullet and MuJoCo do, so that every engine's CPU time is the whole of its work.
// One benchmark iteration builds the engine (not timed) and steps it, so every iteration times
// the same motion. Counters: per_step (s), and contacts, the engine's contact points after the
// last step (each engine counts its own).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "generated_scenes.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/solver/step_context.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/reference/registry.hpp"

namespace boxpile {
namespace {

// With `profile`, an engine that keeps a per-stage profile (ours) records it, and the last
// iteration's is reported as counters stage_NAME (wall-clock seconds per step).
void time_steps(benchmark::State& state, const Scene& scene, const std::string& engine,
                const nlohmann::json& settings, long steps, bool profile = false) {
  std::vector<BodyContact> contacts;
  StepProfile stages;
  nlohmann::json engine_settings = settings;
  if (engine == "own" && !engine_settings.contains("threads")) engine_settings["threads"] = 1;
  for (auto _ : state) {
    state.PauseTiming();
    try {
      const auto world = make_engine(engine, scene, engine_settings);
      const bool profiled = profile && world->enable_profile();
      state.ResumeTiming();
      for (long k = 0; k < steps; ++k) world->step();
      state.PauseTiming();
      world->contacts(contacts);
      if (profiled) stages = world->solver_counters()->profile;
    } catch (const EngineRefused& e) {
      // The engine cannot take the scene (MuJoCo 2.2 above its 12,000 constraint rows): no figure.
      state.SkipWithError(e.what());
      break;
    }
    state.ResumeTiming();
  }
  if (state.error_occurred()) return;
  for (std::size_t k = 0; k < kStageCount; ++k)
    if (const double seconds = stages.seconds(static_cast<Stage>(k)); seconds > 0.0)
      state.counters["stage_" + std::string(kStageNames[k])] = seconds / static_cast<double>(steps);
  // Seconds per step: the inverse of steps per second.
  state.counters["per_step"] = benchmark::Counter(static_cast<double>(steps),
                                                  benchmark::Counter::kIsIterationInvariantRate |
                                                      benchmark::Counter::kInvert);
  state.counters["contacts"] = static_cast<double>(contacts.size());
  state.counters["bodies"] = static_cast<double>(scene.bodies.size());
}

Scene fixture_scene(const std::string& scene_name) {
  return load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + scene_name + ".json");
}

void step_scene(benchmark::State& state, const std::string& scene_name, const std::string& engine,
                const nlohmann::json& settings) {
  const Scene scene = fixture_scene(scene_name);
  time_steps(state, scene, engine, settings, step_count(scene.time));
}

nlohmann::json ode_world_step() { return {{"stepper", "world"}}; }
nlohmann::json dart_fcl_meshes() { return {{"detector", "fcl"}}; }

BENCHMARK_CAPTURE(step_scene, stack_5/ode_quickstep, "stack_5", "ode", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_5/ode_worldstep, "stack_5", "ode", ode_world_step())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_5/bullet, "stack_5", "bullet", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_5/mujoco, "stack_5", "mujoco", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_5/dart, "stack_5", "dart", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_5/dart_fcl, "stack_5", "dart", dart_fcl_meshes())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_5/own, "stack_5", "own", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_10/own, "stack_10", "own", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_10/ode_quickstep, "stack_10", "ode", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_10/bullet, "stack_10", "bullet", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_10/mujoco, "stack_10", "mujoco", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_10/dart, "stack_10", "dart", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, pile_100/own, "pile_100", "own", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(step_scene, pile_100/ode_quickstep, "pile_100", "ode", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(step_scene, pile_100/bullet, "pile_100", "bullet", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(step_scene, pile_100/mujoco, "pile_100", "mujoco", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(step_scene, pile_100/dart, "pile_100", "dart", nlohmann::json::object())
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

// The engines of the generated scenes: the registry's stability list (ours, ODE, Bullet) and
// MuJoCo, every native engine whose step stays within milliseconds on thousands of boxes. DART's
// Dantzig LCP does not (it ran `brick_wall_ram`, 81 boxes, 27 minutes without finishing its 480
// steps): it runs the shared scenes above only.
std::vector<std::string> generated_scene_engines() {
  std::vector<std::string> engines = default_engines(&DefaultLists::stability);
  if (std::find(engines.begin(), engines.end(), "mujoco") == engines.end()) engines.push_back("mujoco");
  return engines;
}
const std::vector<std::string> kEngines = generated_scene_engines();

// The catalogue's durations: long enough for each scene to settle.
constexpr double kPyramid6Duration = 3.0;   // s
constexpr double kPyramid10Duration = 1.5;  // s
constexpr double kJengaDuration = 5.0;      // s

// The scaling sweep: every size over the same first steps, so that sizes compare (base 30 takes
// ODE some 60 s of the sweep's three repetitions, ours and Bullet's some 15 to 20 s).
constexpr std::array<int, 7> kScalingBases = {4, 6, 8, 10, 14, 20, 30};
constexpr long kScalingSteps = 60;

// The scenes in motion: long enough for the cube to be scattered and the heaps to land.
constexpr double kRammedCubeDuration = 2.0;  // s
constexpr double kHeapDuration = 3.0;        // s: the top layers land after some 1.5 s

void step_generated(benchmark::State& state, const Scene& scene, const std::string& engine, long steps) {
  time_steps(state, scene, engine, nlohmann::json::object(), steps);
}

// The scenes in motion, with our per-stage profile (9 clock reads a step, some 0.5 us: under 1%
// of these steps).
void step_profiled(benchmark::State& state, const Scene& scene, const std::string& engine, long steps,
                   const nlohmann::json& settings) {
  time_steps(state, scene, engine, settings, steps, true);
}

long whole(const Scene& s) { return step_count(s.time); }

// Our impulse method with the lab text's collision and contact loops alone, at their default passes
// (5 and 10, the least the lab text asks for): no shock propagation, no penetration recovery.
Scene lab_loops_only(Scene scene) {
  scene.solver.shock_propagation = false;
  scene.solver.penetration_recovery = 0.0;
  return scene;
}

// Registered at start-up: the generated and changed scenes are built once, here.
const bool registered = [] {
  const Scene lab_loops = lab_loops_only(fixture_scene("pile_100"));
  benchmark::RegisterBenchmark("step_scene/pile_100/own_lab_loops", step_generated, lab_loops, std::string("own"),
                               whole(lab_loops))
      ->Unit(benchmark::kMillisecond)
      ->Iterations(5);
  const std::vector<std::pair<std::string, Scene>> hard = {
      {"pyramid_6", bench::square_pyramid(6, kPyramid6Duration)},
      {"pyramid_10", bench::square_pyramid(10, kPyramid10Duration)},
      {"jenga", bench::jenga_tower(kJengaDuration)},
  };
  for (const auto& [name, scene] : hard) {
    for (const std::string& engine : kEngines)
      benchmark::RegisterBenchmark(("step_hard/" + name + "/" + engine).c_str(), step_generated, scene,
                                   engine, whole(scene))
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
    Scene sequential = scene;
    sequential.solver.contact_batches = false;
    benchmark::RegisterBenchmark(("step_hard/" + name + "/own_sequential").c_str(), step_generated, sequential,
                                 std::string("own"), whole(scene))
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  }
  const std::vector<std::pair<std::string, Scene>> moving = {
      {"pile_100", fixture_scene("pile_100")},
      {"bone_hits_pile", fixture_scene("bone_hits_pile")},
      {"rammed_cube_64", bench::rammed_cube(kRammedCubeDuration)},
      {"heap_300", bench::falling_heap(300, 6, kHeapDuration)},
      {"heap_1000", bench::falling_heap(1000, 10, kHeapDuration)},
  };
  for (const auto& [name, scene] : moving) {
    for (const std::string& engine : kEngines)
      benchmark::RegisterBenchmark(("step_moving/" + name + "/" + engine).c_str(), step_profiled, scene, engine,
                                   whole(scene), nlohmann::json::object())
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
    // Ours with the contact loop one contact at a time (solver.contact_batches off), one thread:
    // what the batches buy.
    benchmark::RegisterBenchmark(("step_moving/" + name + "/own_sequential").c_str(), step_profiled, scene,
                                 std::string("own"), whole(scene), nlohmann::json{{"contact_batches", false}})
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
    // Ours on two threads (`own` above: one), timed by the wall clock, per_step included.
    benchmark::RegisterBenchmark(("step_moving/" + name + "/own_threads_2").c_str(), step_profiled, scene,
                                 std::string("own"), whole(scene), nlohmann::json{{"threads", 2}})
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
  }
  // Each engine's colour (the registry's, as in every plot of boxpile's) in the results' context,
  // for scripts/plot-scaling.
  for (const std::string& engine : kEngines)
    if (const EngineRow* row = find_engine_row(engine)) benchmark::AddCustomContext("engine_colour/" + engine, row->colour);
  for (int base : kScalingBases) {
    const Scene scene = bench::square_pyramid(base, kScalingSteps * TimeSettings{}.dt);
    for (const std::string& engine : kEngines)
      benchmark::RegisterBenchmark(("step_scaling/pyramid_" + std::to_string(bench::square_pyramid_boxes(base)) +
                                    "/" + engine).c_str(),
                                   step_profiled, scene, engine, kScalingSteps, nlohmann::json::object())
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
  }
  return true;
}();

}  // namespace
}  // namespace boxpile
