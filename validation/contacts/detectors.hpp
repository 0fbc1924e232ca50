// Every contact detector by name: the detectors of the registry's rows (reference/registry.hpp:
// ours, ODE's, Bullet's and Bullet with its multipoint box-plane option today). `boxpile
// contacts`, `contacts --serve` and `boxpile conform` iterate over them; an outside collider
// joins them as a Collider (check_collider.hpp).
#pragma once

#include <stdexcept>
#include <string_view>

#include "boxpile/reference/detector.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/conform/judge/check_collider.hpp"

namespace boxpile {

// The detector our engine uses, against which the others are compared.
inline constexpr std::string_view kOwnDetector = "own";

// A detector name that is not registered; what() lists the registered ones.
class UnknownDetector : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};
const DetectorInfo& find_detector(std::string_view name);

// A registered detector as a Collider.
Collider detector_collider(std::string_view name, const DetectOptions& options = {});

}  // namespace boxpile
