// Settings of the reference engines (ODE, Bullet and DART) that a Scene does not say: solver method and
// iterations, error reduction and constraint mixing, contact caps. Every field has a default and a
// unit; docs/reference-engines.md says how each maps to the engine and what cannot be matched.
#pragma once

#include <limits>

#include "boxpile/reference/dart/dart_settings.hpp"

namespace boxpile {

enum class OdeStepMethod {
  QuickStep,  // dWorldQuickStep: projected Gauss-Seidel (SOR-LCP), fixed iterations, O(n)
  Step,       // dWorldStep: the "big matrix" Dantzig LCP, exact but O(n^3)
};

struct ReferenceSettings {
  // --- ODE 0.16 -----------------------------------------------------------------------------
  OdeStepMethod ode_method = OdeStepMethod::QuickStep;
  int ode_quickstep_iterations = 20;  // passes per step (ODE's default)
  double ode_quickstep_sor = 1.3;     // over-relaxation w, dimensionless (ODE's default)
  // Fraction of the joint (and contact) error removed per step, dimensionless (ODE's default).
  double ode_erp = 0.2;
  // Constraint force mixing, the diagonal added to the LCP: (m/s)/N for contacts. ODE's default
  // in double precision.
  double ode_cfm = 1e-10;
  // Points per geom pair passed to dCollide: dBoxBox clips up to 8 (dBoxPlane caps itself at 4).
  int ode_max_contacts = 8;
  // Penetration allowed before ODE corrects it, m (dWorldSetContactSurfaceLayer; default 0).
  double ode_surface_layer = 0.0;
  // Largest velocity ERP may give a contact, m/s (dWorldSetContactMaxCorrectingVel; default none).
  double ode_max_correcting_velocity = std::numeric_limits<double>::infinity();
  // QuickStep shuffles the constraint order with ODE's global generator: reseeded on every build.
  unsigned long ode_seed = 0;
  // A body on a wire hangs by a ball joint from a carriage that a slider joint keeps on the wire
  // (docs/reference-engines.md, "The bone on the wire"). The carriage's mass as a fraction of the
  // body's, dimensionless: heavier carriages hold the wire better in QuickStep but change the
  // swing (measured on a bone hanging by one end: 1% stayed within 2 mm of Bullet's bone for
  // 1.8 s of sliding and swinging, 10% drifted 15 mm away).
  double ode_wire_carriage_mass_fraction = 0.01;

  // --- Bullet 3.24 (double precision) --------------------------------------------------------
  int bullet_iterations = 10;  // sequential-impulse passes (btContactSolverInfo::m_numIterations)
  // Error reduction per step, dimensionless (m_erp; Bullet's default): for contacts shallower
  // than the split-impulse threshold (or all contacts without split impulse) it is a Baumgarte
  // velocity bias inside the contact impulse.
  double bullet_erp = 0.2;
  // Split impulse: contacts deeper than the threshold are pushed apart by a separate
  // pseudo-velocity that adds no momentum, with error reduction m_erp2 (Bullet's defaults: on,
  // 0.04 m, 0.2).
  bool bullet_split_impulse = true;
  double bullet_split_impulse_threshold = -0.04;  // m, a negative distance
  double bullet_split_erp = 0.2;
  double bullet_cfm = 0.0;  // m_globalCfm, Bullet's default
  // Box-plane pairs: Bullet adds one point per step unless perturbation iterations are set
  // (btDefaultCollisionConfiguration::setPlaneConvexMultipointIterations); 0 keeps the default.
  int bullet_plane_iterations = 0;
  int bullet_plane_min_points = 3;  // perturb only while the manifold has fewer points

  // --- both ---------------------------------------------------------------------------------
  // Approach speeds below this bounce with no restitution, m/s (ODE bounce_vel, Bullet
  // m_restitutionVelocityThreshold; Bullet's default).
  double restitution_threshold = 0.2;

  // --- DART 6.12 (its own struct: reference/dart/dart_settings.hpp) --------------------------
  DartSettings dart;
};

}  // namespace boxpile
