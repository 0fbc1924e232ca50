// Where a body's wire anchor is, from its reported state alone: how far along the wire, how far
// off its line, and how far past its ends. The same ruler for every engine.
#pragma once

#include <algorithm>

#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

struct WireGap {
  double along = 0.0;     // m from `from` toward `to`, measured on the wire's line
  double off = 0.0;       // m, distance of the anchor from the wire's line
  double past_end = 0.0;  // m beyond the nearer end (0 while between the ends)
};

inline WireGap wire_gap(const Wire& wire, const BodyState& state) {
  const Vec3 anchor = state.position + state.orientation * wire.anchor;
  const Vec3 along = wire.to - wire.from;
  const double length = along.norm();
  const Vec3 axis = along / length;
  const Vec3 r = anchor - wire.from;
  WireGap g;
  g.along = r.dot(axis);
  g.off = (r - g.along * axis).norm();
  g.past_end = std::max({0.0, -g.along, g.along - length});
  return g;
}

}  // namespace boxpile
