// What the engine protocol itself costs (docs/engine-protocol.md, "Its cost"): a step of our
// World in this process against the same World served over the protocol by
// examples/engines/own_world_engine, states and contacts asked every step as boxpile asks them.
// The difference per step is the protocol's cost: the JSON of a request and an answer, two pipe
// transfers and the context switches. Scenes of 10 and 100 unit cubes at rest on the ground.
#include <benchmark/benchmark.h>

#include "boxpile/reference/process/process_engine.hpp"
#include "boxpile/sim/world.hpp"

namespace {

using namespace boxpile;

// `n` unit cubes resting on the ground: a column of ten (n = 10) or a grid of columns of one
// (n = 100), 5 cm apart; dt 1/240 s, friction 0.5. Every step has contacts to report.
Scene resting_boxes(int n) {
  Scene scene;
  scene.name = "resting_" + std::to_string(n);
  scene.ground = HalfSpace{};
  scene.effects.restitution = false;
  const int columns = n >= 100 ? 10 : 1;
  const int per_column = n / (columns * columns);
  for (int i = 0; i < columns; ++i) {
    for (int j = 0; j < columns; ++j) {
      for (int k = 0; k < per_column; ++k) {
        BodyDesc d;
        d.name = "b" + std::to_string(scene.bodies.size());
        d.boxes = {BoxShape{}};
        d.frame.position = Vec3(1.05 * i, 1.05 * j, 0.5 + k);
        scene.bodies.push_back(d);
      }
    }
  }
  return scene;
}

// Steps `engine` and asks its states and (unless `with_contacts` is false, as stability, sweeps
// and accuracy runs ask) its contacts, as boxpile's run loop does each step.
template <class E>
void step_and_report(benchmark::State& state, E& engine, std::size_t bodies, bool with_contacts = true) {
  std::vector<BodyState> states;
  std::vector<BodyContact> contacts;
  engine.report_contacts(with_contacts);
  for (auto _ : state) {
    engine.step();
    engine.body_states(states);
    if (with_contacts) engine.contacts(contacts);
    benchmark::DoNotOptimize(states.data());
  }
  state.counters["bodies"] = static_cast<double>(bodies);
}

void BM_StepInProcess(benchmark::State& state) {
  const Scene scene = resting_boxes(static_cast<int>(state.range(0)));
  World world(scene);
  step_and_report(state, world, scene.bodies.size());
}

// range(1): 1 asks the contacts every step, 0 the states alone.
void BM_StepOverProtocol(benchmark::State& state) {
  const Scene scene = resting_boxes(static_cast<int>(state.range(0)));
  ProcessEngineOptions options;
  options.name = "own-world";
  options.command = BOXPILE_OWN_WORLD_ENGINE;
  ProcessEngine engine(scene, options);
  step_and_report(state, engine, scene.bodies.size(), state.range(1) != 0);
  // The engine's own time per step, as it reported it: the in-process cost seen from the far side.
  state.counters["engine_us"] = 1e6 * engine.reported_seconds().value_or(0.0) / static_cast<double>(state.iterations());
}

}  // namespace

// Interleaved (in-process, protocol) per size, so that both see the same load.
BENCHMARK(BM_StepInProcess)->Arg(10)->Unit(benchmark::kMicrosecond)->Repetitions(3);
BENCHMARK(BM_StepOverProtocol)->Args({10, 1})->Args({10, 0})->Unit(benchmark::kMicrosecond)->Repetitions(3);
BENCHMARK(BM_StepInProcess)->Arg(100)->Unit(benchmark::kMicrosecond)->Repetitions(3);
BENCHMARK(BM_StepOverProtocol)->Args({100, 1})->Args({100, 0})->Unit(benchmark::kMicrosecond)->Repetitions(3);
