// penetration: the deepest overlap over the run (between bodies and with the ground) stays below
// this fraction of the scene's smallest box edge. Held in every scene (default 0.01).
#include "boxpile/validation/stability/checks/penetration.hpp"

#include "boxpile/validation/stability/scene_checks.hpp"

namespace boxpile {

using json_input::JsonNode;
namespace {

constexpr double kDefaultFraction = 0.01;

class PenetrationCheck final : public Check {
 public:
  explicit PenetrationCheck(double fraction) : fraction_(fraction) {}
  double fraction() const { return fraction_; }
  void evaluate(const RunView& run, std::vector<SceneCheckResult>& out) const override {
    const RunMeasures& m = run.measures;
    out.push_back(at_most("penetration", m.deepest_penetration, fraction_ * m.smallest_edge, "m"));
  }

 private:
  double fraction_;
};

std::unique_ptr<Check> read_penetration(const std::optional<JsonNode>& node, const Scene&) {
  return std::make_unique<PenetrationCheck>(node ? json_input::read_positive(*node) : kDefaultFraction);
}

}  // namespace

double penetration_fraction(const Scene& scene) {
  // Read as every check is, through the table: the check is held in every scene.
  for (const SceneCheckSet::Held& h : read_scene_checks(scene).held)
    if (const auto* p = dynamic_cast<const PenetrationCheck*>(h.check.get())) return p->fraction();
  return kDefaultFraction;
}

const CheckRow& penetration_check() {
  static const CheckRow row{"penetration",
                            "the deepest overlap over the run stays below this fraction of the smallest box edge "
                            "(default 0.01)",
                            30, true, false, read_penetration};
  return row;
}

}  // namespace boxpile
