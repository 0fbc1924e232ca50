// The error measures and checks of one sweep cell, taken from a measured run (validation/compare's
// EngineRun): the same rulers `compare` uses (settled stack heights, energy, penetration, the
// final state), and pass/fail checks with the limits of the hard-case catalogue.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/compare.hpp"

namespace boxpile {

// The error measures, in report order, each with its unit and what it is. A measure that does not
// apply to a scene (no stack at the start: no stack height error) is null.
struct ErrorMeasure {
  std::string_view name;
  std::string_view unit;
  std::string_view what;
};
inline constexpr std::array<ErrorMeasure, 5> kErrorMeasures = {{
    {"stack_height", "m", "largest |settled height - start height| over the stacks the scene starts with"},
    {"drift", "m", "largest sideways (across gravity) move of a body of a starting stack, start to end"},
    {"penetration", "m", "deepest penetration at any step"},
    {"energy_rise", "J", "largest rise of the total energy above its start, at any step"},
    {"kinetic_final", "J", "kinetic energy left at the end"},
}};

struct CellCheck {
  std::string name;
  double value = 0.0;
  double limit = 0.0;
  bool passed = false;
};

struct CellMeasures {
  nlohmann::json error = nlohmann::json::object();  // {measure: value or null}
  std::vector<CellCheck> checks;
  bool stable = false;  // finite, and the total energy never rose beyond its limit
  bool passed = false;  // every check passed
};

CellMeasures measure_run(const Scene& scene, const EngineRun& run);

}  // namespace boxpile
