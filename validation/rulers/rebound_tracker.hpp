// A body's rebound, followed from its height and upward speed after each step: it falls, then
// rises after its first impact (the highest point of that rise is the rebound), then falls again.
// One implementation for the rebound check (validation/stability/stability_checks.hpp) and the
// rebound truth (validation/accuracy/truth_meter.hpp), so that both read a bounce alike.
#pragma once

#include <algorithm>
#include <optional>

namespace boxpile {

class ReboundTracker {
 public:
  // The body's height (m, along up) and upward speed (m/s) after a step, or at the start.
  void observe(double height, double v_up) {
    switch (phase_) {
      case Phase::Falling:
        if (v_up < 0.0) fell_ = true;
        if (fell_ && v_up > 0.0) {
          phase_ = Phase::Rising;
          apex_ = height;
        }
        break;
      case Phase::Rising:
        apex_ = std::max(*apex_, height);
        if (v_up < 0.0) phase_ = Phase::Done;
        break;
      case Phase::Done:
        break;
    }
  }

  // The highest height of the rise after the first impact so far (m); unset before it rises.
  std::optional<double> apex() const { return apex_; }
  // Whether the rise is over (the body falls again): apex() no longer changes.
  bool done() const { return phase_ == Phase::Done; }

 private:
  enum class Phase { Falling, Rising, Done } phase_ = Phase::Falling;
  bool fell_ = false;  // it has moved down at least once (a body launched upwards is not a bounce)
  std::optional<double> apex_;
};

}  // namespace boxpile
