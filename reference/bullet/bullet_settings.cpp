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
      {{"iterations", Kind::Integer, "", "sequential-impulse passes per step", 1, reference_limits::kMaxIterations},
       [](S& s, const json& v) { s.iterations = v.get<int>(); }, [](const S& s) { return json(s.iterations); }},
      {{"split_impulse", Kind::Boolean, "", "push deep contacts apart by pseudo-velocities"},
       [](S& s, const json& v) { s.split_impulse = v.get<bool>(); },
       [](const S& s) { return json(s.split_impulse); }},
      {{"split_impulse_threshold", Kind::Number, "m",
        "contacts deeper than this (a negative distance) get split impulses", -reference_limits::kMaxLength, 0},
       [](S& s, const json& v) { s.split_impulse_threshold = v.get<double>(); },
       [](const S& s) { return json(s.split_impulse_threshold); }},
      {{"erp", Kind::Number, "1/step", "Baumgarte error reduction inside the contact impulse", 0, 1},
       [](S& s, const json& v) { s.erp = v.get<double>(); }, [](const S& s) { return json(s.erp); }},
      {{"split_erp", Kind::Number, "1/step", "error reduction of the split impulse", 0, 1},
       [](S& s, const json& v) { s.split_erp = v.get<double>(); }, [](const S& s) { return json(s.split_erp); }},
      {{"cfm", Kind::Number, "1/kg", "constraint force mixing added to each contact's inverse mass", 0, 1},
       [](S& s, const json& v) { s.cfm = v.get<double>(); }, [](const S& s) { return json(s.cfm); }},
      {{"plane_iterations", Kind::Integer, "",
        "box-plane perturbation iterations that fill the manifold at once (0: one point per step)", 0,
        kMaxSolverPasses},
       [](S& s, const json& v) { s.plane_iterations = v.get<int>(); },
       [](const S& s) { return json(s.plane_iterations); }},
      {{"plane_min_points", Kind::Integer, "", "perturb only while the manifold has fewer points", 0,
        kMostPlanePoints},
       [](S& s, const json& v) { s.plane_min_points = v.get<int>(); },
       [](const S& s) { return json(s.plane_min_points); }},
      {{"restitution_threshold", Kind::Number, "m/s", "approach speeds below this do not bounce", 0,
        reference_limits::kMaxLength},
       [](S& s, const json& v) { s.restitution_threshold = v.get<double>(); },
       [](const S& s) { return json(s.restitution_threshold); }},
      {{"sleeping", Kind::Boolean, "",
        "deactivation: a body below both sleeping speeds for 2 s (Bullet's deactivation time) sleeps until touched"},
       [](S& s, const json& v) { s.sleeping = v.get<bool>(); }, [](const S& s) { return json(s.sleeping); }},
      {{"linear_sleeping_threshold", Kind::Number, "m/s", "sleeping: a body slower than this may sleep", 0,
        reference_limits::kMaxLength},
       [](S& s, const json& v) { s.linear_sleeping_threshold = v.get<double>(); },
       [](const S& s) { return json(s.linear_sleeping_threshold); }},
      {{"angular_sleeping_threshold", Kind::Number, "rad/s", "sleeping: a body turning slower than this may sleep", 0,
        reference_limits::kMaxLength},
       [](S& s, const json& v) { s.angular_sleeping_threshold = v.get<double>(); },
       [](const S& s) { return json(s.angular_sleeping_threshold); }},
      {{"ccd_motion_threshold", Kind::Number, "m",
        "continuous collision detection for a body moving farther than this in a step (0: off)", 0,
        reference_limits::kMaxLength},
       [](S& s, const json& v) { s.ccd_motion_threshold = v.get<double>(); },
       [](const S& s) { return json(s.ccd_motion_threshold); }},
      {{"ccd_swept_sphere_radius", Kind::Number, "m",
        "continuous collision detection: radius of the sphere swept along a fast body's step", 0,
        reference_limits::kMaxLength},
       [](S& s, const json& v) { s.ccd_swept_sphere_radius = v.get<double>(); },
       [](const S& s) { return json(s.ccd_swept_sphere_radius); }},
  };
  return table;
}

}  // namespace boxpile
