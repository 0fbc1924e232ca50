// One interface for every engine that can run a scene: our simulator, ODE and Bullet. Declared
// beside the simulator's types so that sim/ knows nothing of ODE or Bullet; the reference
// adapters in reference/ implement it.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

// An engine's own refusal of a scene, or of a state it reached: a model MuJoCo cannot allocate, a
// contact list it cannot grow, an assertion inside ODE. The engine cannot go on with that scene. A
// command that runs one scene reports it as input outside what the engine can take (exit 2);
// `boxpile stability` records it as the cell's failure and goes on with the next cell.
class EngineRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CollisionEvent;  // sim/solver/step_context.hpp
class ContactMethod;  // sim/solver/contact_method.hpp
struct WorldCounters;

// A body's state as every engine reports it. `position` and `orientation` are the scene file's
// body frame (not the centre of mass of a compound); `velocity` is the centre of mass's linear
// velocity and `angular_velocity` is in world coordinates.
struct BodyState {
  std::string name;
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
};

class Engine {
 public:
  virtual ~Engine() = default;

  // "own", "ode", "bullet", or the name of an engine run over the protocol.
  virtual std::string_view name() const = 0;
  // Advances the world by one time step of the scene's dt.
  virtual void step() = 0;
  // Simulated time since the start, s.
  virtual double time() const = 0;
  // Body states in scene order (out is resized; no allocation once it has the size).
  virtual void body_states(std::vector<BodyState>& out) const = 0;
  // The contact set the last step used, in the project's convention (midpoint position, normal
  // from body_b toward body_a, depth > 0 when penetrating); body indices in scene order, kGround
  // for the ground.
  virtual void contacts(std::vector<BodyContact>& out) const = 0;
  // Whether the caller will read contacts() after the steps to come (on when built). An engine
  // for which reporting them costs more than finding them (one run over the protocol, which
  // writes and parses every point as JSON) leaves them out while off, and contacts() is then
  // empty; one in this process finds them for its step anyway and ignores this.
  virtual void report_contacts(bool on) { (void)on; }

  // --- diagnostics: what an engine can tell beside its states (by default, nothing) ---------
  // The collision events its solver recorded so far (ours); nullptr when it records none.
  virtual const std::vector<CollisionEvent>* collision_events() const { return nullptr; }
  // Our solver's contact method (its own records: ContactMethod::diagnostics), and the counters
  // of the stages every method shares; nullptr for the other engines.
  virtual const ContactMethod* solver_method() const { return nullptr; }
  virtual const WorldCounters* solver_counters() const { return nullptr; }
  // Switches on the per-stage profile of its steps (solver_counters()->profile); false when it
  // keeps none.
  virtual bool enable_profile() { return false; }
  // The contact method of its solver ("impulse" or "penalty" for ours); empty when it has no
  // choice of method.
  virtual std::string_view contact_method() const { return {}; }
  // Messages its library reported since the engine was built (ODE's), and the last of them.
  virtual std::uint64_t messages() const { return 0; }
  virtual std::string last_message() const { return {}; }
  // The time the engine measured itself inside its steps so far (s), for an engine run in
  // another process that reports it (docs/engine-protocol.md: `engine_seconds`), so that the
  // protocol's cost is not counted as the engine's; empty when it reports none.
  virtual std::optional<double> reported_seconds() const { return std::nullopt; }
};

}  // namespace boxpile
