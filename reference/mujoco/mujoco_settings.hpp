// Settings of the MuJoCo 2.2.2 engine that a Scene does not say: the constraint solver, its
// iterations and tolerance, the friction cone, the contacts' softness (solref, solimp), the
// noslip pass and the integrator. Every default is MuJoCo's own (mjOption and the geom defaults
// of 2.2.2), so a run is what a MuJoCo user gets; docs/reference-engines.md says how each maps
// and what cannot be matched.
#pragma once

#include "boxpile/sim/io/setting.hpp"

namespace boxpile {

enum class MujocoSolver { PGS, CG, Newton };
enum class MujocoCone { Pyramidal, Elliptic };
enum class MujocoIntegrator { Euler, RK4, Implicit };

struct MujocoSettings {
  MujocoSolver solver = MujocoSolver::Newton;  // mjOption::solver
  int iterations = 100;                        // main solver iterations per step
  double tolerance = 1e-8;                     // main solver tolerance, dimensionless (relative improvement)
  MujocoCone cone = MujocoCone::Pyramidal;     // friction cone
  // Contact reference (solref, standard form): the time constant of the contact's spring-damper,
  // s, and its damping ratio, dimensionless (1: critically damped).
  double solref_timeconst = 0.02;
  double solref_dampratio = 1.0;
  // Contact impedance (solimp): the constraint's impedance grows from dmin at zero penetration to
  // dmax at `width` (m), dimensionless in (0, 1); midpoint and power keep MuJoCo's 0.5 and 2.
  double solimp_dmin = 0.9;
  double solimp_dmax = 0.95;
  double solimp_width = 0.001;  // m
  int noslip_iterations = 0;    // iterations of the noslip solver after the main one (0: off)
  // Ratio of the frictional to the normal constraint impedance, dimensionless (elliptic cones).
  double impratio = 1.0;
  MujocoIntegrator integrator = MujocoIntegrator::Euler;  // semi-implicit Euler, MuJoCo's default
};

// MuJoCo's settings, one row per field (sim/io/setting.hpp).
const SettingsTable<MujocoSettings>& mujoco_settings_table();

}  // namespace boxpile
