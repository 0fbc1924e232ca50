// Settings of the DART 6.12 engine that a Scene does not say: its contact detector, its boxed LCP
// solver and the contact constraint's error correction. Every default is DART's own except the
// detector (see DartSettings::detector); docs/reference-engines.md ("DART 6.12") says how each
// maps onto DART and what cannot be matched. No DART header here: DART's types stay in the .cpp
// files of reference/dart/.
#pragma once

#include "boxpile/sim/io/setting.hpp"

namespace boxpile {

// DART's collision detectors in Debian's build (libdart6.12, libdart-collision-ode6.12). Bullet's
// (libdart-collision-bullet) is not offered: Debian builds it against single-precision Bullet,
// whose symbols clash with the double-precision Bullet boxpile links.
enum class DartDetector {
  Dart,          // DARTCollisionDetector: DART's own box-box (a port of ODE's dBoxBox), no planes
  Fcl,           // FCLCollisionDetector as DART builds it by default: every box as a triangle mesh
  FclPrimitive,  // FCLCollisionDetector with FCL's analytic box primitives (setPrimitiveShapeType)
  Ode,           // OdeCollisionDetector: ODE's dCollide (dBoxBox, dBoxPlane)
};

// The boxed LCP solver of DART's BoxedLcpConstraintSolver.
enum class DartLcpSolver {
  Dantzig,  // DantzigBoxedLcpSolver: ODE's pivoting solver, exact up to rounding
  Pgs,      // PgsBoxedLcpSolver: projected Gauss-Seidel, iterative
};

struct DartSettings {
  // DART's own default is Fcl (boxes as meshes). It is not ours: FCL's meshes give bogus contacts
  // against a plane, 6 points per resting face pair instead of 4 against a box, let a stack of 10
  // drift 2.5e-2 m and cost about 11 times DART's own detector a step there
  // (docs/reference-engines.md, "DART 6.12").
  DartDetector detector = DartDetector::Dart;
  // DART's default: Dantzig first, PGS when Dantzig fails (a secondary solver).
  DartLcpSolver lcp_solver = DartLcpSolver::Dantzig;
  bool pgs_fallback = true;  // run PGS when the main solver fails (DART's default: on)
  int pgs_iterations = 30;   // PGS sweeps per solve (PgsBoxedLcpSolver::Option, DART's default)
  // Contact points kept per collision pass, all pairs together (CollisionOption::maxNumContacts;
  // DART's default 1000). Contacts beyond it are dropped, the rest of the pass unchecked.
  int max_contacts = 1000;
  // The contact constraint's error correction (ContactConstraint's static parameters; DART's
  // defaults): penetration left alone, m; fraction of the rest removed per step; the largest
  // velocity that correction may give, m/s; constraint force mixing (the diagonal added to the
  // LCP), dimensionless in DART's normalised rows.
  double error_allowance = 0.0;
  double erp = 0.01;
  double max_erv = 1e-3;
  double cfm = 1e-5;
  // A body on a wire hangs by a ball joint from a carriage on a prismatic joint (reduced
  // coordinates: the chain holds exactly). The carriage's mass and inertia as a fraction of the
  // body's: a small value changes the motion little; DART's articulated-body algorithm needs
  // some mass on every body.
  double wire_carriage_mass_fraction = 1e-3;
};

// DART's settings, one row per field (sim/io/setting.hpp).
const SettingsTable<DartSettings>& dart_settings_table();

}  // namespace boxpile
