#include "boxpile/reference/ode/ode_settings.hpp"

#include <cmath>

#include "boxpile/reference/limits.hpp"

namespace boxpile {

using nlohmann::json;
using Kind = SettingInfo::Kind;

namespace {

// ODE's seed: any value a grid's integer (an int) can hold.
constexpr double kLargestSeed = 2147483647;
// dBoxBox clips to at most 8 points: asking for more changes nothing.
constexpr double kMostOdeContacts = 8;
// Steps of calm before sleeping: beyond a million (over an hour at 1/240 s) nothing ever sleeps.
constexpr double kMostAutoDisableSteps = 1'000'000;

}  // namespace

const SettingsTable<OdeSettings>& ode_settings_table() {
  using S = OdeSettings;
  static const SettingsTable<OdeSettings> table{
      {{"stepper", Kind::Choice, "", "dWorldQuickStep (iterative) or dWorldStep (Dantzig LCP)", 0, 0,
        {"quickstep", "world"}},
       [](S& s, const json& v) { s.method = v.get<std::string>() == "world" ? OdeStepMethod::Step : OdeStepMethod::QuickStep; },
       [](const S& s) { return json(s.method == OdeStepMethod::Step ? "world" : "quickstep"); }},
      {{"iterations", Kind::Integer, "", "QuickStep passes per step (dWorldStep does not read it)", 1,
        reference_limits::kMaxIterations},
       [](S& s, const json& v) { s.quickstep_iterations = v.get<int>(); },
       [](const S& s) { return json(s.quickstep_iterations); }},
      {{"sor", Kind::Number, "", "QuickStep over-relaxation w", 0.01, 2},
       [](S& s, const json& v) { s.quickstep_sor = v.get<double>(); },
       [](const S& s) { return json(s.quickstep_sor); }},
      {{"erp", Kind::Number, "1/step", "error reduction: fraction of joint and contact error removed per step", 0, 1},
       [](S& s, const json& v) { s.erp = v.get<double>(); }, [](const S& s) { return json(s.erp); }},
      {{"cfm", Kind::Number, "(m/s)/N", "constraint force mixing: softness added to every constraint", 0, 1},
       [](S& s, const json& v) { s.cfm = v.get<double>(); }, [](const S& s) { return json(s.cfm); }},
      {{"max_contacts", Kind::Integer, "", "points per geom pair asked of dCollide", 1, kMostOdeContacts},
       [](S& s, const json& v) { s.max_contacts = v.get<int>(); }, [](const S& s) { return json(s.max_contacts); }},
      {{"surface_layer", Kind::Number, "m", "penetration allowed before ERP corrects it", 0,
        reference_limits::kMaxLength},
       [](S& s, const json& v) { s.surface_layer = v.get<double>(); },
       [](const S& s) { return json(s.surface_layer); }},
      {{"max_correcting_velocity", Kind::Number, "m/s", "largest velocity ERP may give a contact", 0,
        reference_limits::kMaxLength, {}, nullptr, "none (no cap)"},
       [](S& s, const json& v) { s.max_correcting_velocity = v.get<double>(); },
       [](const S& s) { return std::isfinite(s.max_correcting_velocity) ? json(s.max_correcting_velocity) : json(); }},
      {{"wire_carriage_mass_fraction", Kind::Number, "", "the wire carriage's mass over the body's", 1e-6, 1},
       [](S& s, const json& v) { s.wire_carriage_mass_fraction = v.get<double>(); },
       [](const S& s) { return json(s.wire_carriage_mass_fraction); }},
      {{"seed", Kind::Integer, "", "seed of ODE's generator, which shuffles QuickStep's constraint order", 0,
        kLargestSeed},
       [](S& s, const json& v) { s.seed = v.get<unsigned long>(); }, [](const S& s) { return json(s.seed); }},
      {{"restitution_threshold", Kind::Number, "m/s", "approach speeds below this do not bounce", 0,
        reference_limits::kMaxLength},
       [](S& s, const json& v) { s.restitution_threshold = v.get<double>(); },
       [](const S& s) { return json(s.restitution_threshold); }},
      {{"auto_disable", Kind::Boolean, "",
        "sleeping: an island below both auto_disable speeds for auto_disable_steps steps stops (velocities "
        "zeroed) until touched"},
       [](S& s, const json& v) { s.auto_disable = v.get<bool>(); }, [](const S& s) { return json(s.auto_disable); }},
      {{"auto_disable_linear_threshold", Kind::Number, "m/s", "auto_disable: a body slower than this may sleep", 0,
        reference_limits::kMaxLength},
       [](S& s, const json& v) { s.auto_disable_linear_threshold = v.get<double>(); },
       [](const S& s) { return json(s.auto_disable_linear_threshold); }},
      {{"auto_disable_angular_threshold", Kind::Number, "rad/s", "auto_disable: a body turning slower than this may sleep",
        0, reference_limits::kMaxLength},
       [](S& s, const json& v) { s.auto_disable_angular_threshold = v.get<double>(); },
       [](const S& s) { return json(s.auto_disable_angular_threshold); }},
      {{"auto_disable_steps", Kind::Integer, "", "auto_disable: steps below both speeds before an island sleeps", 1,
        kMostAutoDisableSteps},
       [](S& s, const json& v) { s.auto_disable_steps = v.get<int>(); },
       [](const S& s) { return json(s.auto_disable_steps); }},
  };
  return table;
}

}  // namespace boxpile
