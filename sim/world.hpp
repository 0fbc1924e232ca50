// Our simulator: a World built from a Scene, stepped by the Guendelman-Bridson-Fedkiw method.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "sim/body.hpp"
#include "sim/collision/broadphase.hpp"
#include "sim/collision/collide.hpp"
#include "sim/engine.hpp"
#include "sim/scene.hpp"
#include "sim/solver/loops.hpp"
#include "sim/solver/recovery.hpp"
#include "sim/solver/wire.hpp"

namespace boxpile {

// How often each stage ran and how much work it did: a scene without an effect never pays for it.
struct WorldCounters {
  std::uint64_t steps = 0;
  std::uint64_t broadphase_pairs = 0;     // pairs the broadphase passed on
  std::uint64_t narrowphase_calls = 0;    // box-box and box-plane tests run
  std::uint64_t collision_loop_runs = 0;
  std::uint64_t contact_loop_runs = 0;
  std::uint64_t shock_propagation_runs = 0;
  std::uint64_t recovery_runs = 0;
  std::uint64_t gravity_applications = 0;  // per body and step
  std::uint64_t damping_applications = 0;  // per body and step
  std::uint64_t gyroscopic_updates = 0;    // per body and step
  ImpulseCounters impulses;
};

class World final : public Engine {
 public:
  explicit World(const Scene& scene);

  std::string_view name() const override { return "own"; }
  void step() override;
  double time() const override { return time_; }
  void body_states(std::vector<BodyState>& out) const override;
  void contacts(std::vector<BodyContact>& out) const override { out = contacts_; }

  const std::vector<RigidBody>& bodies() const { return bodies_; }
  std::vector<RigidBody>& bodies() { return bodies_; }
  const WorldCounters& counters() const { return counters_; }
  const StepStats& last_step_stats() const { return stats_; }
  const std::vector<CollisionEvent>& events() const { return events_; }
  const Scene& scene() const { return scene_; }
  const std::vector<WireJoint>& wires() const { return wires_; }

 private:
  // The stages of one step, in the order of the method (see docs/solver.md).
  void find_contacts();
  void prepare_solver_contacts();
  void integrate_momenta();
  void integrate_positions();
  // The wires' velocity constraint on every wired body (the bone), and the projection after the
  // position update.
  void enforce_wires();
  void project_wires();

  Scene scene_;
  std::vector<RigidBody> bodies_;
  RigidBody ground_;  // a fixed body standing for the half-space in the solver
  double time_ = 0.0;

  SweepAndPrune broadphase_;
  std::vector<BodyContact> contacts_;
  std::vector<SolverContact> solver_contacts_;
  ShockPropagation shock_;
  PenetrationRecovery recovery_;
  std::vector<WireJoint> wires_;
  std::vector<Vec3> start_v_, start_omega_;
  std::vector<double> margins_;          // per body, this step's speculative margin, m
  std::vector<double> bounding_radius_;  // per body, m  // velocities at the step's start (explicit Euler)
  std::vector<CollisionEvent> events_;
  WorldCounters counters_;
  StepStats stats_;
};

// Pair materials: friction is the geometric mean sqrt(mu_a mu_b) (zero if either is
// frictionless), restitution the larger of the two (docs/scene-format.md).
Material combine_materials(const Material& a, const Material& b);

}  // namespace boxpile
