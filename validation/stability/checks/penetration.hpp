// The penetration check's limit, for what else scales with it (stability --tune's slops).
#pragma once

#include "boxpile/validation/stability/checks/check.hpp"

namespace boxpile {

// The scene's penetration limit as a fraction of its smallest box edge (checks.penetration,
// 0.01 when the scene does not give it).
double penetration_fraction(const Scene& scene);

}  // namespace boxpile
