// Time of one frame's measurements (StateMeter: energy, deepest penetration, levitation) of a
// flat grid of n unit boxes resting on the ground, 2 m apart: linear in n through the broadphase.
// The all-pairs loops they replaced took 89-104 s at 10^5 bodies (docs/reliability.md).
#include <benchmark/benchmark.h>

#include <cmath>

#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/rulers/state_meter.hpp"

namespace boxpile {
namespace {

Scene flat_grid(long n) {
  Scene s;
  s.name = "grid";
  s.ground = HalfSpace{Vec3::UnitZ(), 0.0};
  const long side = static_cast<long>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (long i = 0; i < n; ++i) {
    BodyDesc b;
    b.name = std::string("b").append(std::to_string(i));
    b.boxes = {BoxShape{Vec3(0.5, 0.5, 0.5), Vec3::Zero(), Quat::Identity()}};
    b.frame = {Vec3(2.0 * static_cast<double>(i % side), 2.0 * static_cast<double>(i / side), 0.5), Quat::Identity()};
    s.bodies.push_back(b);
  }
  return s;
}

void measure_flat_grid(benchmark::State& state) {
  const Scene scene = flat_grid(state.range(0));
  StateMeter meter(scene);
  std::vector<BodyState> states;
  for (const BodyDesc& b : scene.bodies) states.push_back({b.name, b.frame.position, b.frame.orientation, {}, {}});
  for (auto _ : state) benchmark::DoNotOptimize(meter.measure(states));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK(measure_flat_grid)->Arg(10'000)->Arg(100'000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace boxpile
