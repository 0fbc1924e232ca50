// The step context: what every stage of a step works on, the world's shared parts by reference
// (scene settings, bodies, the contact set, wires), the step's time and length, and where the
// stages record their work. The contact methods (impulse, penalty) take it instead of long
// argument lists.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/sim/step_profile.hpp"
#include "boxpile/sim/thread_pool.hpp"
#include "boxpile/sim/solver/impulse.hpp"
#include "boxpile/sim/solver/wire.hpp"

namespace boxpile {

// The largest number of passes a loop may be given (keeps per-pass statistics fixed-size).
inline constexpr int kMaxSolverPasses = 64;

// How often each stage the methods share ran and how much work it did: a scene without an effect
// never pays for it. What a method alone does it counts itself (ContactMethod::diagnostics).
struct WorldCounters {
  std::uint64_t steps = 0;
  std::uint64_t broadphase_pairs = 0;     // pairs the broadphase passed on
  std::uint64_t narrowphase_calls = 0;    // box-box and box-plane tests run
  std::uint64_t pairs_found = 0;          // body pairs (and body-ground pairs) whose contacts were found
  std::uint64_t pairs_reused = 0;         // those copied from the last step instead (ContactReuse)
  std::uint64_t gravity_applications = 0;  // per body and step
  std::uint64_t damping_applications = 0;  // per body and step
  std::uint64_t gyroscopic_updates = 0;    // per body and step
  StepProfile profile;  // seconds per stage, when switched on (World::enable_profile)
};

// A collision event: an impulse at an approach faster than resting contact explains.
struct CollisionEvent {
  double time = 0.0;
  int body_a = 0;
  int body_b = 0;
  double impulse = 0.0;  // N s, summed over the pair's points in that step
  double approach_speed = 0.0;  // m/s, the fastest approaching point
};

struct StepContext {
  const Scene& scene;
  std::vector<RigidBody>& bodies;
  const RigidBody& ground;                  // a fixed body standing for the half-space
  const std::vector<BodyContact>& contacts;  // found at the start of this step
  // Per contact, 1 when it is the last step's contact at the same index, found at poses within
  // ContactReuse::kPoseTolerance of both bodies' present ones (what was derived from it holds).
  const std::vector<char>& same_as_last_step;
  const std::vector<WireJoint>& wires;
  double time = 0.0;  // s, at the step's start
  double dt = 0.0;    // s, this step's length (a penalty substep is a step of its own)
  WorldCounters& counters;
  std::vector<CollisionEvent>& events;
  ThreadPool& pool;  // the world's threads (solver.threads), for work that splits into independent parts
};

}  // namespace boxpile
