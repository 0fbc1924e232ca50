// energy_rise: the total energy (kinetic + gravitational) never rises above its start by more
// than this fraction of |E0| in any step. Held in every scene (default 1e-4): with e < 1 and
// friction, contacts only take energy away, so a rise is the solver's.
#include "boxpile/validation/stability/checks/check.hpp"

namespace boxpile {
namespace {

std::unique_ptr<Check> read_energy_rise(const std::optional<json_input::JsonNode>& node, const Scene&) {
  return figure_at_most("energy_rise", &RunMeasures::energy_rise, node ? json_input::read_positive(*node) : 1e-4, "");
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
