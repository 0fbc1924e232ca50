#include "boxpile/sim/solver/contact_loop.hpp"

#include <algorithm>
#include <cassert>

namespace boxpile {

void ContactLoop::run(ImpulseStep& step) {
  SolverBodyArray& sb = step.resting;
  sb.gather(step.sb.bodies);
  const int passes = step.settings().contact_passes;
  const double dt = step.dt();
  assert(passes <= kMaxSolverPasses);
  // The lab text's "remaining non-separating contacts in the original contact set": a point that
  // separates, or whose gap stays open at its speed, by more than rounding takes no part (13% off
  // the tumbling pile's step). Points at rest stay in, though their start may separate by
  // rounding: left out, the loop pushed a card of the card house away from the one it leans on,
  // and the house fell. Shock propagation, which follows, solves every contact of the bodies the
  // ground supports again.
  resting_.clear();
  for (int k = 0; k < static_cast<int>(step.contacts.size()); ++k) {
    SolverContact& c = step.contacts[k];
    begin_resting_phase(c, sb.relative_velocity(c));
    if (c.start_un <= allow_gap(c, 0.0, dt) + kRestingSpeed) resting_.push_back(k);
  }
  for (int pass = 0; pass < passes; ++pass) {
    // e = -1 would leave velocities unchanged; the ramp starts one step above it and ends at 0,
    // slowing resting contacts gradually instead of stopping the first one met at full force.
    // Pass k asks each approaching point for u_n >= -e_k u_n(start).
    const double e = -1.0 + static_cast<double>(pass + 1) / passes;
    // The residual of a pass is the largest approach met in it, each contact measured just
    // before its impulse (free: the velocity is needed anyway).
    double residual = 0.0;
    for (const int k : resting_) {
      SolverContact& c = step.contacts[k];
      const Vec3 u = sb.relative_velocity(c);
      residual = std::max(residual, allow_gap(c, 0.0, dt) - c.n.dot(u));
      const double target = allow_gap(c, c.start_un < 0.0 ? -e * c.start_un : 0.0, dt);
      const Vec3 j = resting_impulse(c, u, target, step.friction(), step.counters());
      if (!is_exact_zero(j)) sb.apply(c, j);  // a zero impulse would leave every velocity as it is
    }
    step.stats().contact_residual[pass] = residual;
    step.stats().contact_passes_used = pass + 1;
  }
  sb.scatter(step.sb.bodies);
}

}  // namespace boxpile
