// The finiteness check of body states during a run: the first body and quantity that is not a
// finite number, so that a run stops at the first bad step and says where it went wrong. Every
// runner (run, compare, and any later tool) uses it.
#pragma once

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/sim/engine.hpp"

namespace boxpile {

struct NonFiniteState {
  std::size_t body = 0;         // index in scene order
  std::string_view quantity;    // "position", "orientation", "velocity", "angular_velocity"
};

// A vector whose squared norm overflows is as useless as an infinite one: every energy and
// distance computed from it is infinite. So the test is on the squared norm, which also catches
// NaN and infinity in any component.
template <class V>
bool finite_magnitude(const V& v) {
  return std::isfinite(v.squaredNorm());
}

inline std::optional<std::string_view> non_finite_quantity(const BodyState& s) {
  if (!finite_magnitude(s.position)) return "position";
  if (!finite_magnitude(s.orientation.coeffs())) return "orientation";
  if (!finite_magnitude(s.velocity)) return "velocity";
  if (!finite_magnitude(s.angular_velocity)) return "angular_velocity";
  return std::nullopt;
}

// The first body (in scene order) whose state is not finite, if any.
inline std::optional<NonFiniteState> find_non_finite(const std::vector<BodyState>& states) {
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (const auto q = non_finite_quantity(states[i])) return NonFiniteState{i, *q};
  }
  return std::nullopt;
}

// "step 812 (t = 3.38333 s): body \"box_3\" has a non-finite angular_velocity".
inline std::string describe_non_finite(long step, double t, const std::vector<BodyState>& states,
                                       const NonFiniteState& bad) {
  char time[32];
  std::snprintf(time, sizeof time, "%.6g", t);
  return "step " + std::to_string(step) + " (t = " + time + " s): body \"" + states[bad.body].name +
         "\" has a non-finite " + std::string(bad.quantity);
}

}  // namespace boxpile
