// The contact loop of the Guendelman-Bridson-Fedkiw step (sec. 6 of the paper).
#pragma once

#include <vector>

#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/step_storage.hpp"

namespace boxpile {

// Contact loop: `contact_passes` passes over the contacts that do not separate when it begins,
// restitution ramped e_k = -1 + (k + 1) / passes (from -1 + 1/n up to 0), nothing removed.
class ContactLoop {
 public:
  void reserve(const StepStorage& storage) { resting_.reserve(storage.contacts()); }
  void run(ImpulseStep& step);

 private:
  std::vector<int> resting_;  // the loop's contacts: those not separating at its start
};

}  // namespace boxpile
