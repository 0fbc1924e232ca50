// energy_rise: the total energy (kinetic + gravitational) never rises above its start by more
// than this fraction of |E0| in any step. Held in every scene (default 1e-4): with e < 1 and
// friction, contacts only take energy away, so a rise is the solver's.
#include "boxpile/validation/stability/checks/check.hpp"

namespace boxpile {

using json_input::JsonNode;
namespace {

class EnergyRiseCheck final : public Check {
 public:
  explicit EnergyRiseCheck(double limit) : limit_(limit) {}
  void evaluate(const RunView& run, std::vector<SceneCheckResult>& out) const override {
    out.push_back(at_most("energy_rise", run.measures.energy_rise, limit_, ""));
  }

 private:
  double limit_;
};

std::unique_ptr<Check> read_energy_rise(const std::optional<JsonNode>& node, const Scene&) {
  return std::make_unique<EnergyRiseCheck>(node ? json_input::read_positive(*node) : 1e-4);
}

}  // namespace

const CheckRow& energy_rise_check() {
  static const CheckRow row{"energy_rise",
                            "the total energy never rises above its start by more than this fraction of |E0| "
                            "(default 1e-4)",
                            10, true, false, read_energy_rise};
  return row;
}

}  // namespace boxpile
