#include "boxpile/sim/io/own_settings.hpp"

#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/solver/step_context.hpp"

namespace boxpile {

using nlohmann::json;
using Kind = SettingInfo::Kind;

namespace {

json optional_json(const auto& v) { return v ? json(*v) : json(); }

constexpr std::string_view kImpulse = "impulse", kPenalty = "penalty";

}  // namespace

std::string_view method_name(ContactSolver method) { return method == ContactSolver::Penalty ? kPenalty : kImpulse; }

std::optional<ContactSolver> setting_group_method(const SettingInfo& setting) {
  if (setting.group == kImpulse) return ContactSolver::Impulse;
  if (setting.group == kPenalty) return ContactSolver::Penalty;
  return std::nullopt;
}

const SettingsTable<Scene>& own_settings_table() {
  using S = Scene;
  const std::string impulse(kImpulse), penalty(kPenalty);
  static const SettingsTable<Scene> table{
      // The impulse method (docs/solver.md).
      {{.key = "collision_passes", .kind = Kind::Integer, .what = "passes of the collision loop", .min = 1,
        .max = kMaxSolverPasses, .scene_key = "solver.collision_passes", .group = impulse},
       [](S& s, const json& v) { s.solver.collision_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.collision_passes); }},
      {{.key = "contact_passes", .kind = Kind::Integer, .what = "passes of the contact loop (restitution ramped to 0)",
        .min = 1, .max = kMaxSolverPasses, .scene_key = "solver.contact_passes", .group = impulse},
       [](S& s, const json& v) { s.solver.contact_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.contact_passes); }},
      {{.key = "shock_propagation", .kind = Kind::Boolean, .what = "shock propagation after the contact loop",
        .scene_key = "solver.shock_propagation", .group = impulse},
       [](S& s, const json& v) { s.solver.shock_propagation = v.get<bool>(); },
       [](const S& s) { return json(s.solver.shock_propagation); }},
      {{.key = "shock_passes", .kind = Kind::Integer, .what = "most passes over one level in shock propagation",
        .min = 1, .max = kMaxSolverPasses, .scene_key = "solver.shock_passes", .group = impulse},
       [](S& s, const json& v) { s.solver.shock_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.shock_passes); }},
      {{.key = "recovery_passes", .kind = Kind::Integer,
        .what = "most passes of penetration recovery per group of a phase (split impulses)", .min = 1,
        .max = kMaxSolverPasses, .scene_key = "solver.recovery_passes", .group = impulse},
       [](S& s, const json& v) { s.solver.recovery_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.recovery_passes); }},
      {{.key = "penetration_recovery", .kind = Kind::Number, .unit = "1/step",
        .what = "fraction of a penetration pushed out per step (0: off)", .min = 0, .max = 1,
        .scene_key = "solver.penetration_recovery", .group = impulse},
       [](S& s, const json& v) { s.solver.penetration_recovery = v.get<double>(); },
       [](const S& s) { return json(s.solver.penetration_recovery); }},
      {{.key = "penetration_slop", .kind = Kind::Number, .unit = "m", .what = "overlaps this shallow are left alone",
        .min = 0, .max = limits::kMaxMargin, .scene_key = "solver.penetration_slop", .group = impulse},
       [](S& s, const json& v) { s.solver.penetration_slop = v.get<double>(); },
       [](const S& s) { return json(s.solver.penetration_slop); }},
      {{.key = "integrator", .kind = Kind::Choice, .what = "position update",
        .choices = {"explicit_euler", "semi_implicit_euler"}, .scene_key = "solver.integrator", .group = impulse},
       [](S& s, const json& v) {
         s.solver.integrator = v.get<std::string>() == "explicit_euler" ? PositionIntegrator::ExplicitEuler
                                                                        : PositionIntegrator::SemiImplicitEuler;
       },
       [](const S& s) {
         return json(s.solver.integrator == PositionIntegrator::ExplicitEuler ? "explicit_euler" : "semi_implicit_euler");
       }},
      // Both methods: the contact set they share.
      {{.key = "contact_margin", .kind = Kind::Number, .unit = "m",
        .what = "points this far apart stay in the step's contact set", .min = 0, .max = limits::kMaxMargin,
        .scene_key = "solver.contact_margin"},
       [](S& s, const json& v) { s.solver.contact_margin = v.get<double>(); },
       [](const S& s) { return json(s.solver.contact_margin); }},
      // The penalty method (docs/penalty.md); each one left out is derived from the scene when the
      // world is built.
      {{.key = "stiffness", .kind = Kind::Number, .unit = "N/m", .what = "normal spring per contact point",
        .min = kSoftestSpring, .max = kStiffestSpring, .scene_key = "solver.stiffness", .group = penalty},
       [](S& s, const json& v) { s.solver.penalty.stiffness = v.get<double>(); },
       [](const S& s) { return optional_json(s.solver.penalty.stiffness); }},
      {{.key = "damping", .kind = Kind::Number, .unit = "N s/m",
        .what = "normal and tangential damper per contact point", .min = 0, .max = kStiffestSpring,
        .scene_key = "solver.damping", .group = penalty},
       [](S& s, const json& v) { s.solver.penalty.damping = v.get<double>(); },
       [](const S& s) { return optional_json(s.solver.penalty.damping); }},
      {{.key = "friction_stiffness", .kind = Kind::Number, .unit = "N/m", .what = "friction spring per contact point",
        .min = kSoftestSpring, .max = kStiffestSpring, .scene_key = "solver.friction_stiffness", .group = penalty},
       [](S& s, const json& v) { s.solver.penalty.friction_stiffness = v.get<double>(); },
       [](const S& s) { return optional_json(s.solver.penalty.friction_stiffness); }},
      {{.key = "substeps", .kind = Kind::Integer, .what = "penalty steps per scene step", .min = 1,
        .max = kMaxPenaltySubsteps, .scene_key = "solver.substeps", .group = penalty},
       [](S& s, const json& v) { s.solver.penalty.substeps = v.get<int>(); },
       [](const S& s) { return optional_json(s.solver.penalty.substeps); }},
      // Contact generation, shared by both methods (the scene's `collision` object).
      {{.key = "reduce_to_four", .kind = Kind::Boolean, .what = "reduce each box-box manifold to at most 4 points",
        .scene_key = "collision.reduce_to_four"},
       [](S& s, const json& v) { s.collision.reduce_to_four = v.get<bool>(); },
       [](const S& s) { return json(s.collision.reduce_to_four); }},
      {{.key = "collision_margin", .kind = Kind::Number, .unit = "m",
        .what = "points up to this far apart count as contacts (speculative contacts)", .min = 0,
        .max = limits::kMaxMargin, .scene_key = "collision.margin"},
       [](S& s, const json& v) { s.collision.margin = v.get<double>(); },
       [](const S& s) { return json(s.collision.margin); }},
      // The impulse method's alone: the penalty method tests every pair at every step.
      {{.key = "reuse_contacts", .kind = Kind::Boolean,
        .what = "copy a pair's contacts from the last step while neither body moves beyond rounding (1e-12)",
        .scene_key = "collision.reuse_contacts", .group = impulse},
       [](S& s, const json& v) { s.collision.reuse_contacts = v.get<bool>(); },
       [](const S& s) { return json(s.collision.reuse_contacts); }},
  };
  return table;
}

}  // namespace boxpile
