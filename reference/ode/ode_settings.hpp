// ODE 0.16's settings that a Scene does not say (solver method and iterations, error reduction
// and constraint mixing, contact caps), and their table: each setting declared once (key, kind,
// unit, range, meaning; the default is the member's initialiser below). docs/reference-engines.md
// says how each maps onto ODE's calls and what cannot be matched.
#pragma once

#include <limits>

#include "boxpile/sim/io/setting.hpp"

namespace boxpile {

enum class OdeStepMethod {
  QuickStep,  // dWorldQuickStep: projected Gauss-Seidel (SOR-LCP), fixed iterations, O(n)
  Step,       // dWorldStep: the "big matrix" Dantzig LCP, exact but O(n^3)
};

struct OdeSettings {
  OdeStepMethod method = OdeStepMethod::QuickStep;
  int quickstep_iterations = 20;  // passes per step (ODE's default)
  double quickstep_sor = 1.3;     // over-relaxation w, dimensionless (ODE's default)
  // Fraction of the joint (and contact) error removed per step, dimensionless (ODE's default).
  double erp = 0.2;
  // Constraint force mixing, the diagonal added to the LCP: (m/s)/N for contacts. ODE's default
  // in double precision.
  double cfm = 1e-10;
  // Points per geom pair passed to dCollide: dBoxBox clips up to 8 (dBoxPlane caps itself at 4).
  int max_contacts = 8;
  // Penetration allowed before ODE corrects it, m (dWorldSetContactSurfaceLayer; default 0).
  double surface_layer = 0.0;
  // Largest velocity ERP may give a contact, m/s (dWorldSetContactMaxCorrectingVel; default none).
  double max_correcting_velocity = std::numeric_limits<double>::infinity();
  // QuickStep shuffles the constraint order with ODE's global generator: reseeded on every build.
  unsigned long seed = 0;
  // A body on a wire hangs by a ball joint from a carriage that a slider joint keeps on the wire
  // (docs/reference-engines.md, "The bone on the wire"). The carriage's mass as a fraction of the
  // body's, dimensionless: heavier carriages hold the wire better in QuickStep but change the
  // swing (measured on a bone hanging by one end: 1% stayed within 2 mm of Bullet's bone for
  // 1.8 s of sliding and swinging, 10% drifted 15 mm away).
  double wire_carriage_mass_fraction = 0.01;
  // Approach speeds below this bounce with no restitution, m/s (bounce_vel).
  double restitution_threshold = 0.2;
  // Sleeping (dWorldSetAutoDisableFlag): an island whose bodies all stay below both speeds for
  // `auto_disable_steps` steps is disabled (its velocities zeroed, its bodies no longer stepped)
  // until something touches it. Off by default here, as every engine is run awake; the speeds
  // and steps are ODE's defaults.
  bool auto_disable = false;
  double auto_disable_linear_threshold = 0.01;   // m/s
  double auto_disable_angular_threshold = 0.01;  // rad/s
  int auto_disable_steps = 10;
};

// ODE's settings, by the names of `--set ode.KEY=VALUE` and sweep grids.
const SettingsTable<OdeSettings>& ode_settings_table();

}  // namespace boxpile
