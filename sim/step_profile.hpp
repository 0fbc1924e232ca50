// Where a step's time goes: the wall-clock seconds of each stage of our steps, summed over the
// steps since profiling was switched on (as Box2D's b2Profile; `boxpile run --profile`, and the
// moving-scene benchmarks' stage_* counters). Off by default: a stage's lap reads the clock,
// some 50 ns on the project's machine, nine times a step (1% of the bone scene's step). The clock
// is read outside the computation and nothing reads it back, so results are the same with it on.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <string_view>

namespace boxpile {

// The stages of a step in the order they run (the impulse method's, then the penalty method's
// own; the world's contact search and the methods' shared stages once).
enum class Stage : std::size_t {
  contacts,           // the contact search: margins, placed boxes, broadphase, narrowphase
  prepare,            // the solver contacts: offsets, collision matrices
  collision_loop,     // the collision loop's passes
  forces,             // gravity and damping on the momenta, the wires' share
  contact_loop,       // the contact loop's passes
  shock_propagation,  // its graph, levels, groups, direct solves and passes
  recovery,           // penetration recovery's pseudo-velocities
  integration,        // positions and orientations, wires projected
  penalty_forces,     // the penalty method's springs and friction anchors
  count
};
inline constexpr std::size_t kStageCount = static_cast<std::size_t>(Stage::count);
inline constexpr std::array<std::string_view, kStageCount> kStageNames = {
    "contacts", "prepare",  "collision_loop", "forces", "contact_loop", "shock_propagation",
    "recovery", "integration", "penalty_forces"};

class StepProfile {
 public:
  using Clock = std::chrono::steady_clock;

  void enable(bool on) { enabled_ = on; }
  bool enabled() const { return enabled_; }
  // Starts a step's clock; each lap then adds the time since the last lap (or the start) to its stage.
  void begin() {
    if (enabled_) last_ = Clock::now();
  }
  void lap(Stage stage) {
    if (!enabled_) return;
    const Clock::time_point now = Clock::now();
    seconds_[static_cast<std::size_t>(stage)] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  // Seconds spent in a stage so far (0 while profiling was off).
  double seconds(Stage stage) const { return seconds_[static_cast<std::size_t>(stage)]; }
  double total() const {
    double sum = 0.0;
    for (double s : seconds_) sum += s;
    return sum;
  }

 private:
  bool enabled_ = false;
  Clock::time_point last_{};
  std::array<double, kStageCount> seconds_{};
};

}  // namespace boxpile
