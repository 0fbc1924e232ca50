// A run measured against its scene's truth (sim/scene.hpp, SceneTruth; docs/accuracy.md): the
// bodies' final states against the stated ones, each trajectory's deviation over the run, the
// rebound's height. From body states alone, so that every engine is measured by one ruler.
#pragma once

#include <optional>
#include <stdexcept>
#include <vector>

#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/rulers/rebound_tracker.hpp"

namespace boxpile {

struct TruthMeasures {
  // m: the largest distance of a body's final position from the truth's (final_positions, and
  // each trajectory at the run's end); unset when the truth states no position.
  std::optional<double> position;
  std::optional<double> velocity;     // m/s: the largest final velocity error (final_velocities)
  std::optional<double> orientation;  // rad: the largest final rotation error (final_orientations)
  std::optional<double> trajectory;   // m: the largest deviation from a trajectory over the run
  std::optional<double> rebound;      // m: |apex after the first impact - truth's| (no bounce: the last height's)
  // The headline error, m: `position`, or the rebound's error when the truth states no position.
  double error() const;
};

// The truth's final states hold at the scene's duration only: a run of another length cannot be
// measured against them.
class TruthMismatch : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class TruthMeter {
 public:
  // `scene` states a truth (TruthMismatch when it states none, or final states for another
  // duration than the scene's).
  explicit TruthMeter(const Scene& scene);
  // Every state of the run, the start (t = 0) included.
  void observe(double t, const std::vector<BodyState>& states);
  // The measures at the end of the run (the last states observed).
  TruthMeasures measures() const;

 private:
  const SceneTruth& truth_;
  Vec3 up_ = Vec3::UnitZ();
  std::vector<BodyState> last_;
  double t_ = 0.0;
  double trajectory_ = 0.0;
  ReboundTracker rebound_;  // the truth's rebound body
};

// The angle (rad) of the rotation from `a` to `b`.
double rotation_angle(const Quat& a, const Quat& b);

}  // namespace boxpile
