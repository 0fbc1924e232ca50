// The scene: what every engine (ours, ODE, Bullet) is built from. Plain data; the JSON loader is
// in sim/io/scene_loader.hpp and the format is documented in docs/scene-format.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

// The ground half-space: solid where normal . x < offset.
struct HalfSpace {
  Vec3 normal = Vec3::UnitZ();  // unit
  double offset = 0.0;          // m
};

// Effects a scene asks for. Contact is always on; everything else is simulated only when listed.
struct Effects {
  bool gravity = true;
  bool friction = true;
  bool restitution = true;
  bool damping = false;
  bool gyroscopic = false;  // off unless listed: the lab text neglects the gyroscopic term
};

// Air damping, applied to momenta when the `damping` effect is on: dP = -linear * P dt.
struct Damping {
  double linear = 0.0;   // 1/s
  double angular = 0.0;  // 1/s
};

struct CollisionSettings {
  // Reduce each box-box manifold to at most 4 points (deepest first, then largest area).
  bool reduce_to_four = false;
  // Points up to this far apart still count as contacts (speculative contacts), m.
  double margin = 0.0;
};

enum class ContactSolver { Impulse, Penalty };
enum class PositionIntegrator { ExplicitEuler, SemiImplicitEuler };

// The penalty method's settings (docs/penalty.md). Each one left unset is derived from the
// scene when the world is built (sim/solver/penalty_parameters.hpp).
struct PenaltySettings {
  std::optional<double> stiffness;           // N/m per contact point, normal spring
  std::optional<double> damping;             // N s/m per contact point, normal and tangential damper
  std::optional<double> friction_stiffness;  // N/m per contact point, the friction spring
  std::optional<int> substeps;               // penalty steps per scene step, >= 1
};

struct SolverSettings {
  ContactSolver method = ContactSolver::Impulse;
  PenaltySettings penalty;  // read only by the penalty method
  int collision_passes = 5;       // GBF collision loop passes (5-10)
  int contact_passes = 10;        // GBF contact loop passes, restitution ramped -0.9 -> 0 (10-20)
  bool shock_propagation = true;  // GBF shock propagation after the contact loop
  int shock_passes = 10;          // most passes over one level in shock propagation (fewer once converged)
  PositionIntegrator integrator = PositionIntegrator::ExplicitEuler;
  // Points this far apart (m) are kept in the step's contact set, so that a resting face whose
  // corners rise by rounding (1e-17 m) does not lose them and tip; the solver lets such a point
  // approach by at most its gap in the step (a speculative contact). Suits boxes of 0.1-1 m.
  double contact_margin = 1e-3;
  // Penetration recovery (split impulses, docs/solver.md): the fraction of a penetration deeper
  // than `penetration_slop` pushed out per step through pseudo-velocities that never enter the
  // momenta. 0 turns the stage off (the plain GBF method has none).
  double penetration_recovery = 0.2;  // per step, in [0, 1]
  double penetration_slop = 1e-4;     // m: overlaps this shallow are left alone
  int recovery_passes = 5;
};

struct TimeSettings {
  double dt = 1.0 / 240.0;  // s
  double duration = 5.0;    // s
};

// A wire: the body's anchor point slides without friction along the segment from `from` to `to`
// (and stops at its ends), while the body swings freely about the anchor. The lab text's "bone"
// is a compound body with a wire.
struct Wire {
  Vec3 from = Vec3::Zero();    // m, world
  Vec3 to = Vec3::UnitX();     // m, world
  Vec3 anchor = Vec3::Zero();  // m, in the body frame (the scene file's frame, not the centre of mass)
};

// One body as the scene file describes it. `frame` is the body frame (where `boxes` are placed);
// it need not be the centre of mass of a compound.
struct BodyDesc {
  std::string name;
  double mass = 1.0;  // kg; ignored for fixed bodies
  std::vector<BoxShape> boxes;
  Pose frame;
  Vec3 velocity = Vec3::Zero();          // m/s, of the centre of mass
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, world
  std::optional<Material> material;      // falls back to the scene default
  bool fixed = false;
  std::optional<Wire> wire;  // constrained to a wire (the bone); unset for ordinary bodies
};

struct Scene {
  std::string name;
  std::string note;    // free text: why the scene exists (fixtures say what they test)
  std::string source;  // the file it was loaded from, for messages
  Vec3 gravity{0.0, 0.0, -9.81};
  std::optional<HalfSpace> ground;
  Material material;
  Effects effects;
  Damping damping;
  std::vector<BodyDesc> bodies;
  CollisionSettings collision;
  SolverSettings solver;
  TimeSettings time;
  bool allow_initial_overlap = false;
};

// The simulator's bodies for a scene, in scene order.
std::vector<RigidBody> make_bodies(const Scene& scene);

// An approach faster than this counts as a collision event (m/s), in our World's events and in
// every engine's events of a compare report alike: above twice the |g| dt that gravity adds to a
// resting contact in one step, and above rounding.
double collision_event_speed(const Scene& scene, double dt);

}  // namespace boxpile
