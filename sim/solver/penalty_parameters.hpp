// The penalty method's parameters: the scene's `solver` keys where it sets them, derived from the
// scene where it does not (docs/penalty.md, "Defaults"):
//   stiffness       k = M g / (n d): the heaviest stack's weight M g carried on n = 4 corner points
//                   with an allowed resting overlap d;
//   damping         c = 2 zeta sqrt(k m): m the mass one point carries (a quarter of a body, of
//                   the pair's reduced mass at a contact), zeta from the pair's restitution
//                   (critical, zeta = 1, at e = 0);
//   substeps        enough that h = dt / n stays within a fraction of the explicit stability
//                   bound h < 2 (sqrt(1 + zeta^2) - zeta) / omega, omega = sqrt(k / m) for a point
//                   of the lightest body (2 / omega when undamped).
#pragma once

#include <optional>
#include <string>

#include "boxpile/sim/scene.hpp"

namespace boxpile {

// A box rests on its four corners: the points one body's weight is spread over.
inline constexpr int kPointsPerSupport = 4;
// The resting overlap the derived stiffness allows under the heaviest stack, m: a millimetre,
// 1% of the 0.1-1 m boxes the scenes use (docs/penalty.md measures what it costs).
inline constexpr double kDefaultRestingOverlap = 1e-3;
// Derived substeps keep h below this fraction of the single-point stability bound: a box's
// rocking and twisting modes on its corner springs (normal and friction) run up to sqrt(3) times
// faster than its bounce, a pair of moving bodies sqrt(2) faster again, and a box held between
// two layers sqrt(2) more, about 3.5 times in all. At 0.25 the pyramid rings in a limit cycle and
// creeps; at 0.08 it comes to rest (docs/penalty.md).
inline constexpr double kStabilityFraction = 0.08;
// More derived substeps than this and the scene is refused: the stiffness asks for a step the
// method cannot afford (a scene that sets `substeps` itself is taken as it is).
inline constexpr int kMaxDerivedSubsteps = 1000;

struct PenaltyParameters {
  double stiffness = 0.0;           // N/m per contact point
  double friction_stiffness = 0.0;  // N/m per contact point
  std::optional<double> damping;    // N s/m per point; unset: per pair, from its restitution
  int substeps = 1;

  // The derivation (for the messages, the docs and the tests).
  double stack_mass = 0.0;     // kg, the heaviest stack (bodies above a body, and the body)
  double lightest_mass = 0.0;  // kg, the lightest moving body
  double omega = 0.0;          // rad/s, sqrt(k / m_point) for a point of the lightest body
  double damping_ratio = 1.0;  // zeta of a point of the lightest body (1 when derived per pair)
  double stable_step = 0.0;    // s, the explicit bound 2 (sqrt(1 + zeta^2) - zeta) / omega
  int substeps_needed = 1;     // to keep dt / n within kStabilityFraction of stable_step
};

// The parameters for a scene (its penalty settings, the rest derived). Does not refuse anything:
// penalty_parameters_problem() says whether the scene can run.
PenaltyParameters derive_penalty_parameters(const Scene& scene);

// Why the scene cannot run the penalty method with `p` (the derived substeps exceed
// kMaxDerivedSubsteps), naming the bound; empty when it can.
std::string penalty_parameters_problem(const Scene& scene, const PenaltyParameters& p);

// The damping ratio whose free bounce has restitution e: zeta = -ln e / sqrt(pi^2 + ln^2 e)
// (1, critical, at e = 0), the inverse of restitution_for_damping_ratio.
double damping_ratio_for_restitution(double e);
// The restitution of a linear damped spring's bounce, e = exp(-zeta pi / sqrt(1 - zeta^2)), and
// 0 at zeta >= 1 (no bounce).
double restitution_for_damping_ratio(double zeta);
// A point's damper for ratio zeta on a spring k carrying mass m: c = 2 zeta sqrt(k m).
double point_damping(double stiffness, double point_mass, double zeta);

}  // namespace boxpile
