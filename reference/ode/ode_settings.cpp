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
      {{"stepper",
        Kind::Choice,
        "",
        "dWorldQuickStep (iterative) or dWorldStep (Dantzig LCP)",
        0,
        0,
        {"quickstep", "world"}},
       [](S& s, const json& v) {
         s.method = v.get<std::string>() == "world" ? OdeStepMethod::Step : OdeStepMethod::QuickStep;
       },
       [](const S& s) { return json(s.method == OdeStepMethod::Step ? "world" : "quickstep"); }},
      member_setting<&S::quickstep_iterations>({"iterations", Kind::Integer, "",
                                                "QuickStep passes per step (dWorldStep does not read it)", 1,
                                                reference_limits::kMaxIterations}),
      member_setting<&S::quickstep_sor>({"sor", Kind::Number, "", "QuickStep over-relaxation w", 0.01, 2}),
      member_setting<&S::erp>({"erp", Kind::Number, "1/step",
                               "error reduction: fraction of joint and contact error removed per step", 0, 1}),
      member_setting<&S::cfm>(
          {"cfm", Kind::Number, "(m/s)/N", "constraint force mixing: softness added to every constraint", 0, 1}),
      member_setting<&S::max_contacts>(
          {"max_contacts", Kind::Integer, "", "points per geom pair asked of dCollide", 1, kMostOdeContacts}),
      member_setting<&S::surface_layer>({"surface_layer", Kind::Number, "m",
                                         "penetration allowed before ERP corrects it", 0,
                                         reference_limits::kMaxLength}),
      {{"max_correcting_velocity",
        Kind::Number,
        "m/s",
        "largest velocity ERP may give a contact",
        0,
        reference_limits::kMaxLength,
        {},
        nullptr,
        "none (no cap)"},
       [](S& s, const json& v) { s.max_correcting_velocity = v.get<double>(); },
       [](const S& s) { return std::isfinite(s.max_correcting_velocity) ? json(s.max_correcting_velocity) : json(); }},
      member_setting<&S::wire_carriage_mass_fraction>(
          {"wire_carriage_mass_fraction", Kind::Number, "", "the wire carriage's mass over the body's", 1e-6, 1}),
      member_setting<&S::seed>({"seed", Kind::Integer, "",
                                "seed of ODE's generator, which shuffles QuickStep's constraint order", 0,
                                kLargestSeed}),
      member_setting<&S::restitution_threshold>(reference_limits::restitution_threshold_info()),
      member_setting<&S::auto_disable>(
          {"auto_disable", Kind::Boolean, "",
           "sleeping: an island below both auto_disable speeds for auto_disable_steps steps stops (velocities "
           "zeroed) until touched"}),
      member_setting<&S::auto_disable_linear_threshold>({"auto_disable_linear_threshold", Kind::Number, "m/s",
                                                         "auto_disable: a body slower than this may sleep", 0,
                                                         reference_limits::kMaxLength}),
      member_setting<&S::auto_disable_angular_threshold>({"auto_disable_angular_threshold", Kind::Number, "rad/s",
                                                          "auto_disable: a body turning slower than this may sleep", 0,
                                                          reference_limits::kMaxLength}),
      member_setting<&S::auto_disable_steps>({"auto_disable_steps", Kind::Integer, "",
                                              "auto_disable: steps below both speeds before an island sleeps", 1,
                                              kMostAutoDisableSteps}),
  };
  return table;
}

}  // namespace boxpile
