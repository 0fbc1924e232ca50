// The one loop that steps an engine through a scene, for every command that runs one (`run`,
// `compare`): it times the steps alone, checks every state for finiteness after each step, and
// calls its hooks after each step and at each recorded frame.
#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "boxpile/sim/engine.hpp"

namespace boxpile {

// The first quantity found non-finite after a step: the run stops there.
struct NonFiniteStop {
  long step = 0;  // 1-based: the step that produced it
  double t = 0.0;  // s, after that step
  std::string body;
  std::string quantity;  // "position", "orientation", "velocity" or "angular_velocity"
  std::string description;  // step, time, body and quantity in one line (sim/finite.hpp)
};

// What the hooks see. Step 0 is the start (`before` is then the start too).
struct StepView {
  const Engine& engine;
  long step = 0;
  double t = 0.0;  // s, after the step
  const std::vector<BodyState>& before;  // states before the step
  const std::vector<BodyState>& states;  // states after it
};

struct RunHooks {
  // After every step, and once at the start (step 0).
  std::function<void(const StepView&)> step;
  // At the start, every `every` steps and after the last step.
  std::function<void(const StepView&)> frame;
  // After each step's hooks: true ends the run there (RunLoopResult::cut_short), e.g. a cell's
  // wall-time limit. Not asked at the start.
  std::function<bool(const StepView&)> stop;
};

// An allocation failed inside a step or a hook: the message names the engine, the step and the
// part (std::bad_alloc names nothing). A run that is out of memory went wrong (exit 1).
class OutOfMemory : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunLoopResult {
  long steps = 0;  // steps taken (fewer than asked when stopped)
  double wall_seconds = 0.0;  // in Engine::step() alone
  // The engine's own time for these steps when it reports one (an engine over the protocol:
  // Engine::reported_seconds()), else wall_seconds: the figure per-step costs are made of.
  double engine_seconds = 0.0;
  std::optional<NonFiniteStop> stopped;
  bool cut_short = false;  // hooks.stop ended the run before its last step
  std::vector<BodyState> final_states;  // the last finite states
  double final_t = 0.0;  // s
};

// The steps between recorded frames for `frame_rate` frames per simulated second at `dt`: at
// least one (every step).
long steps_per_frame(double dt, double frame_rate);

// Steps `engine` `steps` times (dt is the engine's). A step that leaves any state non-finite
// (sim/finite.hpp) ends the run: no hook sees that step, the last finite states are recorded as a frame (when not
// already), and the result says where it happened. SIGINT or SIGTERM inside an InterruptScope
// (output_safety.hpp) ends it after the step in progress: Interrupted is thrown.
RunLoopResult run_loop(Engine& engine, double dt, long steps, long every, const RunHooks& hooks);

}  // namespace boxpile
