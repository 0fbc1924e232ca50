// Our detector as a collider (validation/contacts/detectors.hpp), for the judge's tests: built once per
// program, shared by the files that judge it.
#pragma once

#include "boxpile/validation/contacts/detectors.hpp"

namespace boxpile::test {

inline const Collider kOwn = detector_collider("own");

}  // namespace boxpile::test
