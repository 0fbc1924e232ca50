// Penetration recovery by split impulses: overlaps left by impacts are pushed apart through
// pseudo-velocities that move positions but never enter the momenta, so recovery adds no kinetic
// energy (the "split impulse" of Catto's and Coumans' solvers, in place of a Baumgarte bias).
// Not part of the Guendelman-Bridson-Fedkiw method, which has no position correction; it is a
// solver setting (`penetration_recovery`, 0 turns it off).
#pragma once

#include <array>
#include <limits>
#include <span>
#include <vector>

#include "boxpile/sim/solver/body_groups.hpp"
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
  // both bodies movable; each phase as groups that share no moving body, each in at most
  // `recovery_passes` sequential passes, fewer once converged (or, in a shock level, stalled:
  // the phase with every body movable takes it up). Fills pseudo_v and pseudo_omega (per body).
  void run(const ImpulseStep& step, const ShockPropagation* shock);

  // A contact of the phase being solved, with what its passes read.
  struct PhaseContact {
    int index = 0;  // in step.contacts
    int a = 0, b = 0;  // its bodies (kGround: the ground)
    bool a_moves = false, b_moves = false;
    double inv_k_nn = 0.0;  // 1 / (n . K n) over the bodies that move
    double change_scale = 0.0;  // (n . K n) dt / slop: |change| times it is the pass's change term
  };
  // What a worker keeps for itself while it solves an island: the phase's contacts and groups.
  struct Worker {
    void reserve(const StepStorage& storage);
    std::vector<PhaseContact> phase;
    std::vector<PhaseContact> grouped;  // phase by group
    BodyGroups groups;                  // the phase's groups
    int skipped_phases = 0;
  };
  // A run in parts: `prepare` sets every contact's target and clears the pseudo-velocities (false:
  // no contact asks for a push, and nothing is left to solve), reading the velocities from
  // step.resting, which must hold the bodies' present ones (run gathers them); then `solve_island`
  // solves the contacts [begin, end) of the set, an island (islands.hpp), phase after phase. Islands share no
  // moving body, so they may be solved at once on several threads, each with a worker of its own.
  bool prepare(const ImpulseStep& step);
  void solve_island(const ImpulseStep& step, const ShockPropagation* shock, int begin, int end, Worker& worker);

  const std::vector<Vec3>& pseudo_v() const { return pseudo_v_; }
  const std::vector<Vec3>& pseudo_omega() const { return pseudo_omega_; }
  // Phases of the last run skipped whole because none of their contacts could change, and whether
  // such phases are skipped (the default; off, they run their first pass, which changes nothing:
  // the tests compare the two).
  int skipped_phases() const { return own_.skipped_phases; }
  void skip_idle_phases(bool on) { skip_idle_phases_ = on; }

 private:
  // The separating pseudo-velocity contact `c` asks for, m/s (see the .cpp).
  static double pseudo_target(const SolverBodyArray& sb, const SolverContact& c, double beta, double dt);
  // Whether contact k (between bodies a and b) may change in a pass: it asks for a push, has one,
  // or a body of it has been pushed. One that may not would stay at zero.
  bool may_change(int k, int a, int b) const {
    return target_[k] > 0.0 || lambda_[k] != 0.0 || (a >= 0 && pushed_[a]) || (b >= 0 && pushed_[b]);
  }
  // n . K n of contacts[k] over the bodies that move (at least one), formed once per run for each
  // of A alone, B alone and both.
  double normal_mass(const ImpulseStep& step, int k, bool a_moves, bool b_moves);

  // One phase: `contacts` with bodies below `level` frozen (none without `shock`), solved as groups
  // that share no moving body, each by its passes until it converges.
  void solve_phase(const ImpulseStep& step, std::span<const int> contacts, const ShockPropagation* shock, int level,
                   Worker& worker);
  // The phase's contacts with which of their bodies move.
  void collect_phase(const ImpulseStep& step, std::span<const int> contacts, const ShockPropagation* shock, int level,
                     std::vector<PhaseContact>& phase);
  // The passes over one group, until it converges, `recovery_passes` have run, or (with
  // `stop_stalled`) it stalls: kRecoveryStallPasses passes in a row without progress.
  void solve_group(const ImpulseStep& step, std::span<const PhaseContact> group, bool stop_stalled);

  std::vector<Vec3> pseudo_v_, pseudo_omega_;
  std::vector<char> pushed_;    // per body, whether a pseudo-impulse has reached it this step
  std::vector<double> lambda_;  // per contact, its pseudo-impulse so far
  std::vector<double> target_;  // per contact, the separating pseudo-velocity it asks for, m/s
  // Per contact, n . K n with A's share alone, B's alone and both (NaN until a phase asks): each
  // contact is in two phases, often with the same bodies moving in both.
  std::vector<std::array<double, 3>> normal_mass_;
  static constexpr std::array<double, 3> kNormalMassUnset = {std::numeric_limits<double>::quiet_NaN(),
                                                             std::numeric_limits<double>::quiet_NaN(),
                                                             std::numeric_limits<double>::quiet_NaN()};
  bool skip_idle_phases_ = true;
  std::vector<int> all_;  // every contact of the step
  Worker own_;            // run's worker
};

}  // namespace boxpile
