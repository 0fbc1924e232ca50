// The penalty method (the lab text, "Penalty based simulation method"; docs/penalty.md): at each
// contact point a damped spring along the normal and a friction spring to an anchor, forces and
// torques summed per body, and symplectic Euler (momenta first, then positions with the new
// velocities) over `substeps` steps per scene step.
#pragma once

#include <cstdint>
#include <vector>

#include "boxpile/sim/solver/contact_method.hpp"
#include "boxpile/sim/solver/friction_anchors.hpp"
#include "boxpile/sim/solver/penalty_parameters.hpp"

namespace boxpile {

// What the penalty method did: the tests check that its anchors follow the contacts.
struct PenaltyCounters {
  std::uint64_t substeps = 0;            // penalty steps taken
  std::uint64_t spring_evaluations = 0;  // contact points that carried a spring force
  std::uint64_t anchors_created = 0;     // contacts that began (a new friction anchor)
  std::uint64_t sliding_points = 0;      // points whose anchor was dragged (sliding friction)
};

class PenaltyMethod final : public ContactMethod {
 public:
  PenaltyMethod(const PenaltyParameters& parameters, std::size_t body_count);
  int substeps() const override { return parameters_.substeps; }
  void step(StepContext& ctx) override;
  nlohmann::json diagnostics(std::size_t events) const override;
  const PenaltyCounters& counters() const { return counters_; }
  const PenaltyParameters& parameters() const { return parameters_; }

 private:
  // The stages of the method that are its own; the rest are the world's shared stages.
  void apply_contact_forces(StepContext& ctx);
  void integrate_positions(StepContext& ctx);

  PenaltyParameters parameters_;
  FrictionAnchors anchors_;
  PenaltyCounters counters_;
};

}  // namespace boxpile
