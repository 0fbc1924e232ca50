// The contact loop four contacts at a time (solver.contact_batches).
//
// The contacts of a group of islands are regrouped into batches of kBatchLanes contacts that
// share no moving body: each contact, in the search's order, joins the first batch with a free
// lane after every batch that holds one of its moving bodies. So each body still meets its
// contacts in the search's order, and the batches' sweep is the sequential sweep in that order
// (only contacts that share no body trade places, which changes nothing), with four updates in
// flight instead of one chain.
//
// The update is the contact loop's projected Gauss-Seidel step on the impulse accumulated over
// the phase (resting_impulse's, without its shortcuts, which only skip work), applied to the
// bodies' velocities directly (dv = j / m, d omega = I^-1 (r x j), I^-1 [r]x formed once per
// step) instead of through the momenta: the same impulses up to rounding, with half the state.
// A body's velocities live in one 64-byte line (BatchVelocities), read and written four bodies at
// once; its momenta are formed from them when the loop ends.
//
// The arithmetic is written on four-lane vectors (GCC's vector extensions) and compiled twice,
// for AVX2 and for the baseline x86-64 (SSE2), the first chosen at run time when the processor
// has it; neither contracts a product and a sum into one rounding, so both give the same bits.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/solver/impulse.hpp"
#include "boxpile/sim/solver/solver_body.hpp"

namespace boxpile {

inline constexpr int kBatchLanes = 4;

// A body's velocities as the batches read them.
struct alignas(64) BatchVelocity {
  double v[3] = {0.0, 0.0, 0.0};
  double omega[3] = {0.0, 0.0, 0.0};
  double unused[2] = {0.0, 0.0};
};

// Every body's velocities (slot 0: the ground, at rest), shared by the workers: a group's
// batches write only its own bodies.
class BatchVelocities {
 public:
  void reserve(std::size_t bodies) {
    velocity_.reserve(bodies + 1);
    touched_.reserve(bodies + 1);
  }
  // Copies the velocities of `sb` (bodies 0 .. count - 1 and the ground) and marks every body
  // untouched.
  void gather(const SolverBodyArray& sb, int count);
  // Writes the touched bodies' velocities back into `sb`, with the momenta they imply
  // (P = m v, L = R I R^T omega, as RigidBody::set_velocity forms them).
  void scatter(SolverBodyArray& sb, const std::vector<RigidBody>& bodies) const;
  BatchVelocity& at(int body) { return velocity_[static_cast<std::size_t>(body + 1)]; }
  const BatchVelocity& at(int body) const { return velocity_[static_cast<std::size_t>(body + 1)]; }
  void touch(int body) { touched_[static_cast<std::size_t>(body + 1)] = 1; }

 private:
  std::vector<BatchVelocity> velocity_;
  std::vector<unsigned char> touched_;
};

// One batch: field[k][lane] for each component k.
struct alignas(32) ContactBatch {
  double n[3][kBatchLanes];
  double Wa[9][kBatchLanes], Wb[9][kBatchLanes];  // row-major, W = [r]x^T (zero on the ground's side)
  double Ma[9][kBatchLanes], Mb[9][kBatchLanes];  // row-major, I^-1 [r]x: d omega per unit impulse
  double ma[kBatchLanes], mb[kBatchLanes];        // inverse masses (zero for a body that does not move)
  double Kinv[6][kBatchLanes];                    // upper triangle, row by row (K^-1 is symmetric)
  double Kn[3][kBatchLanes];                      // K n (K is symmetric: n . K x = Kn . x)
  double nKn[kBatchLanes];                        // n . K n (frictionless points)
  double dir[3][kBatchLanes], denom[kBatchLanes];  // n - mu t and n . K (n - mu t) (sliding points)
  double friction[kBatchLanes];
  double gap_speed[kBatchLanes];  // depth / dt for a gap (depth < 0), else +inf: allow_gap's bound
  double start_un[kBatchLanes];
  double acc[3][kBatchLanes];     // the impulse accumulated over the phase
  // Lane flags, all ones or zero (vector masks).
  std::int64_t real[kBatchLanes];        // the lane holds a contact
  std::int64_t frictional[kBatchLanes];  // friction on and mu > 0
  std::int64_t slide_zero[kBatchLanes];  // no sliding direction at the phase's start
  std::int64_t push_a[kBatchLanes], push_b[kBatchLanes];  // the body moves under an impulse
  int a[kBatchLanes], b[kBatchLanes];    // bodies (kGround for the ground)
  int contact[kBatchLanes];              // index in the group's contacts, -1 for an empty lane
};

class ContactBatches {
 public:
  // Room for `contacts` contacts in `batches` batches among `bodies` bodies, so that building them
  // allocates nothing.
  void reserve(std::size_t contacts, std::size_t batches, std::size_t bodies) {
    batches_.reserve(batches);
    lanes_.reserve(batches);
    slot_.reserve(contacts);
    after_.assign(bodies + 1, 0);
  }
  // Regroups `contacts` (whose resting phase has begun: start_un, slide_dir, accumulated set) into
  // batches, reading the bodies' inverse masses and inertias from `sb`; fills their lanes only when
  // they pay (pays()), or always with `fill_always` (the tests).
  void build(std::span<const SolverContact> contacts, const SolverBodyArray& sb, double dt, bool friction,
             bool fill_always = false);
  // Whether the batches hold enough contacts to be cheaper than the contacts one at a time: a
  // batch's update costs some 2.3 single updates (pile_100, AVX2), so at least kPayingLanes of
  // its four lanes must be filled on average.
  static constexpr double kPayingLanes = 2.5;
  bool pays() const { return static_cast<double>(contacts_) >= kPayingLanes * static_cast<double>(used_); }
  // Marks the batches' moving bodies touched in `velocities` (the passes will update them).
  void touch_bodies(BatchVelocities& velocities) const;
  // One pass of restitution e over the batches: updates the velocities and each lane's accumulated
  // impulse, counts the updates as resting_impulse does, and returns the largest approach met (the
  // contact loop's residual). `avx2` chooses the AVX2 code (only where the processor has it:
  // contact_batches_use_avx2) or the baseline's; both give the same bits.
  double pass(BatchVelocities& velocities, double e, ImpulseCounters& counters, bool avx2);
  // Writes each contact's accumulated impulse back.
  void finish(std::span<SolverContact> contacts) const;

  int batches() const { return static_cast<int>(used_); }
  // The batches, once filled (none when build found they would not pay).
  std::span<const ContactBatch> all() const { return {batches_.data(), filled_ ? used_ : 0}; }
  // The contacts in the batches' order (the sequential sweep this is).
  void order(std::vector<int>& out) const;

 private:
  std::vector<ContactBatch> batches_;  // the first used_ hold this phase's batches
  std::size_t used_ = 0;
  std::size_t contacts_ = 0;
  bool filled_ = false;
  std::vector<int> lanes_;             // lanes filled, per batch
  std::vector<int> slot_;              // per contact: its batch times kBatchLanes plus its lane
  std::vector<std::size_t> after_;     // per body slot: 1 + the last batch holding it (0: none yet)
};

// Whether this processor runs AVX2 (the contact loop's batches then use it).
bool contact_batches_use_avx2();

}  // namespace boxpile
