// Time to load a scene of n boxes on a grid from JSON text: parsing (linear, through SAX events),
// validation and the initial-overlap check (through the broadphase). 10^5 bodies must load in
// seconds; both steps used to be quadratic (docs/reliability.md).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "boxpile/sim/io/scene_loader.hpp"

namespace boxpile {
namespace {

// n unit boxes resting on the ground, 2 m apart on a square grid.
std::string grid_scene(long n) {
  std::string text = R"({"name": "grid", "ground": {"normal": [0, 0, 1], "offset": 0}, "bodies": [)";
  const long side = static_cast<long>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (long i = 0; i < n; ++i) {
    if (i > 0) text += ",";
    text += R"({"name": "b)";
    text += std::to_string(i);
    text += R"(", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [)";
    text += std::to_string(2 * (i % side));
    text += ", ";
    text += std::to_string(2 * (i / side));
    text += ", 0.5]}";
  }
  return text + R"(], "time": {"dt": 0.01, "duration": 1}})";
}

void load_grid(benchmark::State& state) {
  const std::string text = grid_scene(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(parse_scene(text, "grid.json"));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK(load_grid)->Arg(10'000)->Arg(100'000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace boxpile
