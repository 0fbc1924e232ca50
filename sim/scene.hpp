// The scene: what every engine (ours, ODE, Bullet) is built from. Plain data; the JSON loader is
// in sim/io/scene_loader.hpp and the format is documented in docs/scene-format.md.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/limits.hpp"
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
  // The impulse method: copy a pair's contacts from the last step while neither body has moved
  // beyond rounding (sim/collision/contact_reuse.hpp); off, every pair is tested at every step.
  // The penalty method always tests every pair: its springs read each contact's depth, which a
  // copy would leave up to the tolerance stale (a box at rest then rings at 1e-10 m/s).
  bool reuse_contacts = true;
};

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
  // The contact method: a row of the registry (sim/solver/contact_method.hpp), by its name.
  std::string method = "impulse";
  PenaltySettings penalty;  // read only by the penalty method
  // The impulse method's variant (a row of its variants): ours, "boxpile" (every addition below
  // on), or the method exactly as the lab text gives it, "lab" (every addition off; docs/solver.md,
  // "The lab method and our additions"). Choosing one sets each addition to that variant's value
  // (set_impulse_additions), and an addition given beside it changes it from there.
  std::string variant = "boxpile";
  // The settings of a registered method that keeps no fields of its own here, by key (numbers,
  // and booleans as 0 or 1); read only by that method's rows.
  std::map<std::string, double, std::less<>> method_values;
  // Our additions to the lab text's method, each one a switch (docs/solver.md). Off, the stage is
  // the lab text's:
  bool pair_impulses = true;         // collision loop: a pair's points solved together (off: one by one)
  bool accumulated_impulses = true;  // resting phases: projected Gauss-Seidel (off: push-only impulses)
  bool speculative_contacts = true;  // points up to a margin apart are contacts (off: touching points only)
  bool sticking_solves = true;       // shock propagation solves groups that stick directly (off: passes only)
  bool contact_batches = true;       // contact loop: batches of four sharing no moving body (off: one by one)
  int collision_passes = 5;       // GBF collision loop passes (5-10)
  int contact_passes = 10;        // GBF contact loop passes, restitution ramped -0.9 -> 0 (10-20)
  bool shock_propagation = true;  // GBF shock propagation after the contact loop
  int shock_passes = 64;          // most passes over one level in shock propagation (fewer once converged or stalled)
  PositionIntegrator integrator = PositionIntegrator::SemiImplicitEuler;  // as ODE and Bullet
  // Points this far apart (m) are kept in the step's contact set, so that a resting face whose
  // corners rise by rounding (1e-17 m) does not lose them and tip; the solver lets such a point
  // approach by at most its gap in the step (a speculative contact). Suits boxes of 0.1-1 m.
  double contact_margin = 1e-3;
  // Penetration recovery (split impulses, docs/solver.md): the fraction of a penetration deeper
  // than `penetration_slop` pushed out per step through pseudo-velocities that never enter the
  // momenta. 0 turns the stage off (the plain GBF method has none).
  double penetration_recovery = 0.2;  // per step, in [0, 1]
  double penetration_slop = 1e-4;     // m: overlaps this shallow are left alone
  int recovery_passes = 20;  // most per group of a phase (each shock level, then all contacts), fewer once converged
  // Threads a step runs on, every method's (0: every core of the machine): the contact search's
  // pairs and the impulse method's islands of touching bodies are shared among them. The result
  // is the same to the bit whatever the number.
  int threads = 0;
};

// Sets every addition of ours on (the "boxpile" variant: semi-implicit Euler, penetration recovery
// 0.2, shock propagation and contacts kept at rest) or off (the "lab" variant: explicit Euler, no
// recovery, no shock propagation, every pair tested at every step).
void set_impulse_additions(SolverSettings& solver, CollisionSettings& collision, bool on);

// The contact margin and penetration slop for boxes whose smallest edge is `smallest_edge` (m):
// the settings' values, or less for small boxes (docs/solver.md, "Lengths relative to the boxes").
double contact_margin_for(const SolverSettings& settings, double smallest_edge);
double penetration_slop_for(const SolverSettings& settings, double smallest_edge);

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

// What the scene's bodies do, known in closed form (docs/scene-format.md, "Truth"): what
// `boxpile accuracy` and the tests measure every engine's error against. Bodies are named in the
// file and resolved to scene indices by the loader.
struct TruthPoint {  // a body's position (m) or velocity (m/s) at the end of the run
  int body = 0;
  Vec3 value = Vec3::Zero();
};
struct TruthOrientation {  // a body's orientation at the end of the run
  int body = 0;
  Quat orientation = Quat::Identity();
};
// position(t) = start + velocity s + acceleration s^2 / 2 with s = min(t, until): uniform
// acceleration until `until`, then at rest there (a box sliding to a stop).
struct TruthTrajectory {
  int body = 0;
  Vec3 start = Vec3::Zero();         // m (the body's start unless given)
  Vec3 velocity = Vec3::Zero();      // m/s (the body's start velocity unless given)
  Vec3 acceleration = Vec3::Zero();  // m/s^2
  std::optional<double> until;       // s; unset: the whole run
  Vec3 at(double t) const;
};
// After its first impact the body's centre rises to `height` (m, along -gravity, the highest
// point of its first flight after the impact).
struct TruthRebound {
  int body = 0;
  double height = 0.0;
};
struct SceneTruth {
  std::vector<TruthPoint> final_positions;
  std::vector<TruthPoint> final_velocities;
  std::vector<TruthOrientation> final_orientations;
  std::vector<TruthTrajectory> trajectories;
  std::optional<TruthRebound> rebound;
  // The duration (s) the final states are stated for: the scene's, as loaded. A run of another
  // length cannot be measured against them (trajectories and rebounds hold at any length).
  double duration = 0.0;
  bool empty() const {
    return final_positions.empty() && final_velocities.empty() && final_orientations.empty() &&
           trajectories.empty() && !rebound;
  }
  bool has_final_states() const {
    return !final_positions.empty() || !final_velocities.empty() || !final_orientations.empty();
  }
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
  // What the scene promises to hold in every engine: its "checks" object as the file gives it,
  // compact JSON text ("" when the file has none). The checks are validation's, one file each
  // (validation/stability/checks/, docs/scene-format.md "Checks"): each reads its own key, and
  // every command that runs checks loads scenes through load_checked_scene()
  // (validation/stability/scene_checks.hpp), so that a bad check is refused at load.
  std::string checks;
  SceneTruth truth;  // empty when the scene states none
  // A cap on work, not read from the file (the loader's LoadLimits, the command line's
  // --max-pairs): our World refuses a step whose broadphase finds more pairs than this.
  std::size_t max_pairs = limits::kDefaultMaxPairs;
};

// The simulator's bodies for a scene, in scene order.
std::vector<RigidBody> make_bodies(const Scene& scene);

// An approach faster than this counts as a collision event (m/s), in our World's events and in
// every engine's events of a compare report alike: above twice the |g| dt that gravity adds to a
// resting contact in one step, and above rounding.
double collision_event_speed(const Scene& scene, double dt);

}  // namespace boxpile
