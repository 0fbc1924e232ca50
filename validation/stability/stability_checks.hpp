// The checks of the hard-scene catalogue, measured the same way for every engine from the body
// states it reports after each step: finiteness, and each check the scene holds (one file each
// in validation/stability/checks/: energy rise, penetration, rest, turning, rebound, slide
// distance, tunnelling, an end position). One implementation, used by `boxpile stability`,
// `boxpile compare`'s verdict and the tests (docs/stability.md says what each check means).
//
// Use: build a RunMonitor from the scene (it reads the scene's checks, scene_checks.hpp), call observe() with the states at the start (step 0)
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
#include "boxpile/validation/stability/scene_checks.hpp"

namespace boxpile {

// The smallest edge of any box in the scene (m; 0 for a scene without boxes): the scale of the
// penetration check and of --tune's slops.
double smallest_edge(const Scene& scene);

class RunMonitor {
 public:
  // Throws InputError when the scene's checks do not read (load_checked_scene() refuses them first).
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
  RunView view() const { return {scene_, up_, start_, m_}; }

  const Scene& scene_;
  SceneCheckSet checks_;
  std::vector<RigidBody> bodies_;
  std::vector<Vec3> start_;  // body frame positions at the start
  std::vector<double> radii_;  // m, per body: a sphere about its centre of mass that holds its boxes
  Vec3 up_ = Vec3::UnitZ();
  RunMeasures m_;
  double energy_now_ = 0.0, kinetic_now_ = 0.0;
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
