#include "boxpile/validation/sweep/sweep_measures.hpp"

#include <cmath>

#include "boxpile/validation/rulers/stacks.hpp"

namespace boxpile {
namespace {

// Whether every free body of the scene starts in a stack: then the catalogue's height error and
// drift are the stacks' settled error.
bool starts_as_stacks(const Scene& scene) {
  std::size_t free = 0;
  for (const BodyDesc& b : scene.bodies) free += b.fixed ? 0 : 1;
  std::size_t stacked = 0;
  for (const Stack& s : find_stacks(make_bodies(scene), scene)) stacked += s.bodies.size();
  return free > 0 && stacked == free;
}

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

CellMeasures cell_measures(const Scene& scene, const RunMeasures& m, std::vector<SceneCheckResult> checks) {
  CellMeasures c;
  const bool stacks = m.finite && starts_as_stacks(scene);
  const bool finite = m.finite;
  c.error["stack_height"] = stacks ? number_or_null(m.height_error) : nlohmann::json(nullptr);
  c.error["drift"] = stacks ? number_or_null(m.drift) : nlohmann::json(nullptr);
  c.error["penetration"] = finite ? number_or_null(m.deepest_penetration) : nlohmann::json(nullptr);
  c.error["energy_rise"] = finite ? number_or_null(m.energy_rise) : nlohmann::json(nullptr);
  c.error["kinetic_final"] = finite ? number_or_null(m.kinetic_end) : nlohmann::json(nullptr);
  c.checks = std::move(checks);
  c.stable = first_instability(c.checks) == nullptr;
  c.passed = all_passed(c.checks);
  return c;
}

}  // namespace boxpile
