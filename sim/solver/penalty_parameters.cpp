#include "boxpile/sim/solver/penalty_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace boxpile {

namespace {
// A scene without gravity still gets springs: stiff enough for Earth's gravity.
constexpr double kReferenceGravity = 9.81;  // m/s^2

std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// The radius of the sphere around a body's frame origin that holds all its boxes, m.
double reach(const BodyDesc& body) {
  double r = 0.0;
  for (const BoxShape& box : body.boxes) r = std::max(r, box.offset.norm() + box.half_extents.norm());
  return r;
}

// The heaviest stack: for each moving body, its mass plus the mass of the moving bodies above it
// (along `up`) whose spheres overlap its sphere's column. Wired bodies hang from their wire, so
// they load no stack.
double heaviest_stack(const Scene& scene, const Vec3& up) {
  double heaviest = 0.0;
  for (const BodyDesc& below : scene.bodies) {
    if (below.fixed || below.wire) continue;
    double load = below.mass;
    for (const BodyDesc& above : scene.bodies) {
      if (&above == &below || above.fixed || above.wire) continue;
      const Vec3 d = above.frame.position - below.frame.position;
      const double height = d.dot(up);
      const double across = (d - height * up).norm();
      if (height > 0.0 && across < reach(below) + reach(above)) load += above.mass;
    }
    heaviest = std::max(heaviest, load);
  }
  return heaviest;
}

}  // namespace

double damping_ratio_for_restitution(double e) {
  if (e <= 0.0) return 1.0;
  const double l = std::log(e);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

double restitution_for_damping_ratio(double zeta) {
  if (zeta >= 1.0) return 0.0;
  return std::exp(-zeta * std::numbers::pi / std::sqrt(1.0 - zeta * zeta));
}

double point_damping(double stiffness, double point_mass, double zeta) {
  return 2.0 * zeta * std::sqrt(stiffness * point_mass);
}

PenaltyParameters derive_penalty_parameters(const Scene& scene) {
  const PenaltySettings& set = scene.solver.penalty;
  PenaltyParameters p;
  const double g = scene.gravity.norm() > 0.0 ? scene.gravity.norm() : kReferenceGravity;
  const Vec3 up = scene.ground                     ? scene.ground->normal
                  : scene.gravity.norm() > 0.0     ? Vec3(-scene.gravity.normalized())
                                                   : Vec3::UnitZ();
  p.stack_mass = heaviest_stack(scene, up);
  p.lightest_mass = 0.0;
  for (const BodyDesc& b : scene.bodies)
    if (!b.fixed && (p.lightest_mass == 0.0 || b.mass < p.lightest_mass)) p.lightest_mass = b.mass;
  if (p.stack_mass == 0.0) p.stack_mass = std::max(p.lightest_mass, 1.0);  // only wired or fixed bodies
  if (p.lightest_mass == 0.0) p.lightest_mass = p.stack_mass;

  p.stiffness = set.stiffness.value_or(p.stack_mass * g / (kPointsPerSupport * kDefaultRestingOverlap));
  p.friction_stiffness = set.friction_stiffness.value_or(p.stiffness);
  p.damping = set.damping;

  const double point_mass = p.lightest_mass / kPointsPerSupport;
  p.omega = std::sqrt(p.stiffness / point_mass);
  p.damping_ratio = p.damping ? *p.damping / (2.0 * std::sqrt(p.stiffness * point_mass)) : 1.0;
  const double zeta = p.damping_ratio;
  p.stable_step = 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta) / p.omega;
  const double needed = std::ceil(scene.time.dt / (kStabilityFraction * p.stable_step));
  p.substeps_needed = needed > kMaxDerivedSubsteps ? kMaxDerivedSubsteps + 1 : std::max(1, static_cast<int>(needed));
  p.substeps = set.substeps.value_or(std::min(p.substeps_needed, kMaxDerivedSubsteps));
  return p;
}

std::string penalty_parameters_problem(const Scene& scene, const PenaltyParameters& p) {
  if (scene.solver.penalty.substeps || p.substeps_needed <= kMaxDerivedSubsteps) return {};
  return "dt " + format_number(scene.time.dt) + " s breaks the penalty method's stability bound h < 2 (sqrt(1 + zeta^2) - zeta) / omega = " +
         format_number(p.stable_step) + " s (omega = sqrt(k / m) = " + format_number(p.omega) +
         " rad/s for a point of the lightest body, " + format_number(p.lightest_mass) + " kg, with stiffness " +
         format_number(p.stiffness) + " N/m, zeta = " + format_number(p.damping_ratio) + "): it would need more than " +
         std::to_string(kMaxDerivedSubsteps) + " substeps; lower \"stiffness\", shorten \"dt\" or set \"substeps\"";
}

}  // namespace boxpile
