#include "boxpile/validation/stability/tune_moves.hpp"

#include "boxpile/validation/stability/checks/penetration.hpp"
#include "boxpile/validation/stability/stability_checks.hpp"

namespace boxpile {
namespace {

// The penetration the scene's check allows (m): slops are set to a tenth of it.
double allowed_depth(const Scene& scene) { return penetration_fraction(scene) * smallest_edge(scene); }

}  // namespace

std::vector<TuneMove> tune_moves(std::string_view engine, const Scene& scene, double dt) {
  const double edge = smallest_edge(scene);
  const double slop = 0.1 * allowed_depth(scene);
  if (engine == "ode") {
    return {{"stepper world", "dWorldStep: the step's contacts solved exactly (Dantzig LCP) instead of QuickStep's passes",
             {{"stepper", "world"}}, false, false},
            {"surface_layer", "let contacts rest a tenth of the allowed depth deep, so ERP stops pushing at rest",
             {{"surface_layer", slop}}}};
  }
  if (engine == "bullet") {
    return {{"ccd", "continuous collision for a body moving more than half its smallest edge in a step",
             {{"ccd_motion_threshold", 0.5 * edge}, {"ccd_swept_sphere_radius", 0.4 * edge}}},
            {"no split impulse", "penetration corrected inside the velocity impulse (Baumgarte) instead of apart",
             {{"split_impulse", false}}}};
  }
  if (engine == "mujoco" || engine == "mujoco-wasm") {
    return {{"stiff contacts", "solref time constant 2 dt, the stiffest MuJoCo's documentation advises",
             {{"solref_timeconst", 2.0 * dt}}},
            {"noslip", "10 no-slip passes after the main solver: friction without soft-constraint creep",
             {{"noslip_iterations", 10}}},
            {"stiff contacts, noslip", "both", {{"solref_timeconst", 2.0 * dt}, {"noslip_iterations", 10}}}};
  }
  if (engine == "dart") {
    return {{"lcp pgs", "DART's iterative (PGS) LCP instead of the pivoting Dantzig solver", {{"lcp_solver", "pgs"}},
             true}};
  }
  if (engine == "jolt") {
    return {{"convex_radius 0", "sharp box edges: no 0.05 m rounding of every box", {{"convex_radius", 0.0}}},
            {"penetration_slop", "a tenth of the allowed depth left uncorrected instead of 0.02 m",
             {{"penetration_slop", slop}}},
            {"linear_cast", "continuous collision of moving bodies", {{"motion_quality", "linear_cast"}}}};
  }
  if (engine == "rapier") {
    return {{"stiff contacts", "contact natural frequency 300 Hz instead of 30 Hz",
             {{"contact_natural_frequency", 300.0}}},
            {"ccd", "continuous collision on every dynamic body", {{"ccd", true}}}};
  }
  return {};
}

std::vector<std::string> engines_with_tune_moves() {
  return {"ode", "bullet", "mujoco", "mujoco-wasm", "dart", "jolt", "rapier"};
}

}  // namespace boxpile
