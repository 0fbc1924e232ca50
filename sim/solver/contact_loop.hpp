// The contact loop of the Guendelman-Bridson-Fedkiw step (sec. 6 of the paper).
#pragma once

#include <span>

#include "boxpile/sim/solver/contact_batches.hpp"
#include "boxpile/sim/solver/impulse_step.hpp"

namespace boxpile {

// Contact loop: `contact_passes` passes over `contacts` (the step's set, or an island of it),
// restitution ramped e_k = -1 + (k + 1) / passes (from -1 + 1/n up to 0), nothing removed. With
// accumulated_impulses a projected Gauss-Seidel over the phase's impulses; without, the lab
// text's push-only Newton-Coulomb impulses. Works on the compact bodies (step.resting), gathered
// before and scattered after by the caller. With solver.contact_batches the caller gives
// `batches` (the worker's, kept from step to step) and `velocities` (gathered from the compact
// bodies before and scattered back after): the accumulated impulses then go in batches of four
// contacts that share no moving body, where they fill enough lanes (ContactBatches::pays).
void contact_loop(ImpulseStep& step, std::span<SolverContact> contacts, ContactBatches* batches = nullptr,
                  BatchVelocities* velocities = nullptr);

}  // namespace boxpile
