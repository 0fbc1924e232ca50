// energy_conserved: for e = 1 scenes, |E - E0| stays within this fraction of |E0| in every step.
#include "boxpile/validation/stability/checks/check.hpp"

namespace boxpile {

using json_input::JsonNode;
namespace {

class EnergyConservedCheck final : public Check {
 public:
  explicit EnergyConservedCheck(double limit) : limit_(limit) {}
  void evaluate(const RunView& run, std::vector<SceneCheckResult>& out) const override {
    out.push_back(at_most("energy_conserved", run.measures.energy_change, limit_, ""));
  }

 private:
  double limit_;
};

std::unique_ptr<Check> read_energy_conserved(const std::optional<JsonNode>& node, const Scene&) {
  return std::make_unique<EnergyConservedCheck>(json_input::read_positive(*node));
}

}  // namespace

const CheckRow& energy_conserved_check() {
  static const CheckRow row{"energy_conserved",
                            "e = 1 scenes: |E - E0| stays within this fraction of |E0| in every step", 20, false,
                            true, read_energy_conserved};
  return row;
}

}  // namespace boxpile
