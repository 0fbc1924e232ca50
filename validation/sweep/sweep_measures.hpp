// The error measures and checks of one sweep cell: the hard-scene catalogue's own (RunMonitor,
// validation/stability/stability_checks.hpp), observed at every step of the cell's measured run, so that a
// sweep, `boxpile stability` and `boxpile compare` judge a run alike.
#pragma once

#include <array>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/core/measure.hpp"
#include "boxpile/validation/stability/stability_checks.hpp"

namespace boxpile {

// The error measures, in report order, each with its unit and what it is. A measure that does not
// apply to a scene is null: the stack measures need a scene whose free bodies all start in stacks
// (a resting stack or pile; not one with a body in flight or on a wire).
inline constexpr std::array<MeasureDeclaration, 5> kErrorMeasures = {{
    {"stack_height", "m", "settled height error: largest |height change| (along gravity) of a body, start to end"},
    {"drift", "m", "largest sideways (across gravity) move of a body, start to end"},
    {"penetration", "m", "deepest penetration at any step"},
    {"energy_rise", "of |E0|", "largest rise of the total energy above its start at any step, as a fraction of |E0|"},
    {"kinetic_final", "J", "kinetic energy of all bodies at the end"},
}};

struct CellMeasures {
  nlohmann::json error = nlohmann::json::object();  // {measure: value or null}
  std::vector<SceneCheckResult> checks;             // the scene's catalogue checks (RunMonitor::evaluate)
  bool stable = false;  // no check failed that shows instability (first_instability)
  bool passed = false;  // every check passed
};

// The cell's figures from the catalogue's measures and checks of its run.
CellMeasures cell_measures(const Scene& scene, const RunMeasures& measures, std::vector<SceneCheckResult> checks);

}  // namespace boxpile
