// Penetration recovery by split impulses: overlaps left by impacts are pushed apart through
// pseudo-velocities that move positions but never enter the momenta, so recovery adds no kinetic
// energy (the "split impulse" of Catto's and Coumans' solvers, in place of a Baumgarte bias).
// Not part of the Guendelman-Bridson-Fedkiw method, which has no position correction; it is a
// solver setting (`penetration_recovery`, 0 turns it off).
#pragma once

#include <span>
#include <vector>

#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/solver/shock_propagation.hpp"
#include "boxpile/sim/step_storage.hpp"

namespace boxpile {

class PenetrationRecovery {
 public:
  // Sizes the pseudo-velocities and the pseudo-impulses for `storage`.
  void reserve(const StepStorage& storage);
  // Solves for normal pseudo-impulses lambda >= 0 that give each contact deeper than
  // `penetration_slop` the separating pseudo-velocity beta (depth - slop) / dt (beta =
  // `penetration_recovery`) and keep every contact from ending the step deeper than the slop,
  // counting the velocities the step resolved. With `shock`'s levels (nullptr: shock propagation
  // is off) each level from the ground up with the lower ones frozen, then every contact with
  // both bodies movable; each phase in at most `recovery_passes` sequential passes, fewer once
  // converged. Fills pseudo_v and pseudo_omega (per body).
  void run(const ImpulseStep& step, const ShockPropagation* shock);

  const std::vector<Vec3>& pseudo_v() const { return pseudo_v_; }
  const std::vector<Vec3>& pseudo_omega() const { return pseudo_omega_; }

 private:
  // The separating pseudo-velocity contact `c` asks for, m/s (see the .cpp).
  static double pseudo_target(const SolverBodies& sb, const SolverContact& c, double beta, double dt);
  // The passes over one group of contacts; bodies below `level` are frozen (none without `shock`).
  void solve_phase(const ImpulseStep& step, std::span<const int> group, const ShockPropagation* shock, int level);

  // A contact of the phase being solved, with what its passes read.
  struct PhaseContact {
    int index = 0;  // in step.contacts
    bool a_moves = false, b_moves = false;
    double inv_k_nn = 0.0;  // 1 / (n . K n) over the bodies that move
  };

  std::vector<Vec3> pseudo_v_, pseudo_omega_;
  // The passes' clock: one tick per contact visited this step. A contact visited with no change,
  // whose bodies no pseudo-impulse has reached since, would come out unchanged again: skipped.
  long clock_ = 0;
  std::vector<long> pushed_at_;  // per body, the tick of its last pseudo-impulse this step (-1: none)
  std::vector<long> still_at_;   // per contact, the tick it was last visited without change (-1: none)
  std::vector<double> lambda_;   // per contact, its pseudo-impulse so far
  std::vector<double> target_;  // per contact, the separating pseudo-velocity it asks for, m/s
  std::vector<int> all_;        // every contact of the step
  std::vector<PhaseContact> phase_;
};

}  // namespace boxpile
