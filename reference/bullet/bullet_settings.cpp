#include "boxpile/reference/bullet/bullet_settings.hpp"

#include "boxpile/reference/limits.hpp"
#include "boxpile/sim/solver/step_context.hpp"

namespace boxpile {

using nlohmann::json;
using Kind = SettingInfo::Kind;

namespace {

// A persistent manifold holds at most 4 points; 8 leaves room for a box's vertices.
constexpr double kMostPlanePoints = 8;

}  // namespace

const SettingsTable<BulletSettings>& bullet_settings_table() {
  using S = BulletSettings;
  static const SettingsTable<BulletSettings> table{
      member_setting<&S::iterations>(
          {"iterations", Kind::Integer, "", "sequential-impulse passes per step", 1, reference_limits::kMaxIterations}),
      member_setting<&S::split_impulse>(
          {"split_impulse", Kind::Boolean, "", "push deep contacts apart by pseudo-velocities"}),
      member_setting<&S::split_impulse_threshold>({"split_impulse_threshold", Kind::Number, "m",
                                                   "contacts deeper than this (a negative distance) get split impulses",
                                                   -reference_limits::kMaxLength, 0}),
      member_setting<&S::erp>(
          {"erp", Kind::Number, "1/step", "Baumgarte error reduction inside the contact impulse", 0, 1}),
      member_setting<&S::split_erp>(
          {"split_erp", Kind::Number, "1/step", "error reduction of the split impulse", 0, 1}),
      member_setting<&S::cfm>(
          {"cfm", Kind::Number, "1/kg", "constraint force mixing added to each contact's inverse mass", 0, 1}),
      member_setting<&S::plane_iterations>(
          {"plane_iterations", Kind::Integer, "",
           "box-plane perturbation iterations that fill the manifold at once (0: one point per step)", 0,
           kMaxSolverPasses}),
      member_setting<&S::plane_min_points>({"plane_min_points", Kind::Integer, "",
                                            "perturb only while the manifold has fewer points", 0, kMostPlanePoints}),
      member_setting<&S::restitution_threshold>(reference_limits::restitution_threshold_info()),
      member_setting<&S::sleeping>({"sleeping", Kind::Boolean, "",
                                    "deactivation: a body below both sleeping speeds for 2 s (Bullet's deactivation "
                                    "time) sleeps until touched"}),
      member_setting<&S::linear_sleeping_threshold>({"linear_sleeping_threshold", Kind::Number, "m/s",
                                                     "sleeping: a body slower than this may sleep", 0,
                                                     reference_limits::kMaxLength}),
      member_setting<&S::angular_sleeping_threshold>({"angular_sleeping_threshold", Kind::Number, "rad/s",
                                                      "sleeping: a body turning slower than this may sleep", 0,
                                                      reference_limits::kMaxLength}),
      member_setting<&S::ccd_motion_threshold>(
          {"ccd_motion_threshold", Kind::Number, "m",
           "continuous collision detection for a body moving farther than this in a step (0: off)", 0,
           reference_limits::kMaxLength}),
      member_setting<&S::ccd_swept_sphere_radius>(
          {"ccd_swept_sphere_radius", Kind::Number, "m",
           "continuous collision detection: radius of the sphere swept along a fast body's step", 0,
           reference_limits::kMaxLength}),
  };
  return table;
}

}  // namespace boxpile
