#include "boxpile/validation/engine_settings.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "boxpile/sim/solver/step_context.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/validation/engine_factory.hpp"
#include "boxpile/reference/dart/dart_settings_table.hpp"

namespace boxpile {
namespace {

using json_input::JsonNode;
using Kind = EngineSetting::Kind;
using nlohmann::json;

// Iteration counts of the reference engines: far above any useful value, low enough that a typo
// (1e9) is refused instead of running for hours.
constexpr double kMaxReferenceIterations = 100000;
// Largest distance or speed a setting may name: none of them has a meaningful value beyond.
constexpr double kMaxLength = 1e3;  // m (or m/s)
// Penalty springs: the loader's bounds (positive; substeps as many as a run of seconds can take).
constexpr double kSoftestSpring = 1e-6;   // N/m: softer holds nothing up
constexpr double kStiffestSpring = 1e12;  // N/m (and N s/m for the damper)
constexpr int kMaxPenaltySubsteps = 100000;
// ODE's seed: any value a grid's integer (an int) can hold.
constexpr double kLargestSeed = 2147483647;

constexpr std::array<std::string_view, 2> kIntegrators = {"explicit_euler", "semi_implicit_euler"};
constexpr std::array<std::string_view, 2> kOdeSteppers = {"quickstep", "world"};

// Contact generation, shared by both of our methods (the scene's `collision` key).
const EngineSetting kReduceToFour{
    "reduce_to_four", Kind::Boolean, "", "reduce each box-box manifold to at most 4 points", 0, 0, {},
    [](EngineConfig& c, const json& v) { c.scene.collision.reduce_to_four = v.get<bool>(); }};
const EngineSetting kCollisionMargin{
    "collision_margin", Kind::Number, "m", "points up to this far apart count as contacts (speculative contacts)", 0,
    kMaxLength, {}, [](EngineConfig& c, const json& v) { c.scene.collision.margin = v.get<double>(); }};
// The impulse method's alone: the penalty method tests every pair at every step (scene.hpp).
const EngineSetting kReuseContacts{
    "reuse_contacts", Kind::Boolean, "",
    "copy a pair's contacts from the last step while neither body moves beyond rounding (1e-12)", 0, 0, {},
    [](EngineConfig& c, const json& v) { c.scene.collision.reuse_contacts = v.get<bool>(); }};

// Our impulse method (the scene's `solver` and `collision` keys, docs/scene-format.md).
const std::array kImpulseSettings = {
    EngineSetting{"collision_passes", Kind::Integer, "", "passes of the collision loop", 1, kMaxSolverPasses, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.collision_passes = v.get<int>(); }},
    EngineSetting{"contact_passes", Kind::Integer, "", "passes of the contact loop (restitution ramped to 0)", 1,
                  kMaxSolverPasses, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.contact_passes = v.get<int>(); }},
    EngineSetting{"shock_propagation", Kind::Boolean, "", "shock propagation after the contact loop", 0, 0, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.shock_propagation = v.get<bool>(); }},
    EngineSetting{"shock_passes", Kind::Integer, "", "most passes over one level in shock propagation", 1,
                  kMaxSolverPasses, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.shock_passes = v.get<int>(); }},
    EngineSetting{"recovery_passes", Kind::Integer, "",
                  "most passes of penetration recovery per group of a phase (split impulses)", 1, kMaxSolverPasses, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.recovery_passes = v.get<int>(); }},
    EngineSetting{"penetration_recovery", Kind::Number, "1/step",
                  "fraction of a penetration pushed out per step (0: off)", 0, 1, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.penetration_recovery = v.get<double>(); }},
    EngineSetting{"penetration_slop", Kind::Number, "m", "overlaps this shallow are left alone", 0, kMaxLength, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.penetration_slop = v.get<double>(); }},
    EngineSetting{"contact_margin", Kind::Number, "m", "points this far apart stay in the step's contact set", 0,
                  kMaxLength, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.contact_margin = v.get<double>(); }},
    EngineSetting{"integrator", Kind::Choice, "", "position update", 0, 0, kIntegrators,
                  [](EngineConfig& c, const json& v) {
                    c.scene.solver.integrator = v.get<std::string>() == "explicit_euler"
                                                    ? PositionIntegrator::ExplicitEuler
                                                    : PositionIntegrator::SemiImplicitEuler;
                  }},
    kReduceToFour,
    kCollisionMargin,
    kReuseContacts,
};

// Our penalty method (the scene's penalty keys in `solver`, docs/penalty.md); each one left out
// is derived from the scene when the world is built.
const std::array kPenaltySettings = {
    EngineSetting{"stiffness", Kind::Number, "N/m", "normal spring per contact point", kSoftestSpring, kStiffestSpring,
                  {}, [](EngineConfig& c, const json& v) { c.scene.solver.penalty.stiffness = v.get<double>(); }},
    EngineSetting{"damping", Kind::Number, "N s/m", "normal and tangential damper per contact point", 0,
                  kStiffestSpring, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.penalty.damping = v.get<double>(); }},
    EngineSetting{"friction_stiffness", Kind::Number, "N/m", "friction spring per contact point", kSoftestSpring,
                  kStiffestSpring, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.penalty.friction_stiffness = v.get<double>(); }},
    EngineSetting{"substeps", Kind::Integer, "", "penalty steps per scene step", 1, kMaxPenaltySubsteps, {},
                  [](EngineConfig& c, const json& v) { c.scene.solver.penalty.substeps = v.get<int>(); }},
    kReduceToFour,
    kCollisionMargin,
};

// "own" runs each scene's method: every setting of either method (load_grid checks that a
// method's setting meets only scenes of that method).
const std::vector<EngineSetting> kOwnSettings = [] {
  std::vector<EngineSetting> all(kImpulseSettings.begin(), kImpulseSettings.end());
  for (const EngineSetting& s : kPenaltySettings) {
    if (s.key != kReduceToFour.key && s.key != kCollisionMargin.key) all.push_back(s);
  }
  return all;
}();

bool lists(std::span<const EngineSetting> settings, std::string_view key) {
  return std::any_of(settings.begin(), settings.end(), [&](const EngineSetting& s) { return s.key == key; });
}

// The restitution threshold is one setting of both references.
const EngineSetting kRestitutionThreshold{
    "restitution_threshold", Kind::Number, "m/s", "approach speeds below this do not bounce", 0, kMaxLength, {},
    [](EngineConfig& c, const json& v) { c.reference.restitution_threshold = v.get<double>(); }};

// ODE 0.16 (reference/settings.hpp says how each maps onto ODE's calls).
const std::array kOdeSettings = {
    EngineSetting{"stepper", Kind::Choice, "", "dWorldQuickStep (iterative) or dWorldStep (Dantzig LCP)", 0, 0,
                  kOdeSteppers,
                  [](EngineConfig& c, const json& v) {
                    c.reference.ode_method =
                        v.get<std::string>() == "world" ? OdeStepMethod::Step : OdeStepMethod::QuickStep;
                  }},
    EngineSetting{"iterations", Kind::Integer, "", "QuickStep passes per step (dWorldStep ignores it)", 1,
                  kMaxReferenceIterations, {},
                  [](EngineConfig& c, const json& v) { c.reference.ode_quickstep_iterations = v.get<int>(); }},
    EngineSetting{"sor", Kind::Number, "", "QuickStep over-relaxation w", 0.01, 2, {},
                  [](EngineConfig& c, const json& v) { c.reference.ode_quickstep_sor = v.get<double>(); }},
    EngineSetting{"erp", Kind::Number, "1/step", "error reduction: fraction of joint and contact error removed per step",
                  0, 1, {}, [](EngineConfig& c, const json& v) { c.reference.ode_erp = v.get<double>(); }},
    EngineSetting{"cfm", Kind::Number, "(m/s)/N", "constraint force mixing: softness added to every constraint", 0,
                  1, {}, [](EngineConfig& c, const json& v) { c.reference.ode_cfm = v.get<double>(); }},
    EngineSetting{"max_contacts", Kind::Integer, "", "points per geom pair asked of dCollide", 1, 8, {},
                  [](EngineConfig& c, const json& v) { c.reference.ode_max_contacts = v.get<int>(); }},
    EngineSetting{"surface_layer", Kind::Number, "m", "penetration allowed before ERP corrects it", 0, kMaxLength,
                  {}, [](EngineConfig& c, const json& v) { c.reference.ode_surface_layer = v.get<double>(); }},
    EngineSetting{"max_correcting_velocity", Kind::Number, "m/s", "largest velocity ERP may give a contact", 0,
                  kMaxLength, {},
                  [](EngineConfig& c, const json& v) { c.reference.ode_max_correcting_velocity = v.get<double>(); }},
    EngineSetting{"wire_carriage_mass_fraction", Kind::Number, "", "the wire carriage's mass over the body's", 1e-6,
                  1, {},
                  [](EngineConfig& c, const json& v) {
                    c.reference.ode_wire_carriage_mass_fraction = v.get<double>();
                  }},
    EngineSetting{"seed", Kind::Integer, "", "seed of ODE's generator, which shuffles QuickStep's constraint order", 0,
                  kLargestSeed, {},
                  [](EngineConfig& c, const json& v) { c.reference.ode_seed = v.get<unsigned long>(); }},
    kRestitutionThreshold,
};

// Bullet 3.24 (btContactSolverInfo and the collision configuration).
const std::array kBulletSettings = {
    EngineSetting{"iterations", Kind::Integer, "", "sequential-impulse passes per step", 1, kMaxReferenceIterations,
                  {}, [](EngineConfig& c, const json& v) { c.reference.bullet_iterations = v.get<int>(); }},
    EngineSetting{"split_impulse", Kind::Boolean, "", "push deep contacts apart by pseudo-velocities", 0, 0, {},
                  [](EngineConfig& c, const json& v) { c.reference.bullet_split_impulse = v.get<bool>(); }},
    EngineSetting{"split_impulse_threshold", Kind::Number, "m",
                  "contacts deeper than this (a negative distance) get split impulses", -kMaxLength, 0, {},
                  [](EngineConfig& c, const json& v) {
                    c.reference.bullet_split_impulse_threshold = v.get<double>();
                  }},
    EngineSetting{"erp", Kind::Number, "1/step", "Baumgarte error reduction inside the contact impulse", 0, 1, {},
                  [](EngineConfig& c, const json& v) { c.reference.bullet_erp = v.get<double>(); }},
    EngineSetting{"split_erp", Kind::Number, "1/step", "error reduction of the split impulse", 0, 1, {},
                  [](EngineConfig& c, const json& v) { c.reference.bullet_split_erp = v.get<double>(); }},
    EngineSetting{"cfm", Kind::Number, "1/kg", "constraint force mixing added to each contact's inverse mass", 0, 1,
                  {}, [](EngineConfig& c, const json& v) { c.reference.bullet_cfm = v.get<double>(); }},
    EngineSetting{"plane_iterations", Kind::Integer, "",
                  "box-plane perturbation iterations that fill the manifold at once (0: one point per step)", 0,
                  kMaxSolverPasses, {},
                  [](EngineConfig& c, const json& v) { c.reference.bullet_plane_iterations = v.get<int>(); }},
    EngineSetting{"plane_min_points", Kind::Integer, "", "perturb only while the manifold has fewer points", 0, 8,
                  {}, [](EngineConfig& c, const json& v) { c.reference.bullet_plane_min_points = v.get<int>(); }},
    kRestitutionThreshold,
};

std::string format_range(const EngineSetting& s) {
  return "[" + json_input::format_number(s.min) + ", " + json_input::format_number(s.max) + "]";
}

}  // namespace

std::span<const EngineSetting> engine_settings(std::string_view engine) {
  check_engine_name(engine);
  if (engine == "ode") return kOdeSettings;
  if (engine == "bullet") return kBulletSettings;
  if (engine == "dart") return dart_engine_settings();
  if (engine == "own-impulse") return kImpulseSettings;
  if (engine == "own-penalty") return kPenaltySettings;
  if (engine == "own") return kOwnSettings;
  return {};
}

const EngineSetting& find_setting(std::string_view engine, std::string_view key, const JsonNode& node) {
  const std::span<const EngineSetting> settings = engine_settings(engine);
  std::vector<std::string_view> names;
  for (const EngineSetting& s : settings) {
    if (s.key == key) return s;
    names.push_back(s.key);
  }
  std::string what = "engine " + json_input::in_quotes(engine) + " has no setting " + json_input::in_quotes(key);
  if (const auto close = json_input::closest_match(key, names)) what += "; did you mean " + json_input::in_quotes(*close) + "?";
  std::string all;
  for (std::string_view n : names) all += (all.empty() ? "" : ", ") + std::string(n);
  what += all.empty() ? " (it has none)" : " (its settings: " + all + ")";
  node.fail(what);
}

void check_setting_value(const EngineSetting& setting, const JsonNode& value) {
  switch (setting.kind) {
    case Kind::Integer: {
      const int n = value.integer();
      if (n < setting.min || n > setting.max) {
        value.fail(std::string(setting.key) + " must be in " + format_range(setting) + ", got " + std::to_string(n));
      }
      return;
    }
    case Kind::Number: {
      const double x = value.number();
      if (x < setting.min || x > setting.max) {
        value.fail(std::string(setting.key) + " must be in " + format_range(setting) + ", got " +
                   json_input::format_number(x));
      }
      return;
    }
    case Kind::Boolean:
      value.boolean();
      return;
    case Kind::Choice:
      value.choice(setting.choices, setting.key);
      return;
  }
}

nlohmann::json parse_setting_words(std::string_view engine, const std::vector<std::string>& words,
                                   const std::string& source) {
  json settings = json::object();
  for (const std::string& word : words) {
    const std::size_t eq = word.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError(source, "--set", "expected key=value, got " + json_input::in_quotes(word));
    }
    const std::string key = word.substr(0, eq), text = word.substr(eq + 1);
    json value = json::parse(text, nullptr, false);
    if (value.is_discarded()) value = text;
    settings[key] = value;
  }
  const JsonNode root(settings, source);
  for (const auto& item : settings.items()) {
    const JsonNode value = root.at(item.key());
    check_setting_value(find_setting(engine, item.key(), value), value);
  }
  return settings;
}

std::optional<ContactSolver> setting_method(std::string_view engine, std::string_view key) {
  if (engine != "own") return std::nullopt;
  const bool impulse = lists(kImpulseSettings, key), penalty = lists(kPenaltySettings, key);
  if (impulse == penalty) return std::nullopt;
  return impulse ? ContactSolver::Impulse : ContactSolver::Penalty;
}

std::string settings_markdown() {
  std::string md;
  for (std::string_view engine : available_engine_names()) {
    md += "### " + std::string(engine) + "\n\n";
    const std::span<const EngineSetting> settings = engine_settings(engine);
    if (settings.empty()) {
      md += "No settings.\n\n";
      continue;
    }
    md += "| setting | values | unit | what it sets |\n|---|---|---|---|\n";
    for (const EngineSetting& s : settings) {
      std::string values;
      switch (s.kind) {
        case Kind::Integer:
          values = "integer in " + format_range(s);
          break;
        case Kind::Number:
          values = "number in " + format_range(s);
          break;
        case Kind::Boolean:
          values = "true, false";
          break;
        case Kind::Choice:
          for (std::string_view c : s.choices) values += (values.empty() ? "" : ", ") + std::string("\"") + std::string(c) + "\"";
          break;
      }
      md += "| `" + std::string(s.key) + "` | " + values + " | " + (s.unit.empty() ? "—" : std::string(s.unit)) + " | " +
            std::string(s.what) + " |\n";
    }
    md += "\n";
  }
  return md;
}

void apply_settings(std::string_view engine, const nlohmann::json& settings, EngineConfig& config) {
  const JsonNode root(settings, "settings");
  for (const auto& [key, value] : settings.items()) {
    const EngineSetting& s = find_setting(engine, key, root);
    // Integers written as 5.0 are read as 5 (as the scene loader does).
    s.apply(config, s.kind == Kind::Integer ? json(root.at(key).integer()) : value);
  }
}

}  // namespace boxpile
