// rebound: after its first impact the body's centre rises to rest_height + height (the analytic
// e^2 h), within the relative tolerance; no bounce at all counts as an error of 1.
#include "boxpile/validation/stability/checks/check.hpp"

#include <cmath>

#include "boxpile/validation/rulers/rebound_tracker.hpp"

namespace boxpile {

using json_input::JsonNode;
namespace {

class ReboundCheck final : public Check {
 public:
  ReboundCheck(int body, double rest_height, double height, double tolerance)
      : body_(body), rest_height_(rest_height), height_(height), tolerance_(tolerance) {}

  void observe(const RunView& run, long step, double, const std::vector<BodyState>& states) override {
    if (step == 0) tracker_ = ReboundTracker{};
    const BodyState& s = states[static_cast<std::size_t>(body_)];
    tracker_.observe(s.position.dot(run.up) - rest_height_, s.velocity.dot(run.up));
  }
  void evaluate(const RunView&, std::vector<SceneCheckResult>& out) const override {
    const std::optional<double> rise = tracker_.apex();
    const double error = rise ? std::abs(*rise - height_) / height_ : 1.0;
    out.push_back(at_most("rebound", error, tolerance_, ""));
  }
  void record(RunMeasures& m) const override { m.rebound = tracker_.apex(); }

 private:
  int body_;
  double rest_height_, height_, tolerance_;
  ReboundTracker tracker_;  // the body's height above rest_height
};

std::unique_ptr<Check> read_rebound(const std::optional<JsonNode>& node, const Scene& scene) {
  node->expect_object({"body", "rest_height", "height", "tolerance"});
  const int body = read_check_body(node->at("body"), scene);
  const double rest_height = node->at("rest_height").number();
  const double height = json_input::read_positive(node->at("height"));
  double tolerance = 0.05;
  if (const auto t = node->find("tolerance")) tolerance = json_input::read_positive(*t);
  return std::make_unique<ReboundCheck>(body, rest_height, height, tolerance);
}

}  // namespace

const CheckRow& rebound_check() {
  static const CheckRow row{"rebound",
                            "after its first impact the body's centre rises to rest_height + height (m), within "
                            "the relative tolerance (default 0.05)",
                            60, false, true, read_rebound};
  return row;
}

}  // namespace boxpile
