// Every contact detector by name, one row each: ours, ODE's, Bullet's (and Bullet with its
// multipoint box-plane option), DART's and FCL's (through DART). `boxpile contacts`, `contacts --serve` and `boxpile conform`
// iterate over this table; an outside collider joins them as a Collider (check_collider.hpp).
#pragma once

#include <span>
#include <stdexcept>
#include <string_view>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/validation/judge/check_collider.hpp"

namespace boxpile {

// Settings of our detector (the references have none): its box-box settings (reduction to four
// points, margin) and the margin of box-plane contacts, m.
struct DetectOptions {
  CollisionSettings own;
  double plane_margin = 0.0;
};

struct DetectorInfo {
  std::string_view name;
  std::string_view description;
  bool box_plane_only;  // differs from another row on box-plane queries only
  Manifold (*box_box)(const OrientedBox& a, const OrientedBox& b, const DetectOptions& options);
  Manifold (*box_plane)(const OrientedBox& a, const HalfSpace& plane, const DetectOptions& options);

  // The query's boxes (or box and plane) through box_box or box_plane.
  Manifold detect(const ContactQuery& query, const DetectOptions& options) const;
};

// The detector our engine uses, against which the others are compared.
inline constexpr std::string_view kOwnDetector = "own";

// The registered detectors, in the order help texts list them.
std::span<const DetectorInfo> detectors();

// A detector name that is not registered; what() lists the registered ones.
class UnknownDetector : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};
const DetectorInfo& find_detector(std::string_view name);

// A registered detector as a Collider.
Collider detector_collider(std::string_view name, const DetectOptions& options = {});

}  // namespace boxpile
