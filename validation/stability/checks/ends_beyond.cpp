// ends_beyond: each listed body's centre ends where normal . x >= offset: a ram that must break
// through a wall ends past the wall's far face.
#include "boxpile/validation/stability/checks/check.hpp"

namespace boxpile {

using json_input::JsonNode;
namespace {

class EndsBeyondCheck final : public Check {
 public:
  explicit EndsBeyondCheck(std::vector<PlaneSide> sides) : sides_(std::move(sides)), last_(sides_.size()) {}

  void observe(const RunView&, long, double, const std::vector<BodyState>& states) override {
    for (std::size_t k = 0; k < sides_.size(); ++k)
      last_[k] = side_margin(sides_[k], states[static_cast<std::size_t>(sides_[k].body)]);
  }
  void evaluate(const RunView& run, std::vector<SceneCheckResult>& out) const override {
    for (std::size_t k = 0; k < sides_.size(); ++k)
      out.push_back(at_least("ends_beyond " + run.scene.bodies[static_cast<std::size_t>(sides_[k].body)].name,
                             last_[k], 0.0, "m"));
  }

 private:
  std::vector<PlaneSide> sides_;
  std::vector<double> last_;  // m, per side: the margin last observed
};

std::unique_ptr<Check> read_ends_beyond(const std::optional<JsonNode>& node, const Scene& scene) {
  return std::make_unique<EndsBeyondCheck>(read_plane_sides(*node, scene));
}

}  // namespace

const CheckRow& ends_beyond_check() {
  static const CheckRow row{"ends_beyond", "each listed body's centre ends where normal . x >= offset (m)", 90, false,
                            true, read_ends_beyond};
  return row;
}

}  // namespace boxpile
