#include <array>
#include <string_view>

#include "boxpile/reference/mujoco/mujoco_setting_table.hpp"

namespace boxpile {
namespace {

using Kind = EngineSetting::Kind;
using nlohmann::json;

// Iteration counts: far above any useful value, low enough that a typo (1e9) is refused instead
// of running for hours (as for ODE and Bullet).
constexpr double kMaxIterations = 100000;
// solimp's impedances lie in MuJoCo's open interval (mjMINIMP, mjMAXIMP) = (0.0001, 0.9999).
constexpr double kLeastImpedance = 0.0001, kLargestImpedance = 0.9999;
// Longest contact time constant, transition width and largest ratios a setting may name: none
// has a meaning for boxes of centimetres to metres beyond these.
constexpr double kLongestTimeconst = 10.0;  // s
constexpr double kWidestTransition = 1.0;   // m
constexpr double kLeastRatio = 1e-3, kLargestRatio = 1e3;

constexpr std::array<std::string_view, 3> kSolvers = {"pgs", "cg", "newton"};
constexpr std::array<std::string_view, 2> kCones = {"pyramidal", "elliptic"};
constexpr std::array<std::string_view, 3> kIntegrators = {"euler", "rk4", "implicit"};

MujocoSettings& of(EngineConfig& c) { return c.reference.mujoco; }

const std::array kMujocoSettings = {
    EngineSetting{"solver", Kind::Choice, "", "constraint solver: projected Gauss-Seidel, conjugate gradient or Newton",
                  0, 0, kSolvers,
                  [](EngineConfig& c, const json& v) {
                    const std::string s = v.get<std::string>();
                    of(c).solver = s == "pgs" ? MujocoSolver::PGS : s == "cg" ? MujocoSolver::CG : MujocoSolver::Newton;
                  }},
    EngineSetting{"iterations", Kind::Integer, "", "most main-solver iterations per step", 1, kMaxIterations, {},
                  [](EngineConfig& c, const json& v) { of(c).iterations = v.get<int>(); }},
    EngineSetting{"tolerance", Kind::Number, "", "main solver stops when its relative improvement is below this (0: never)",
                  0, 1, {}, [](EngineConfig& c, const json& v) { of(c).tolerance = v.get<double>(); }},
    EngineSetting{"cone", Kind::Choice, "", "friction cone", 0, 0, kCones,
                  [](EngineConfig& c, const json& v) {
                    of(c).cone = v.get<std::string>() == "elliptic" ? MujocoCone::Elliptic : MujocoCone::Pyramidal;
                  }},
    EngineSetting{"solref_timeconst", Kind::Number, "s",
                  "time constant of the contacts' spring-damper (MuJoCo raises it to 2 dt)", 1e-6, kLongestTimeconst, {},
                  [](EngineConfig& c, const json& v) { of(c).solref_timeconst = v.get<double>(); }},
    EngineSetting{"solref_dampratio", Kind::Number, "", "damping ratio of the contacts' spring-damper (1: critical)",
                  kLeastRatio, kLargestRatio, {},
                  [](EngineConfig& c, const json& v) { of(c).solref_dampratio = v.get<double>(); }},
    EngineSetting{"solimp_dmin", Kind::Number, "", "contact impedance at zero penetration", kLeastImpedance,
                  kLargestImpedance, {}, [](EngineConfig& c, const json& v) { of(c).solimp_dmin = v.get<double>(); }},
    EngineSetting{"solimp_dmax", Kind::Number, "", "contact impedance from solimp_width deep on", kLeastImpedance,
                  kLargestImpedance, {}, [](EngineConfig& c, const json& v) { of(c).solimp_dmax = v.get<double>(); }},
    EngineSetting{"solimp_width", Kind::Number, "m", "penetration over which the impedance goes from dmin to dmax", 0,
                  kWidestTransition, {}, [](EngineConfig& c, const json& v) { of(c).solimp_width = v.get<double>(); }},
    EngineSetting{"noslip_iterations", Kind::Integer, "", "iterations of the noslip solver after the main one (0: off)",
                  0, kMaxIterations, {},
                  [](EngineConfig& c, const json& v) { of(c).noslip_iterations = v.get<int>(); }},
    EngineSetting{"impratio", Kind::Number, "", "frictional over normal constraint impedance (elliptic cones)",
                  kLeastRatio, kLargestRatio, {}, [](EngineConfig& c, const json& v) { of(c).impratio = v.get<double>(); }},
    EngineSetting{"integrator", Kind::Choice, "",
                  "semi-implicit Euler, 4th-order Runge-Kutta or implicit in velocity (the last two need the scene's "
                  "gyroscopic effect on)",
                  0, 0, kIntegrators,
                  [](EngineConfig& c, const json& v) {
                    const std::string s = v.get<std::string>();
                    of(c).integrator = s == "rk4"        ? MujocoIntegrator::RK4
                                       : s == "implicit" ? MujocoIntegrator::Implicit
                                                         : MujocoIntegrator::Euler;
                  }},
};

}  // namespace

std::span<const EngineSetting> mujoco_setting_table() { return kMujocoSettings; }

}  // namespace boxpile
