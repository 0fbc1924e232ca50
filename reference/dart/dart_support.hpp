// What the DART engine and the DART query detectors share: building a detector by kind, and
// conversions between DART's Eigen transforms and our poses. Internal to boxpile::reference (it
// includes DART's headers; only dart_engine.cpp and dart_contacts.cpp include it).
#pragma once

#include <memory>

#include <dart/collision/CollisionDetector.hpp>

#include "boxpile/reference/dart/dart_settings.hpp"
#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile::reference_detail {

// A new detector of the kind. FCL's primitive mode prints a warning to std::cerr whenever it is
// chosen; this one choice is made with std::cerr muted (the warning says what docs say).
std::shared_ptr<dart::collision::CollisionDetector> make_dart_detector(DartDetector detector);

inline Eigen::Isometry3d dart_transform(const Vec3& position, const Mat3& rotation) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation;
  t.translation() = position;
  return t;
}

inline Eigen::Isometry3d dart_transform(const OrientedBox& box) { return dart_transform(box.center, box.axes); }

}  // namespace boxpile::reference_detail
