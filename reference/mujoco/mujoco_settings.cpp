#include "boxpile/reference/mujoco/mujoco_settings.hpp"

#include "boxpile/reference/limits.hpp"

namespace boxpile {

using nlohmann::json;
using Kind = SettingInfo::Kind;

namespace {

// solimp's impedances lie in MuJoCo's open interval (mjMINIMP, mjMAXIMP) = (0.0001, 0.9999).
constexpr double kLeastImpedance = 0.0001, kLargestImpedance = 0.9999;
// Longest contact time constant, transition width and largest ratios a setting may name: none
// has a meaning for boxes of centimetres to metres beyond these.
constexpr double kLongestTimeconst = 10.0;  // s
constexpr double kWidestTransition = 1.0;   // m
constexpr double kLeastRatio = 1e-3, kLargestRatio = 1e3;

const char* solver_key(MujocoSolver s) {
  return s == MujocoSolver::PGS ? "pgs" : s == MujocoSolver::CG ? "cg" : "newton";
}
const char* integrator_key(MujocoIntegrator i) {
  return i == MujocoIntegrator::RK4 ? "rk4" : i == MujocoIntegrator::Implicit ? "implicit" : "euler";
}

}  // namespace

const SettingsTable<MujocoSettings>& mujoco_settings_table() {
  using S = MujocoSettings;
  static const SettingsTable<MujocoSettings> table{
      {{"solver",
        Kind::Choice,
        "",
        "constraint solver: projected Gauss-Seidel, conjugate gradient or Newton",
        0,
        0,
        {"pgs", "cg", "newton"}},
       [](S& s, const json& v) {
         const std::string n = v.get<std::string>();
         s.solver = n == "pgs" ? MujocoSolver::PGS : n == "cg" ? MujocoSolver::CG : MujocoSolver::Newton;
       },
       [](const S& s) { return json(solver_key(s.solver)); }},
      member_setting<&S::iterations>({"iterations", Kind::Integer, "", "most main-solver iterations per step", 1,
                                      reference_limits::kMaxIterations}),
      member_setting<&S::tolerance>({"tolerance", Kind::Number, "",
                                     "main solver stops when its relative improvement is below this (0: never)", 0, 1}),
      {{"cone", Kind::Choice, "", "friction cone", 0, 0, {"pyramidal", "elliptic"}},
       [](S& s, const json& v) {
         s.cone = v.get<std::string>() == "elliptic" ? MujocoCone::Elliptic : MujocoCone::Pyramidal;
       },
       [](const S& s) { return json(s.cone == MujocoCone::Elliptic ? "elliptic" : "pyramidal"); }},
      member_setting<&S::solref_timeconst>({"solref_timeconst", Kind::Number, "s",
                                            "time constant of the contacts' spring-damper (MuJoCo raises it to 2 dt)",
                                            1e-6, kLongestTimeconst}),
      member_setting<&S::solref_dampratio>({"solref_dampratio", Kind::Number, "",
                                            "damping ratio of the contacts' spring-damper (1: critical)", kLeastRatio,
                                            kLargestRatio}),
      member_setting<&S::solimp_dmin>({"solimp_dmin", Kind::Number, "", "contact impedance at zero penetration",
                                       kLeastImpedance, kLargestImpedance}),
      member_setting<&S::solimp_dmax>({"solimp_dmax", Kind::Number, "", "contact impedance from solimp_width deep on",
                                       kLeastImpedance, kLargestImpedance}),
      member_setting<&S::solimp_width>({"solimp_width", Kind::Number, "m",
                                        "penetration over which the impedance goes from dmin to dmax", 0,
                                        kWidestTransition}),
      member_setting<&S::noslip_iterations>({"noslip_iterations", Kind::Integer, "",
                                             "iterations of the noslip solver after the main one (0: off)", 0,
                                             reference_limits::kMaxIterations}),
      member_setting<&S::impratio>({"impratio", Kind::Number, "",
                                    "frictional over normal constraint impedance (elliptic cones)", kLeastRatio,
                                    kLargestRatio}),
      {{"integrator",
        Kind::Choice,
        "",
        "semi-implicit Euler, 4th-order Runge-Kutta or implicit in velocity (the last two need the scene's "
        "gyroscopic effect on)",
        0,
        0,
        {"euler", "rk4", "implicit"}},
       [](S& s, const json& v) {
         const std::string n = v.get<std::string>();
         s.integrator = n == "rk4"        ? MujocoIntegrator::RK4
                        : n == "implicit" ? MujocoIntegrator::Implicit
                                          : MujocoIntegrator::Euler;
       },
       [](const S& s) { return json(integrator_key(s.integrator)); }},
  };
  return table;
}

}  // namespace boxpile
