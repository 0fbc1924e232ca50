#include "boxpile/validation/core/run_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <string>
#include <utility>

#include "boxpile/sim/finite.hpp"
#include "boxpile/validation/core/output_safety.hpp"

namespace boxpile {

long steps_per_frame(double dt, double frame_rate) { return std::max(1L, std::lround(1.0 / (frame_rate * dt))); }

RunLoopResult run_loop(Engine& engine, double dt, long steps, long every, const RunHooks& hooks) {
  using Clock = std::chrono::steady_clock;
  RunLoopResult result;
  std::vector<BodyState> before, states;
  engine.body_states(states);
  before = states;
  long last_frame = 0;
  const auto call = [&](const std::function<void(const StepView&)>& hook, long k) {
    if (hook) hook(StepView{engine, k, static_cast<double>(k) * dt, before, states});
  };
  call(hooks.step, 0);
  call(hooks.frame, 0);

  Clock::duration stepping{};
  const std::optional<double> reported_at_start = engine.reported_seconds();
  for (long k = 1; k <= steps; ++k) {
    std::swap(before, states);
    const Clock::time_point start = Clock::now();
    try {
      engine.step();
    } catch (const std::bad_alloc&) {
      throw OutOfMemory(std::string(engine.name()) + ": step " + std::to_string(k) +
                        ": out of memory building the step's contacts and solver rows (--max-pairs lowers the "
                        "pairs a step may make)");
    }
    stepping += Clock::now() - start;
    engine.body_states(states);
    if (const auto bad = find_non_finite(states)) {
      const double t = static_cast<double>(k) * dt;
      result.stopped = NonFiniteStop{k, t, states[bad->body].name, std::string(bad->quantity),
                                     describe_non_finite(k, t, states, *bad)};
      std::swap(before, states);  // back to the last finite states
      if (last_frame < k - 1) call(hooks.frame, k - 1);
      break;
    }
    result.steps = k;
    throw_if_interrupted();  // a SIGINT or SIGTERM inside an InterruptScope stops the run here
    try {
      call(hooks.step, k);
      if (k % every == 0 || k == steps) {
        call(hooks.frame, k);
        last_frame = k;
      }
    } catch (const std::bad_alloc&) {
      throw OutOfMemory(std::string(engine.name()) + ": step " + std::to_string(k) +
                        ": out of memory measuring or recording the frame");
    }
    if (hooks.stop && k < steps && hooks.stop(StepView{engine, k, static_cast<double>(k) * dt, before, states})) {
      if (last_frame < k) call(hooks.frame, k);
      result.cut_short = true;
      break;
    }
  }
  result.wall_seconds = std::chrono::duration<double>(stepping).count();
  const std::optional<double> reported = engine.reported_seconds();
  result.engine_seconds = reported ? *reported - reported_at_start.value_or(0.0) : result.wall_seconds;
  result.final_states = std::move(states);
  result.final_t = static_cast<double>(result.steps) * dt;
  return result;
}

}  // namespace boxpile
