// Cost of the penalty method per substep and per contact spring, on stack_5, stack_10, the
// pyramid, pile_100 and the bone scene with the derived parameters (docs/penalty.md). One iteration
// builds the world (not timed) and steps it through the scene's whole duration; the counters
// divide the time by the substeps taken and by the spring evaluations made.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/sim/solver/penalty_method.hpp"
#include "boxpile/sim/world.hpp"

namespace boxpile {
namespace {

void penalty_steps(benchmark::State& state, const std::string& scene_name) {
  Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + scene_name + ".json");
  scene.solver.method = "penalty";
  const long steps = step_count(scene.time);
  double substeps = 0.0, springs = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    World world(scene, "own-penalty");
    state.ResumeTiming();
    for (long k = 0; k < steps; ++k) world.step();
    substeps = static_cast<double>(world.method_as<PenaltyMethod>()->counters().substeps);
    springs = static_cast<double>(world.method_as<PenaltyMethod>()->counters().spring_evaluations);
  }
  const auto per = benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert;
  state.counters["per_substep"] = benchmark::Counter(substeps, per);
  state.counters["per_spring"] = benchmark::Counter(springs, per);
  state.counters["substeps_per_step"] = substeps / static_cast<double>(steps);
}

BENCHMARK_CAPTURE(penalty_steps, stack_5, "stack_5")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(penalty_steps, stack_10, "stack_10")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(penalty_steps, pyramid, "pyramid")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(penalty_steps, bone_hits_pile, "bone_hits_pile")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(penalty_steps, pile_100, "pile_100")->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace boxpile
