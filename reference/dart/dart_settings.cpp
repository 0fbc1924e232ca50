#include "boxpile/reference/dart/dart_settings.hpp"

#include <array>
#include <string>

#include "boxpile/reference/limits.hpp"

namespace boxpile {

using nlohmann::json;
using Kind = SettingInfo::Kind;

namespace {

// The choice names, in the order of the enums (dart_settings.hpp).
constexpr std::array<const char*, 4> kDartDetectorKeys = {"dart", "fcl", "fcl_primitive", "ode"};
constexpr std::array<const char*, 2> kDartLcpKeys = {"dantzig", "pgs"};

// The enum value named `v` (a choice the table has already checked).
template <class Enum, std::size_t N>
Enum dart_choice(const std::array<const char*, N>& keys, const json& v) {
  const std::string name = v.get<std::string>();
  for (std::size_t i = 0; i < N; ++i)
    if (name == keys[i]) return static_cast<Enum>(i);
  throw std::invalid_argument("no choice \"" + name + "\"");
}

template <class Enum, std::size_t N>
json dart_key(const std::array<const char*, N>& keys, Enum e) {
  return json(keys[static_cast<std::size_t>(e)]);
}

// Contact points per collision pass: far above any scene's, low enough that a typo is refused.
constexpr double kMaxContactsPerPass = 1e6;

}  // namespace

const SettingsTable<DartSettings>& dart_settings_table() {
  using S = DartSettings;
  static const SettingsTable<DartSettings> table{
      {{"detector",
        Kind::Choice,
        "",
        "contact detector: DART's own (DARTCollisionDetector), FCL with boxes as meshes (DART's default), FCL's "
        "box primitives, or ODE's dCollide",
        0,
        0,
        {kDartDetectorKeys.begin(), kDartDetectorKeys.end()}},
       [](S& s, const json& v) { s.detector = dart_choice<DartDetector>(kDartDetectorKeys, v); },
       [](const S& s) { return dart_key(kDartDetectorKeys, s.detector); }},
      {{"lcp_solver",
        Kind::Choice,
        "",
        "boxed LCP solver of the constraint solver: Dantzig (pivoting) or PGS",
        0,
        0,
        {kDartLcpKeys.begin(), kDartLcpKeys.end()}},
       [](S& s, const json& v) { s.lcp_solver = dart_choice<DartLcpSolver>(kDartLcpKeys, v); },
       [](const S& s) { return dart_key(kDartLcpKeys, s.lcp_solver); }},
      member_setting<&S::pgs_fallback>(
          {"pgs_fallback", Kind::Boolean, "", "run PGS when the Dantzig solver fails (the secondary solver)"}),
      member_setting<&S::pgs_iterations>({"pgs_iterations", Kind::Integer, "",
                                          "PGS sweeps per solve (main or fallback solver)", 1,
                                          reference_limits::kMaxIterations}),
      member_setting<&S::max_contacts>({"max_contacts", Kind::Integer, "",
                                        "contact points per collision pass, all pairs together (the rest dropped)", 1,
                                        kMaxContactsPerPass}),
      member_setting<&S::error_allowance>({"error_allowance", Kind::Number, "m",
                                           "penetration the contact constraint leaves alone", 0,
                                           reference_limits::kMaxLength}),
      member_setting<&S::erp>(
          {"erp", Kind::Number, "1/step", "error reduction: fraction of the penetration removed per step", 0, 1}),
      member_setting<&S::max_erv>({"max_erv", Kind::Number, "m/s",
                                   "largest velocity the error reduction may give a contact", 0,
                                   reference_limits::kMaxLength}),
      member_setting<&S::cfm>(
          {"cfm", Kind::Number, "", "constraint force mixing added to each contact row (normalised)", 0, 1}),
      member_setting<&S::wire_carriage_mass_fraction>({"wire_carriage_mass_fraction", Kind::Number, "",
                                                       "the wire carriage's mass and inertia over the body's", 1e-9,
                                                       1}),
  };
  return table;
}

}  // namespace boxpile
