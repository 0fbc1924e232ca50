#include "boxpile/validation/sweep_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace boxpile {
namespace {

// The hard-case catalogue's limits: total energy may rise above its start by at most this
// fraction of it (a scene that starts at rest: the smaller one), bodies of a scene that starts at
// rest end with less kinetic energy than this each, and no overlap is deeper than this fraction of
// the smallest box.
constexpr double kEnergyRiseMoving = 1e-4;
constexpr double kEnergyRiseAtRest = 1e-6;
constexpr double kRestKineticPerBody = 1e-6;  // J
constexpr double kPenetrationOfSmallestBox = 0.01;
// Energies are compared to at least this much, so a scene whose energy starts near zero (bodies
// near the origin of potential energy) does not demand a rise of 1e-20 J.
constexpr double kEnergyScaleFloor = 1e-3;  // J

bool starts_at_rest(const Scene& scene) {
  return std::all_of(scene.bodies.begin(), scene.bodies.end(), [](const BodyDesc& b) {
    return b.fixed || (b.velocity.isZero(0.0) && b.angular_velocity.isZero(0.0));
  });
}

double smallest_box(const Scene& scene) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const BodyDesc& b : scene.bodies) {
    for (const BoxShape& s : b.boxes) smallest = std::min(smallest, 2.0 * s.half_extents.minCoeff());
  }
  return smallest;
}

// Settled height error of the stacks that were stacks at the start (null when there are none).
nlohmann::json stack_height_error(const EngineRun& run) {
  nlohmann::json worst = nullptr;
  for (const StackReport& s : run.stacks) {
    if (!s.error) continue;
    if (worst.is_null() || std::abs(*s.error) > worst.get<double>()) worst = std::abs(*s.error);
  }
  return worst;
}

// Sideways move of every body that started in a stack (null when none did).
nlohmann::json stack_drift(const Scene& scene, const EngineRun& run) {
  const std::vector<RigidBody> start = make_bodies(scene);
  const std::vector<Stack> stacks = find_stacks(start, scene);
  if (stacks.empty() || run.final_states.size() != start.size()) return nullptr;
  const Vec3 down = scene.gravity.norm() > 0.0 ? Vec3(scene.gravity.normalized()) : Vec3(-Vec3::UnitZ());
  double drift = 0.0;
  for (const Stack& s : stacks) {
    for (int i : s.bodies) {
      const Vec3 moved = run.final_states[static_cast<std::size_t>(i)].position - start[static_cast<std::size_t>(i)].x;
      drift = std::max(drift, (moved - moved.dot(down) * down).norm());
    }
  }
  return std::isfinite(drift) ? nlohmann::json(drift) : nlohmann::json(nullptr);
}

double final_kinetic(const Scene& scene, const EngineRun& run) {
  std::vector<RigidBody> bodies = make_bodies(scene);
  if (run.final_states.size() != bodies.size()) return std::numeric_limits<double>::quiet_NaN();
  set_body_states(bodies, run.final_states);
  return measure_energy(bodies, scene.gravity).kinetic();
}

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

CellMeasures measure_run(const Scene& scene, const EngineRun& run) {
  CellMeasures m;
  const double rise = run.energy_max - run.energy_initial;
  const double kinetic = final_kinetic(scene, run);
  m.error["stack_height"] = stack_height_error(run);
  m.error["drift"] = stack_drift(scene, run);
  m.error["penetration"] = number_or_null(run.deepest.depth);
  m.error["energy_rise"] = number_or_null(std::max(0.0, rise));
  m.error["kinetic_final"] = number_or_null(kinetic);

  const bool at_rest = starts_at_rest(scene);
  const double energy_limit =
      (at_rest ? kEnergyRiseAtRest : kEnergyRiseMoving) * std::max(std::abs(run.energy_initial), kEnergyScaleFloor);
  m.checks.push_back({"finite", run.finite ? 0.0 : 1.0, 0.0, run.finite});
  m.checks.push_back({"energy_rise", rise, energy_limit, run.finite && rise <= energy_limit});
  const double depth_limit = kPenetrationOfSmallestBox * smallest_box(scene);
  m.checks.push_back({"penetration", run.deepest.depth, depth_limit, run.deepest.depth <= depth_limit});
  if (at_rest) {
    const double per_body = kinetic / static_cast<double>(std::max<std::size_t>(1, scene.bodies.size()));
    m.checks.push_back({"rest", per_body, kRestKineticPerBody, per_body <= kRestKineticPerBody});
  }
  m.stable = m.checks[0].passed && m.checks[1].passed;
  m.passed = std::all_of(m.checks.begin(), m.checks.end(), [](const CellCheck& c) { return c.passed; });
  return m;
}

}  // namespace boxpile
