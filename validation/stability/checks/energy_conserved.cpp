// energy_conserved: for e = 1 scenes, |E - E0| stays within this fraction of |E0| in every step.
#include "boxpile/validation/stability/checks/check.hpp"

namespace boxpile {
namespace {

std::unique_ptr<Check> read_energy_conserved(const std::optional<json_input::JsonNode>& node, const Scene&) {
  return figure_at_most("energy_conserved", &RunMeasures::energy_change, json_input::read_positive(*node), "");
}

}  // namespace

const CheckRow& energy_conserved_check() {
  static const CheckRow row{"energy_conserved",
                            "e = 1 scenes: |E - E0| stays within this fraction of |E0| in every step", 20, false,
                            true, read_energy_conserved};
  return row;
}

}  // namespace boxpile
