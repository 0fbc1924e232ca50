// Shock propagation of the Guendelman-Bridson-Fedkiw step (sec. 7 of the paper).
#pragma once

#include <vector>

#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/step_storage.hpp"

namespace boxpile {

// Shock propagation: bodies sorted into levels by contact-graph distance from the ground and
// fixed bodies; level by level from the bottom, up to `shock_passes` passes with e = 0 over the
// contacts that reach down from the level (fewer once the level has converged), with every
// lower level frozen (infinite mass).
class ShockPropagation {
 public:
  // Sizes the graph, the levels and the queue for `storage.bodies` bodies and their contacts.
  void reserve(const StepStorage& storage);
  void run(ImpulseStep& step);
  // Level of each body in the last run (-1: fixed; kUnsupported: not connected to the ground).
  const std::vector<int>& levels() const { return level_; }
  static constexpr int kUnsupported = 1 << 30;

 private:
  std::vector<int> level_;
  std::vector<int> queue_;
  std::vector<int> adjacency_start_, adjacency_;  // contact graph, compressed rows
  std::vector<int> by_level_;                      // contact indices sorted by level
  std::vector<int> level_start_;
};

}  // namespace boxpile
