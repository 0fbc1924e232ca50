#include "boxpile/validation/accuracy/truth_meter.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "boxpile/sim/metrics.hpp"

namespace boxpile {
namespace {

// A final state stated for a duration within this of the run's holds for it (s).
constexpr double kDurationTolerance = 1e-9;

void raise_to(std::optional<double>& worst, double value) { worst = std::max(worst.value_or(0.0), value); }

}  // namespace

double TruthMeasures::error() const {
  if (position) return *position;
  return rebound.value_or(0.0);
}

double rotation_angle(const Quat& a, const Quat& b) {
  const double w = std::min(1.0, std::abs((a.conjugate() * b).normalized().w()));
  return 2.0 * std::acos(w);
}

TruthMeter::TruthMeter(const Scene& scene) : truth_(scene.truth) {
  if (truth_.empty()) throw TruthMismatch("scene " + scene.name + " (" + scene.source + ") states no \"truth\"");
  if (truth_.has_final_states() && std::abs(scene.time.duration - truth_.duration) > kDurationTolerance) {
    throw TruthMismatch("scene " + scene.name + " (" + scene.source + "): its truth's final states hold at t = " +
                        std::to_string(truth_.duration) + " s, the run lasts " + std::to_string(scene.time.duration) +
                        " s");
  }
  up_ = -down_direction(scene.gravity);
}

void TruthMeter::observe(double t, const std::vector<BodyState>& states) {
  last_ = states;
  t_ = t;
  for (const TruthTrajectory& tr : truth_.trajectories) {
    trajectory_ = std::max(trajectory_, (states[static_cast<std::size_t>(tr.body)].position - tr.at(t)).norm());
  }
  if (!truth_.rebound) return;
  const BodyState& s = states[static_cast<std::size_t>(truth_.rebound->body)];
  rebound_.observe(s.position.dot(up_), s.velocity.dot(up_));
}

TruthMeasures TruthMeter::measures() const {
  TruthMeasures m;
  if (last_.empty()) return m;
  auto state = [&](int body) -> const BodyState& { return last_[static_cast<std::size_t>(body)]; };
  for (const TruthPoint& p : truth_.final_positions) raise_to(m.position, (state(p.body).position - p.value).norm());
  for (const TruthTrajectory& tr : truth_.trajectories) raise_to(m.position, (state(tr.body).position - tr.at(t_)).norm());
  for (const TruthPoint& p : truth_.final_velocities) raise_to(m.velocity, (state(p.body).velocity - p.value).norm());
  for (const TruthOrientation& o : truth_.final_orientations) {
    raise_to(m.orientation, rotation_angle(o.orientation, state(o.body).orientation));
  }
  if (!truth_.trajectories.empty()) m.trajectory = trajectory_;
  if (truth_.rebound) {
    // No bounce at all: the body's last height against the apex it should have reached.
    const double reached = rebound_.apex() ? *rebound_.apex() : state(truth_.rebound->body).position.dot(up_);
    m.rebound = std::abs(reached - truth_.rebound->height);
  }
  return m;
}

}  // namespace boxpile
