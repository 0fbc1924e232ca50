// Time per step of our engine and the reference engines on the shared scenes: stack_5 and
// stack_10 (unit cubes) and pile_100 (a hundred boxes falling into a pile). One benchmark iteration builds the engine
// (not timed) and steps it through the scene's whole duration (5 s at dt 1/240, 1200 steps), so
// every iteration times the same motion: the falling phase and the resting phase alike.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "reference/settings.hpp"
#include "sim/io/scene_loader.hpp"
#include "sim/time_steps.hpp"
#include "validation/engine_factory.hpp"

namespace boxpile {
namespace {

void step_scene(benchmark::State& state, const std::string& scene_name, const std::string& engine,
                const ReferenceSettings& settings) {
  const Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + scene_name + ".json");
  const long steps = step_count(scene.time);
  for (auto _ : state) {
    state.PauseTiming();
    const auto world = make_engine(engine, scene, settings);
    state.ResumeTiming();
    for (long k = 0; k < steps; ++k) world->step();
  }
  // Seconds per step: the inverse of steps per second.
  state.counters["per_step"] = benchmark::Counter(static_cast<double>(steps),
                                                  benchmark::Counter::kIsIterationInvariantRate |
                                                      benchmark::Counter::kInvert);
}

ReferenceSettings ode_world_step() {
  ReferenceSettings s;
  s.ode_method = OdeStepMethod::Step;
  return s;
}

BENCHMARK_CAPTURE(step_scene, stack_5/ode_quickstep, "stack_5", "ode", ReferenceSettings{})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_5/ode_worldstep, "stack_5", "ode", ode_world_step())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_5/bullet, "stack_5", "bullet", ReferenceSettings{})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_5/own, "stack_5", "own", ReferenceSettings{})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_10/own, "stack_10", "own", ReferenceSettings{})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_10/ode_quickstep, "stack_10", "ode", ReferenceSettings{})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, stack_10/bullet, "stack_10", "bullet", ReferenceSettings{})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(step_scene, pile_100/own, "pile_100", "own", ReferenceSettings{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(step_scene, pile_100/ode_quickstep, "pile_100", "ode", ReferenceSettings{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(step_scene, pile_100/bullet, "pile_100", "bullet", ReferenceSettings{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

}  // namespace
}  // namespace boxpile
