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
// `batches` (the worker's, kept from step to step) and the contacts go in batches that share no
// moving body; with accumulated impulses they then update `velocities` (gathered from the compact
// bodies before and scattered back after by the caller), and the push-only impulses go in the
// batches' order (`order`: the worker's scratch).
void contact_loop(ImpulseStep& step, std::span<SolverContact> contacts, ContactBatches* batches = nullptr,
                  BatchVelocities* velocities = nullptr, std::vector<int>* order = nullptr);

}  // namespace boxpile
