// The collision loop of the Guendelman-Bridson-Fedkiw step (sec. 5 of the paper).
#pragma once

#include <span>

#include "boxpile/sim/solver/impulse_step.hpp"

namespace boxpile {

// Collision loop: `collision_passes` sequential passes of Newton-Coulomb impulses with the
// scene's restitution over the active contacts of `contacts` (the step's set, or an island of
// it); after each pass, contacts that no longer approach are deactivated.
void collision_loop(ImpulseStep& step, std::span<SolverContact> contacts);
// After the collision loop: impulses at approach speeds faster than resting contact explains,
// over the step's whole set, reported as collision events.
void record_collision_events(ImpulseStep& step);

}  // namespace boxpile
