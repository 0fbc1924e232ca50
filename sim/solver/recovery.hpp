// Penetration recovery by split impulses: overlaps left by impacts are pushed apart through
// pseudo-velocities that move positions but never enter the momenta, so recovery adds no kinetic
// energy (the "split impulse" of Catto's and Coumans' solvers, in place of a Baumgarte bias).
// Not part of the Guendelman-Bridson-Fedkiw method, which has no position correction; it is a
// solver setting (`penetration_recovery`, 0 turns it off).
#pragma once

#include <vector>

#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/step_storage.hpp"

namespace boxpile {

class PenetrationRecovery {
 public:
  // Sizes the pseudo-velocities and the pseudo-impulses for `storage`.
  void reserve(const StepStorage& storage);
  // Solves, in `recovery_passes` sequential passes over the contacts deeper than
  // `penetration_slop`, for normal pseudo-impulses lambda >= 0 that give each point the
  // separating pseudo-velocity beta (depth - slop) / dt, beta = `penetration_recovery`. Fills
  // pseudo_v and pseudo_omega (per body).
  void run(const ImpulseStep& step);

  const std::vector<Vec3>& pseudo_v() const { return pseudo_v_; }
  const std::vector<Vec3>& pseudo_omega() const { return pseudo_omega_; }

 private:
  std::vector<Vec3> pseudo_v_, pseudo_omega_;
  std::vector<double> lambda_;
};

}  // namespace boxpile
