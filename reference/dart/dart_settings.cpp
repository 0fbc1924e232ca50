#include <array>
#include <string>

#include "boxpile/reference/dart/dart_settings_table.hpp"

namespace boxpile {
namespace {

using Kind = EngineSetting::Kind;
using nlohmann::json;

// The choice names, in the order of the enums (reference/dart/dart_settings.hpp).
constexpr std::array<std::string_view, 4> kDetectors = {"dart", "fcl", "fcl_primitive", "ode"};
constexpr std::array<std::string_view, 2> kLcpSolvers = {"dantzig", "pgs"};

template <class Enum, std::size_t N>
Enum choice_of(const std::array<std::string_view, N>& names, const json& v) {
  const std::string name = v.get<std::string>();
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i] == name) return static_cast<Enum>(i);
  }
  return static_cast<Enum>(0);  // not reached: check_setting_value has refused other names
}

// PGS sweeps and contact caps: far above any useful value, low enough that a typo is refused.
constexpr double kMaxPgsIterations = 100000;
constexpr double kMaxContactsPerPass = 1e6;
// Distances and speeds of the error correction, m and m/s: nothing meaningful lies beyond.
constexpr double kMaxLength = 1e3;

const std::array kDartSettings = {
    EngineSetting{"detector", Kind::Choice, "",
                  "contact detector: dart (DARTCollisionDetector, our default), fcl (FCL with boxes as meshes: "
                  "DART's default), fcl_primitive (FCL's box primitives), ode (ODE's dCollide)",
                  0, 0, kDetectors,
                  [](EngineConfig& c, const json& v) { c.reference.dart.detector = choice_of<DartDetector>(kDetectors, v); }},
    EngineSetting{"lcp_solver", Kind::Choice, "", "boxed LCP solver of the constraint solver: Dantzig (pivoting) or PGS",
                  0, 0, kLcpSolvers,
                  [](EngineConfig& c, const json& v) {
                    c.reference.dart.lcp_solver = choice_of<DartLcpSolver>(kLcpSolvers, v);
                  }},
    EngineSetting{"pgs_fallback", Kind::Boolean, "", "run PGS when the Dantzig solver fails (the secondary solver)", 0,
                  0, {}, [](EngineConfig& c, const json& v) { c.reference.dart.pgs_fallback = v.get<bool>(); }},
    EngineSetting{"pgs_iterations", Kind::Integer, "", "PGS sweeps per solve (main or fallback solver)", 1,
                  kMaxPgsIterations, {},
                  [](EngineConfig& c, const json& v) { c.reference.dart.pgs_iterations = v.get<int>(); }},
    EngineSetting{"max_contacts", Kind::Integer, "", "contact points per collision pass, all pairs together", 1,
                  kMaxContactsPerPass, {},
                  [](EngineConfig& c, const json& v) { c.reference.dart.max_contacts = v.get<int>(); }},
    EngineSetting{"error_allowance", Kind::Number, "m", "penetration the contact constraint leaves alone", 0, kMaxLength,
                  {}, [](EngineConfig& c, const json& v) { c.reference.dart.error_allowance = v.get<double>(); }},
    EngineSetting{"erp", Kind::Number, "1/step", "error reduction: fraction of the penetration removed per step", 0, 1,
                  {}, [](EngineConfig& c, const json& v) { c.reference.dart.erp = v.get<double>(); }},
    EngineSetting{"max_erv", Kind::Number, "m/s", "largest velocity the error reduction may give a contact", 0,
                  kMaxLength, {}, [](EngineConfig& c, const json& v) { c.reference.dart.max_erv = v.get<double>(); }},
    EngineSetting{"cfm", Kind::Number, "", "constraint force mixing added to each contact row (normalised)", 0, 1, {},
                  [](EngineConfig& c, const json& v) { c.reference.dart.cfm = v.get<double>(); }},
    EngineSetting{"wire_carriage_mass_fraction", Kind::Number, "", "the wire carriage's mass over the body's", 1e-9, 1,
                  {},
                  [](EngineConfig& c, const json& v) {
                    c.reference.dart.wire_carriage_mass_fraction = v.get<double>();
                  }},
};

}  // namespace

std::span<const EngineSetting> dart_engine_settings() { return kDartSettings; }

}  // namespace boxpile
