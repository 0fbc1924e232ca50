// The impulse method: the Guendelman-Bridson-Fedkiw step (collision loop, contact loop, shock
// propagation) with speculative contacts and penetration recovery (docs/solver.md).
#pragma once

#include <cstdint>
#include <vector>

#include "boxpile/sim/solver/contact_batches.hpp"
#include "boxpile/sim/solver/contact_method.hpp"
#include "boxpile/sim/solver/impulse.hpp"
#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/solver/islands.hpp"
#include "boxpile/sim/solver/recovery.hpp"
#include "boxpile/sim/solver/shock_propagation.hpp"
#include "boxpile/sim/solver/solver_body.hpp"
#include "boxpile/sim/step_storage.hpp"

namespace boxpile {

// How often the method's stages ran (besides its impulses' counters).
struct ImpulseMethodCounters {
  std::uint64_t same_contact_sets = 0;  // steps whose contact set was the last step's, contact for contact
  std::uint64_t collision_loop_runs = 0;
  std::uint64_t contact_loop_runs = 0;
  std::uint64_t shock_propagation_runs = 0;
  std::uint64_t recovery_runs = 0;
  ImpulseCounters impulses;
};

class ImpulseMethod final : public ContactMethod {
 public:
  ImpulseMethod(const Scene& scene, std::size_t body_count);
  bool speculative_margins() const override { return speculative_; }
  bool reuses_contacts() const override { return reuse_; }
  void step(StepContext& ctx) override;
  nlohmann::json diagnostics(std::size_t events) const override;
  const ImpulseMethodCounters& counters() const { return counters_; }
  const ImpulseStepStats& last_step_stats() const { return stats_; }

 private:
  // The stages of the method that are its own; the rest are the world's shared stages.
  void prepare_solver_contacts(const StepContext& ctx);
  void integrate_positions(StepContext& ctx);

  // What one worker of the pool keeps for itself through a step: its counts and records (added to
  // the step's once every island is solved) and the stages' scratch.
  struct Worker {
    ImpulseCounters counters;
    ImpulseStepStats stats;
    ShockPropagation::Worker shock;
    PenetrationRecovery::Worker recovery;
    ContactBatches batches;  // the contact loop's (solver.contact_batches)
  };
  // Runs stage(step, begin, end, worker) for every island [begin, end) of the contact set, on the
  // pool's threads; `step` is the worker's view of the step (its own counts and records).
  template <class Stage>
  void for_each_island(StepContext& ctx, Stage&& stage);
  // The same over groups of consecutive islands of at least kGroupContacts contacts (the last may
  // hold fewer), for the contact loop's batches.
  template <class Stage>
  void for_each_island_group(StepContext& ctx, Stage&& stage);
  // The workers' counts and records, added into the method's and the step's (sums and maxima:
  // the same whichever worker solved which island).
  void merge_workers();

  ImpulseMethodCounters counters_;
  ImpulseStepStats stats_;   // of the last step
  bool speculative_ = true;  // solver.speculative_contacts
  bool reuse_ = true;        // collision.reuse_contacts
  // The step's contacts island by island (islands_.order(): the world's index of each), and last
  // step's order, so that a contact kept from the last step is known to be at the same place.
  std::vector<SolverContact> solver_contacts_;
  Islands islands_;
  std::vector<int> last_order_;
  // Per solver contact, its bodies' shares of K and its collision matrix over both bodies as
  // prepared: shock propagation leaves some contacts with a moving body's share alone, and a
  // contact kept from the last step (StepContext::same_as_last_step) takes K back from here.
  std::vector<ContactMatrices> matrices_;
  // Whether this step's contact set is the last step's, contact for contact (every contact kept at
  // its index): shock propagation then keeps its levels and groups.
  bool same_set_ = false;
  SolverBodyArray resting_bodies_;  // the resting phases' compact bodies
  BatchVelocities batch_velocities_;  // the contact loop's, in batches (solver.contact_batches)
  std::vector<int> group_end_;        // for_each_island_group's groups: where each ends
  ShockPropagation shock_;
  PenetrationRecovery recovery_;
  std::vector<Vec3> start_v_, start_omega_;  // velocities at the step's start (explicit Euler)
  std::vector<Worker> workers_;  // one per thread of the world's pool (StepContext::pool)
};

}  // namespace boxpile
