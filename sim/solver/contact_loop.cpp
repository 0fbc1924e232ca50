#include "boxpile/sim/solver/contact_loop.hpp"

#include <algorithm>
#include <cassert>

namespace boxpile {

void contact_loop(ImpulseStep& step, std::span<SolverContact> contacts, ContactBatches* batches,
                  BatchVelocities* velocities) {
  SolverBodyArray& sb = step.resting;
  const int passes = step.settings().contact_passes;
  const double dt = step.dt();
  const bool accumulated = step.settings().accumulated_impulses;
  assert(passes <= kMaxSolverPasses);
  for (SolverContact& c : contacts) begin_resting_phase(c, sb.relative_velocity(c));
  // solver.contact_batches: the accumulated impulses of batches of four contacts that share no
  // moving body, updated at once on the velocities (contact_batches.hpp), where the batches fill
  // enough lanes to pay; a chain of contacts (a stack: each pair shares a box with the next) fills
  // one lane a batch and runs one contact at a time. (Push-only impulses run one at a time: the
  // batches' order is the search's for every body, so they would change nothing.)
  bool batched = batches != nullptr && accumulated;
  if (batched) {
    batches->build(contacts, sb, dt, step.friction());
    batched = batches->pays();
    if (batched) batches->touch_bodies(*velocities);
  }
  const bool avx2 = contact_batches_use_avx2();
  for (int pass = 0; pass < passes; ++pass) {
    // e = -1 would leave velocities unchanged; the ramp starts one step above it and ends at 0,
    // slowing resting contacts gradually instead of stopping the first one met at full force.
    // Pass k asks each approaching point for u_n >= -e_k u_n(start).
    const double e = -1.0 + static_cast<double>(pass + 1) / passes;
    // The residual of a pass is the largest approach met in it, each contact measured just
    // before its impulse (free: the velocity is needed anyway).
    double residual = 0.0;
    if (batched) {
      residual = batches->pass(*velocities, e, step.counters(), avx2);
    } else {
      const std::size_t count = contacts.size();
      for (std::size_t q = 0; q < count; ++q) {
        SolverContact& c = contacts[q];
        const Vec3 u = sb.relative_velocity(c);
        residual = std::max(residual, allow_gap(c, 0.0, dt) - c.n.dot(u));
        // Ours asks u_n >= -e_k u_n(start) of the impulse accumulated over the phase; the lab
        // text's gives the push-only Newton-Coulomb impulse of restitution e_k on the present u_n
        // (u_n >= -e_k u_n, a speculative point's gap allowed for as in ours).
        const double approach_un = accumulated ? c.start_un : c.n.dot(u);
        const double target = allow_gap(c, approach_un < 0.0 ? -e * approach_un : 0.0, dt);
        const Vec3 j = accumulated ? resting_impulse(c, u, target, step.friction(), step.counters())
                                   : push_impulse(c, u, target, step.friction(), step.counters());
        if (!is_exact_zero(j)) sb.apply(c, j);  // a zero impulse would leave every velocity as it is
      }
    }
    // Islands run apart: the step's residual after a pass is the largest of theirs.
    step.stats().contact_residual[pass] = std::max(step.stats().contact_residual[pass], residual);
    step.stats().contact_passes_used = pass + 1;
  }
  if (batched) batches->finish(contacts);
}

}  // namespace boxpile
