// no_turning: no body turns faster than limit (rad/s), up to `until` (s; the whole run when not
// given): a symmetric impact gives no torque, so any turning is the solver's.
#include "boxpile/validation/stability/checks/check.hpp"

#include <algorithm>

namespace boxpile {

using json_input::JsonNode;
namespace {

class NoTurningCheck final : public Check {
 public:
  NoTurningCheck(double limit, std::optional<double> until) : limit_(limit), until_(until) {}

  void observe(const RunView& run, long step, double t, const std::vector<BodyState>& states) override {
    if (step == 0) spin_ = 0.0;
    if (until_ && t > *until_ + 0.5 * run.scene.time.dt) return;
    for (std::size_t i = 0; i < states.size(); ++i)
      if (!run.scene.bodies[i].fixed) spin_ = std::max(spin_, states[i].angular_velocity.norm());
  }
  void evaluate(const RunView&, std::vector<SceneCheckResult>& out) const override {
    out.push_back(at_most("no_turning", spin_, limit_, "rad/s"));
  }
  void record(RunMeasures& m) const override { m.max_spin = spin_; }

 private:
  double limit_;
  std::optional<double> until_;
  double spin_ = 0.0;  // rad/s, the fastest turn within the window so far
};

std::unique_ptr<Check> read_no_turning(const std::optional<JsonNode>& node, const Scene&) {
  node->expect_object({"limit", "until"});
  double limit = 1e-3;
  std::optional<double> until;
  if (const auto l = node->find("limit")) limit = json_input::read_positive(*l);
  if (const auto u = node->find("until")) until = json_input::read_non_negative(*u);
  return std::make_unique<NoTurningCheck>(limit, until);
}

}  // namespace

const CheckRow& no_turning_check() {
  static const CheckRow row{"no_turning",
                            "no body turns faster than limit (rad/s, default 1e-3), up to until (s; the whole run "
                            "when not given)",
                            50, false, true, read_no_turning};
  return row;
}

}  // namespace boxpile
