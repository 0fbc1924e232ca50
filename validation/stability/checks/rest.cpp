// rest: a scene that starts at rest stays there. No body's position ever moves farther than
// max_move (m) from its start, and at the end the fastest point of any body (|v| + |omega| r, r
// its farthest box corner from its centre of mass) is slower than speed (m/s): judged by speed,
// not kinetic energy, so that a 1,000 kg box and a 1 kg one are held to the same motion.
#include "boxpile/validation/stability/checks/check.hpp"

namespace boxpile {

using json_input::JsonNode;
namespace {

class RestCheck final : public Check {
 public:
  RestCheck(double speed, double max_move) : speed_(speed), max_move_(max_move) {}

  void observe(const RunView& run, long step, double, const std::vector<BodyState>&) override {
    if (step == 0) moved_at_step_.reset();
    if (!moved_at_step_ && run.measures.largest_move > max_move_) moved_at_step_ = step;
  }
  void evaluate(const RunView& run, std::vector<SceneCheckResult>& out) const override {
    out.push_back(at_most("rest_speed", run.measures.speed_end_max, speed_, "m/s"));
    out.push_back(at_most("rest_move", run.measures.largest_move, max_move_, "m"));
  }
  void record(RunMeasures& m) const override { m.moved_at_step = moved_at_step_; }

 private:
  double speed_, max_move_;
  std::optional<long> moved_at_step_;  // the first step past max_move, the pile's "collapse"
};

std::unique_ptr<Check> read_rest(const std::optional<JsonNode>& node, const Scene&) {
  if (node->has("kinetic_per_body"))
    node->at("kinetic_per_body").fail("is no longer a check: rest is judged by speed, \"speed\" (m/s)");
  node->expect_object({"speed", "max_move"});
  double speed = 1e-3, max_move = 1e-3;
  if (const auto k = node->find("speed")) speed = json_input::read_positive(*k);
  if (const auto m = node->find("max_move")) max_move = json_input::read_positive(*m);
  return std::make_unique<RestCheck>(speed, max_move);
}

}  // namespace

const CheckRow& rest_check() {
  static const CheckRow row{"rest",
                            "no body moves farther than max_move (m, default 1e-3) from its start, and at the end "
                            "no point of a body is faster than speed (m/s, default 1e-3)",
                            40, false, true, read_rest};
  return row;
}

}  // namespace boxpile
