// The penalty method (the lab text, "Penalty based simulation method"; docs/penalty.md): at each
// contact point a damped spring along the normal and a friction spring to an anchor, forces and
// torques summed per body, and symplectic Euler (momenta first, then positions with the new
// velocities) over `substeps` steps per scene step.
#pragma once

#include <vector>

#include "boxpile/sim/solver/contact_method.hpp"
#include "boxpile/sim/solver/friction_anchors.hpp"
#include "boxpile/sim/solver/penalty_parameters.hpp"

namespace boxpile {

class PenaltyMethod final : public ContactMethod {
 public:
  PenaltyMethod(const PenaltyParameters& parameters, std::size_t body_count);
  int substeps() const override { return parameters_.substeps; }
  void step(StepContext& ctx) override;
  nlohmann::json diagnostics(const StepStats& stats, const WorldCounters& counters,
                             std::size_t events) const override;
  const PenaltyParameters& parameters() const { return parameters_; }

 private:
  // The stages of the method that are its own; the rest are the world's shared stages.
  void apply_contact_forces(StepContext& ctx);
  void integrate_positions(StepContext& ctx);

  PenaltyParameters parameters_;
  FrictionAnchors anchors_;
};

}  // namespace boxpile
