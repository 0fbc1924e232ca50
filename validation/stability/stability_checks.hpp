// The checks of the hard-scene catalogue, measured the same way for every engine from the body
// states it reports after each step: energy rise, rest, turning, rebound, slide distance,
// tunnelling, penetration, finiteness. One implementation, used by `boxpile stability`,
// `boxpile compare`'s verdict and the tests (docs/stability.md says what each check means).
//
// Use: build a RunMonitor from the scene, call observe() with the states at the start (step 0)
// and after every step, then read measures() (error figures, for any tool) and evaluate() (the
// scene's checks, pass or fail). Finiteness is the run loop's (run_loop.hpp): it stops at the
// first non-finite state, which the monitor never sees, and the runner says so with stopped_non_finite().
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/metrics.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/rulers/rebound_tracker.hpp"

namespace boxpile {

// One scene check's outcome (SceneChecks): the measured value against its limit.
struct SceneCheckResult {
  std::string name;   // "energy_rise", "rest_speed", "rest_move", "no_turning", "rebound", "slide mu_0.30", ...
  double value = 0.0;
  double limit = 0.0;
  bool at_least = false;  // passes when value >= limit (else value <= limit)
  bool passed = false;
  std::string unit;  // "J", "m", "rad/s", "" for fractions
  std::string key;     // the scene's check key it comes from ("rest" for rest_speed and rest_move)
  std::string reason;  // why the limit is what it is (the scene's checks.reasons), empty if not given
};

// Error figures of one run, measured alike for every engine.
struct RunMeasures {
  bool finite = true;          // every state finite at every step observed
  long steps = 0;              // steps observed after the start
  double energy_start = 0.0;   // J, kinetic + gravitational (potential zero at the origin)
  double energy_rise = 0.0;    // largest (E - E0) / |E0| over the steps (0 if E never rose)
  double energy_rise_t = 0.0;  // s, when
  double energy_change = 0.0;  // largest |E - E0| / |E0|
  double kinetic_end = 0.0;           // J, all bodies at the end
  double kinetic_end_max_body = 0.0;  // J, the largest of one body at the end
  double speed_end_max = 0.0;         // m/s, the fastest point of any body at the end (|v| + |omega| r)
  double largest_move = 0.0;  // m, the farthest any body's position got from its start
  // The first step at which a body had moved farther than the scene's rest limit (its "collapse"),
  // unset when none did or the scene has no rest check.
  std::optional<long> moved_at_step;
  double height_error = 0.0;  // m, largest |height change| of a body at the end (along gravity)
  double drift = 0.0;         // m, largest sideways displacement of a body at the end
  double deepest_penetration = 0.0;  // m, over the run
  double max_spin = 0.0;             // rad/s, the fastest any body turned (within no_turning's window)
  std::optional<double> rebound;     // m, rise above rest height after the first impact (rebound check)
  double smallest_edge = 0.0;        // m, of any box in the scene
};

// The smallest edge of any box in the scene (m; 0 for a scene without boxes): the scale of the
// penetration check and of --tune's slops.
double smallest_edge(const Scene& scene);

class RunMonitor {
 public:
  explicit RunMonitor(const Scene& scene);

  // The finite states after `step` steps (0: the start). Cheap enough for every step: energy,
  // the deepest penetration, displacements.
  void observe(long step, const std::vector<BodyState>& states);
  // The run stopped at a non-finite state, which run_loop never hands to observe(): the measures
  // then say so, and evaluate() reports the failed "finite" check alone.
  void stopped_non_finite() { m_.finite = false; }

  const RunMeasures& measures() const { return m_; }
  // The energy and kinetic energy last observed, J (for plots).
  double energy() const { return energy_now_; }
  double kinetic() const { return kinetic_now_; }
  bool finite() const { return m_.finite; }

  // The scene's checks against the measures so far (call after the last step).
  std::vector<SceneCheckResult> evaluate() const;

 private:
  void observe_rebound(const std::vector<BodyState>& states);

  const Scene& scene_;
  std::vector<RigidBody> bodies_;
  std::vector<Vec3> start_;  // body frame positions at the start
  std::vector<double> radii_;  // m, per body: a sphere about its centre of mass that holds its boxes
  Vec3 up_ = Vec3::UnitZ();
  RunMeasures m_;
  double energy_now_ = 0.0, kinetic_now_ = 0.0;
  ReboundTracker rebound_;  // the rebound check's body, its height above the rest height
  std::vector<double> side_margins_;  // per stays_behind check, m: the least n . x - offset so far
};

// The first failed check that shows instability rather than inaccuracy: a NaN, energy that rose
// (or, e = 1, was not conserved), or resting bodies that kept moving. `boxpile compare` names an
// engine with such a failure when the other engine of a pair has none. nullptr when none failed.
const SceneCheckResult* first_instability(const std::vector<SceneCheckResult>& results);

// The check's figure against its limit, e.g. "energy_rise 0.11 > 0.0001" or "rest_move 2e-06 m <= 0.001".
std::string describe(const SceneCheckResult& result);

// Whether every result passed (an empty list passes).
bool all_passed(const std::vector<SceneCheckResult>& results);
// The first failing result, or the result that came closest to its limit when all passed: the
// figure a report shows for the cell.
const SceneCheckResult* deciding_check(const std::vector<SceneCheckResult>& results);

}  // namespace boxpile
