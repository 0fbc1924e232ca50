// Bullet 3.24's (double precision) settings that a Scene does not say (solver iterations, error
// reduction, split impulse, constraint mixing, box-plane points), and their table: each setting
// declared once (key, kind, unit, range, meaning; the default is the member's initialiser below).
// docs/reference-engines.md says how each maps onto Bullet and what cannot be matched.
#pragma once

#include "boxpile/sim/io/setting.hpp"

namespace boxpile {

struct BulletSettings {
  int iterations = 10;  // sequential-impulse passes (btContactSolverInfo::m_numIterations)
  // Error reduction per step, dimensionless (m_erp; Bullet's default): for contacts shallower
  // than the split-impulse threshold (or all contacts without split impulse) it is a Baumgarte
  // velocity bias inside the contact impulse.
  double erp = 0.2;
  // Split impulse: contacts deeper than the threshold are pushed apart by a separate
  // pseudo-velocity that adds no momentum, with error reduction m_erp2 (Bullet's defaults: on,
  // 0.04 m, 0.2).
  bool split_impulse = true;
  double split_impulse_threshold = -0.04;  // m, a negative distance
  double split_erp = 0.2;
  double cfm = 0.0;  // m_globalCfm, Bullet's default
  // Box-plane pairs: Bullet adds one point per step unless perturbation iterations are set
  // (btDefaultCollisionConfiguration::setPlaneConvexMultipointIterations); 0 keeps the default.
  int plane_iterations = 0;
  int plane_min_points = 3;  // perturb only while the manifold has fewer points
  // Approach speeds below this bounce with no restitution, m/s (m_restitutionVelocityThreshold;
  // Bullet's default).
  double restitution_threshold = 0.2;
  // Deactivation (sleeping): a body below both speeds for Bullet's deactivation time (its global
  // gDeactivationTime, 2 s) sleeps with its island until touched. Off by default here
  // (DISABLE_DEACTIVATION), as every engine is run awake; the speeds are Bullet's defaults.
  bool sleeping = false;
  double linear_sleeping_threshold = 0.8;   // m/s
  double angular_sleeping_threshold = 1.0;  // rad/s
  // Continuous collision detection: a body moving farther than the motion threshold in one step
  // is swept as a sphere of the given radius against the others, and stopped at the first touch
  // (btCollisionObject::setCcdMotionThreshold, setCcdSweptSphereRadius). 0: off (Bullet's default).
  double ccd_motion_threshold = 0.0;  // m per step
  double ccd_swept_sphere_radius = 0.0;  // m
};

// Bullet's settings, by the names of `--set bullet.KEY=VALUE` and sweep grids.
const SettingsTable<BulletSettings>& bullet_settings_table();

}  // namespace boxpile
