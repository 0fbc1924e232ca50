// stays_behind: each listed body's centre stays where normal . x >= offset at every step: in
// front of a plate it must not pass (tunnelling).
#include "boxpile/validation/stability/checks/check.hpp"

#include <algorithm>
#include <limits>

namespace boxpile {

using json_input::JsonNode;
namespace {

class StaysBehindCheck final : public Check {
 public:
  explicit StaysBehindCheck(std::vector<PlaneSide> sides) : sides_(std::move(sides)), least_(sides_.size()) {}

  void observe(const RunView&, long step, double, const std::vector<BodyState>& states) override {
    for (std::size_t k = 0; k < sides_.size(); ++k) {
      if (step == 0) least_[k] = std::numeric_limits<double>::infinity();
      least_[k] = std::min(least_[k], side_margin(sides_[k], states[static_cast<std::size_t>(sides_[k].body)]));
    }
  }
  void evaluate(const RunView& run, std::vector<SceneCheckResult>& out) const override {
    for (std::size_t k = 0; k < sides_.size(); ++k)
      out.push_back(at_least("stays_behind " + run.scene.bodies[static_cast<std::size_t>(sides_[k].body)].name,
                             least_[k], 0.0, "m"));
  }

 private:
  std::vector<PlaneSide> sides_;
  std::vector<double> least_;  // m, per side: the least margin so far
};

std::unique_ptr<Check> read_stays_behind(const std::optional<JsonNode>& node, const Scene& scene) {
  return std::make_unique<StaysBehindCheck>(read_plane_sides(*node, scene));
}

}  // namespace

const CheckRow& stays_behind_check() {
  static const CheckRow row{"stays_behind",
                            "each listed body's centre stays where normal . x >= offset (m) at every step", 80, false,
                            true, read_stays_behind};
  return row;
}

}  // namespace boxpile
