#include "boxpile/sim/io/own_settings.hpp"

#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/solver/step_context.hpp"

namespace boxpile {

using nlohmann::json;
using Kind = SettingInfo::Kind;

namespace {

json optional_json(const auto& v) { return v ? json(*v) : json(); }

constexpr std::string_view kImpulse = "impulse", kPenalty = "penalty";

// A boolean setting that is one member of one part of the scene (solver or collision).
template <auto Part, auto Member>
Setting<Scene> flag(SettingInfo info) {
  return {std::move(info), [](Scene& s, const json& v) { (s.*Part).*Member = v.get<bool>(); },
          [](const Scene& s) { return json((s.*Part).*Member); }};
}

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
      // The impulse method (docs/solver.md). Its variant comes first: it sets every addition
      // below, and the table applies its rows in order, so an addition given beside it wins.
      {{.key = "variant", .kind = Kind::Choice,
        .what = "the impulse method: \"boxpile\" (ours, every addition on) or \"lab\" (the lab text's, every "
                "addition off: pair_impulses, accumulated_impulses, speculative_contacts, sticking_solves, "
                "shock_propagation, reuse_contacts off, penetration_recovery 0, integrator explicit_euler); "
                "additions given beside it apply after it",
        .choices = {"boxpile", "lab"}, .scene_key = "solver.variant", .group = impulse},
       [](S& s, const json& v) {
         set_impulse_variant(s.solver, s.collision,
                             v.get<std::string>() == "lab" ? ImpulseVariant::Lab : ImpulseVariant::Boxpile);
       },
       [](const S& s) { return json(s.solver.variant == ImpulseVariant::Lab ? "lab" : "boxpile"); }},
      flag<&Scene::solver, &SolverSettings::pair_impulses>({.key = "pair_impulses", .kind = Kind::Boolean,
        .what = "collision loop: the approaching points of a pair get their normal impulses from one system "
                "(a flat landing stays flat); off: push-only Newton-Coulomb impulses point by point (the lab text)",
        .scene_key = "solver.pair_impulses", .group = impulse}),
      flag<&Scene::solver, &SolverSettings::accumulated_impulses>({.key = "accumulated_impulses", .kind = Kind::Boolean,
        .what = "contact loop and shock propagation: each contact's impulse accumulated over the phase and "
                "projected on the friction cone (may take back what it gave); off: push-only impulses with "
                "the ramped restitution on the present u_n (the lab text)",
        .scene_key = "solver.accumulated_impulses", .group = impulse}),
      flag<&Scene::solver, &SolverSettings::speculative_contacts>({.key = "speculative_contacts", .kind = Kind::Boolean,
        .what = "points up to contact_margin (or collision_margin) plus a step's motion apart are contacts that "
                "may close their gap in the step; off: touching or overlapping points only, both margins "
                "unused (the lab text)",
        .scene_key = "solver.speculative_contacts", .group = impulse}),
      flag<&Scene::solver, &SolverSettings::sticking_solves>({.key = "sticking_solves", .kind = Kind::Boolean,
        .what = "shock propagation: a group of a level whose touching points can all stick is solved "
                "directly (least squares); off: every group by passes",
        .scene_key = "solver.sticking_solves", .group = impulse}),
      {{.key = "collision_passes", .kind = Kind::Integer, .what = "passes of the collision loop", .min = 1,
        .max = kMaxSolverPasses, .scene_key = "solver.collision_passes", .group = impulse},
       [](S& s, const json& v) { s.solver.collision_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.collision_passes); }},
      {{.key = "contact_passes", .kind = Kind::Integer, .what = "passes of the contact loop (restitution ramped to 0)",
        .min = 1, .max = kMaxSolverPasses, .scene_key = "solver.contact_passes", .group = impulse},
       [](S& s, const json& v) { s.solver.contact_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.contact_passes); }},
      flag<&Scene::solver, &SolverSettings::shock_propagation>({.key = "shock_propagation", .kind = Kind::Boolean, .what = "shock propagation after the contact loop",
        .scene_key = "solver.shock_propagation", .group = impulse}),
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
      flag<&Scene::collision, &CollisionSettings::reduce_to_four>({.key = "reduce_to_four", .kind = Kind::Boolean, .what = "reduce each box-box manifold to at most 4 points",
        .scene_key = "collision.reduce_to_four"}),
      {{.key = "collision_margin", .kind = Kind::Number, .unit = "m",
        .what = "points up to this far apart count as contacts (speculative contacts)", .min = 0,
        .max = limits::kMaxMargin, .scene_key = "collision.margin"},
       [](S& s, const json& v) { s.collision.margin = v.get<double>(); },
       [](const S& s) { return json(s.collision.margin); }},
      // The impulse method's alone: the penalty method tests every pair at every step.
      flag<&Scene::collision, &CollisionSettings::reuse_contacts>({.key = "reuse_contacts", .kind = Kind::Boolean,
        .what = "copy a pair's contacts from the last step while neither body moves beyond rounding (1e-12)",
        .scene_key = "collision.reuse_contacts", .group = impulse}),
  };
  return table;
}

}  // namespace boxpile
