// A contact detector: a function from two boxes (or a box and a plane) to a contact set in our
// convention. Each engine's registry row lists the detectors it brings (reference/registry.hpp);
// `boxpile contacts`, `contacts --serve`, `boxpile conform`, compare's contact checks and the
// conformance suite iterate over them (validation/contacts/detectors.hpp).
#pragma once

#include <functional>
#include <string>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/io/query_loader.hpp"

namespace boxpile {

// Settings of our detector (the references have none): its box-box settings (reduction to four
// points, margin) and the margin of box-plane contacts, m.
struct DetectOptions {
  CollisionSettings own;
  double plane_margin = 0.0;
};

struct DetectorInfo {
  std::string name;
  std::string description;
  bool box_plane_only = false;  // differs from another row on box-plane queries only
  std::function<Manifold(const OrientedBox& a, const OrientedBox& b, const DetectOptions& options)> box_box;
  std::function<Manifold(const OrientedBox& a, const HalfSpace& plane, const DetectOptions& options)> box_plane;

  // The query's boxes (or box and plane) through box_box or box_plane.
  Manifold detect(const ContactQuery& query, const DetectOptions& options) const;
};

}  // namespace boxpile
