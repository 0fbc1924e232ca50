// libFuzzer target: the scene loader, and a few steps of every engine on what it accepts.
// What must hold for any input: parse_checked_scene (the loader, then the scene's checks) either
// throws InputError or returns a scene that every engine (ours, ODE, Bullet) steps without
// crashing, without an ODE error and with finite states. Anything else (a crash, a sanitizer
// report, an abort) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>

#include "boxpile/reference/bullet/bullet_engine.hpp"
#include "boxpile/reference/ode/ode_engine.hpp"
#include "boxpile/sim/finite.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/world.hpp"
#include "boxpile/validation/stability/scene_checks.hpp"

namespace {

using namespace boxpile;

// Larger scenes are loaded but not stepped: a few steps of a big pile would cut the fuzzer's
// speed from thousands of inputs per second to a handful.
constexpr std::size_t kMaxSteppedBodies = 32;
constexpr int kSteps = 3;

template <class E>
void step_and_check(const Scene& scene, const char* engine_name) {
  E engine(scene);
  std::vector<BodyState> states;
  for (int k = 1; k <= kSteps; ++k) {
    engine.step();
    engine.body_states(states);
    if (const auto bad = find_non_finite(states)) {
      std::fprintf(stderr, "%s: %s\n", engine_name, describe_non_finite(k, engine.time(), states, *bad).c_str());
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Scene scene;
  try {
    scene = parse_checked_scene(text, "fuzz.json");
  } catch (const InputError&) {
    return 0;  // refused with a message: fine
  }
  if (scene.bodies.size() > kMaxSteppedBodies) return 0;
  // One step count for all: the scene's dt is whatever the input says.
  step_and_check<World>(scene, "own");
  try {
    step_and_check<OdeEngine>(scene, "ode");
  } catch (const OdeError& e) {
    std::fprintf(stderr, "accepted scene reached an ODE error: %s\n", e.what());
    std::abort();
  }
  step_and_check<BulletEngine>(scene, "bullet");
  return 0;
}
