// The number of steps a run takes, from the time step and the duration: the one rule every
// command and tool uses, with the checks that keep it meaningful (no NaN, no overflow, a cap).
#pragma once

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// What is wrong with a (dt, duration) pair: which of the two, and why.
struct TimeSettingsProblem {
  enum class Field { Dt, Duration } field;
  std::string what;
  bool over_cap = false;  // the step count is above the cap (a command line may raise it)
};

// The steps of `duration` at `dt`, rounded to the nearest whole step. Valid only for settings
// that check_time_settings() accepts.
inline long step_count(double dt, double duration) { return std::lround(duration / dt); }
inline long step_count(const TimeSettings& time) { return step_count(time.dt, time.duration); }

namespace time_steps_detail {
inline std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}
// A step count as a whole number ("10000001 steps", not the "1e+07" that hides the one over the
// cap), or "more steps than a double counts" when duration / dt overflows.
inline std::string step_count_text(double steps) {
  if (!(steps < std::numeric_limits<double>::infinity())) return "more steps than a double counts";
  if (steps >= 1e18) return number(steps) + " steps";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f steps", steps);
  return buf;
}
}  // namespace time_steps_detail

// dt must be a number in (0, kMaxTimeStep], duration a number >= 0, and the step count at most
// `max_steps` (at most kMaxRepresentableSteps, far inside a long). A command line adds how to
// raise its cap to the message. NaN fails every comparison, so each test
// is written to pass only for good values.
inline std::optional<TimeSettingsProblem> check_time_settings(double dt, double duration,
                                                              long max_steps = limits::kMaxRepresentableSteps) {
  using time_steps_detail::number;
  using time_steps_detail::step_count_text;
  using Field = TimeSettingsProblem::Field;
  if (!(dt > 0.0 && dt <= limits::kMaxTimeStep)) {
    return TimeSettingsProblem{Field::Dt, "must be a number in (0, " + number(limits::kMaxTimeStep) +
                                              "] s, got " + number(dt)};
  }
  if (!(duration >= 0.0 && duration < std::numeric_limits<double>::infinity())) {
    return TimeSettingsProblem{Field::Duration, "must be a finite number >= 0 s, got " + number(duration)};
  }
  const double steps = std::round(duration / dt);  // finite or +inf, never NaN here
  if (!(steps <= static_cast<double>(max_steps))) {
    return TimeSettingsProblem{Field::Duration, number(duration) + " s at dt " + number(dt) + " s is " +
                                                    step_count_text(steps) + ", above the cap of " +
                                                    std::to_string(max_steps),
                               true};
  }
  return std::nullopt;
}

}  // namespace boxpile
