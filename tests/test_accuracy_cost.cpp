// Our impulse method's cells of the accuracy-cost sweep (benchmarks/grids/accuracy_cost.json,
// docs/accuracy-cost.md), read from the grid file itself so that the test follows the grid: every
// cell passes every check, and its errors stay within bounds taken from the measured figures. A
// solver change that lets a resting stack or pyramid creep fails here, not only in the
// regenerated docs (the 3x3 Schur-complement sticking solve, docs/solver.md, made two of these
// cells creep 1-2 cm).
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/validation/sweep/sweep.hpp"
#include "boxpile/validation/sweep/sweep_grid.hpp"

using namespace boxpile;

namespace {

const std::string kGridFile = std::string(BOXPILE_FIXTURES_DIR) + "/../benchmarks/grids/accuracy_cost.json";
constexpr std::string_view kEngine = "own-impulse";

// One timed run per cell (the measured run): cost is not asserted here.
constexpr int kTimedRuns = 1;

// Bounds on the errors (kErrorMeasures). Measured (docs/accuracy-cost.md, and this test's cells
// on the same tree): every cell's height error, penetration and energy rise exactly 0, its drift
// at most 4e-16 m, its kinetic energy left at most 7e-31 J. With the 3x3 Schur solve the two
// cells that crept (pyramid, dt = 1/60, 5 shock passes) drifted 1.2 and 2.1 cm, changed height by
// 1.2 and 2.2 mm, overlapped 0.23 and 0.11 mm, rose 5.3e-4 and 4.3e-4 of |E0| and kept 0.016 and
// 0.026 J; its other cells stayed within rounding (at most 7e-12 m, 3e-14 of |E0|, 9e-22 J), and
// pass.
// Resting boxes move by rounding only; a change of rounding moves them by up to 7e-12 m.
constexpr double kMaxStackHeight = 1e-9;  // m
// Sideways as along gravity: rounding moves the boxes by 1e-16 to 7e-12 m, a creep by centimetres.
constexpr double kMaxDrift = 1e-9;  // m
// Boxes resting on exact faces overlap by rounding at most; the check's own limit is 1 cm.
constexpr double kMaxPenetration = 1e-9;  // m
// Energy never rose beyond rounding; the check's own limit is 1e-4 of |E0|.
constexpr double kMaxEnergyRise = 1e-9;  // of |E0|
// At rest at the end: the pyramid's 21 boxes (1 kg each) at 1e-6 m/s would hold 1e-11 J.
constexpr double kMaxKineticFinal = 1e-12;  // J

struct ErrorBound {
  std::string_view measure;  // a name of kErrorMeasures
  double bound;
  std::string_view unit;
};
constexpr std::array<ErrorBound, 5> kBounds = {{
    {"stack_height", kMaxStackHeight, "m"},
    {"drift", kMaxDrift, "m"},
    {"penetration", kMaxPenetration, "m"},
    {"energy_rise", kMaxEnergyRise, "of |E0|"},
    {"kinetic_final", kMaxKineticFinal, "J"},
}};

// "cell 60: ../../fixtures/scenes/pyramid.json own-impulse {"contact_passes":5,"shock_passes":5}
// dt=1/60": its number in the grid's order, the scene as the grid names it, settings and step.
std::string cell_name(const SweepGrid& grid, const CellSpec& spec) {
  std::ostringstream name;
  name << "cell " << spec.index << ": " << grid.scenes.at(static_cast<std::size_t>(spec.scene)).path << ' '
       << spec.engine << ' ' << spec.settings.dump() << " dt=1/" << std::lround(1.0 / spec.dt);
  return name.str();
}

}  // namespace

TEST_CASE("our impulse method's cells of the accuracy-cost sweep pass every check and stay at rest",
          "[sweep][accuracy-cost]") {
  SweepGrid grid = load_grid(kGridFile);
  grid.repetitions = kTimedRuns;
  std::vector<CellSpec> ours;
  for (const CellSpec& spec : grid_cells(grid))
    if (spec.engine == kEngine) ours.push_back(spec);
  REQUIRE(!ours.empty());

  for (const CellSpec& spec : ours) {
    const CellResult cell = run_cell(grid, spec);
    INFO(cell_name(grid, spec));
    // The grid's duration, already set on its scenes.
    const double duration = grid.scenes.at(static_cast<std::size_t>(spec.scene)).scene.time.duration;
    CHECK(cell.steps == std::lround(duration / spec.dt));
    for (const SceneCheckResult& check : cell.measures.checks) {
      INFO("check " << describe(check));
      CHECK(check.passed);
    }
    CHECK(cell.measures.passed);
    for (const ErrorBound& b : kBounds) {
      const nlohmann::json& figure = cell.measures.error.at(std::string(b.measure));
      INFO(b.measure << " = " << figure.dump() << ' ' << b.unit << ", bound " << b.bound << ' ' << b.unit);
      // The grid's scenes are resting stacks: every measure applies (null: the run went non-finite).
      CHECK(figure.is_number());
      if (figure.is_number()) CHECK(figure.get<double>() <= b.bound);
    }
  }
}
