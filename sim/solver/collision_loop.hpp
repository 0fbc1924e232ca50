// The collision loop of the Guendelman-Bridson-Fedkiw step (sec. 5 of the paper).
#pragma once

#include "boxpile/sim/solver/impulse_step.hpp"

namespace boxpile {

// Collision loop: `collision_passes` sequential passes of Newton-Coulomb impulses with the
// scene's restitution over the active contacts; after each pass, contacts that no longer
// approach are deactivated. Impulses at approach speeds faster than resting contact explains
// are reported as collision events.
void collision_loop(ImpulseStep& step);

}  // namespace boxpile
