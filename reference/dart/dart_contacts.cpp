#include "boxpile/reference/dart/dart_contacts.hpp"

#include <algorithm>
#include <iostream>
#include <streambuf>

#include <dart/collision/CollisionGroup.hpp>
#include <dart/collision/CollisionObject.hpp>
#include <dart/collision/CollisionResult.hpp>
#include <dart/collision/dart/DARTCollisionDetector.hpp>
#include <dart/collision/fcl/FCLCollisionDetector.hpp>
#include <dart/common/Memory.hpp>
#include <dart/collision/ode/OdeCollisionDetector.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/PlaneShape.hpp>
#include <dart/dynamics/SimpleFrame.hpp>

#include "boxpile/reference/dart/dart_convention.hpp"
#include "boxpile/reference/dart/dart_support.hpp"

namespace boxpile {

using namespace reference_detail;

namespace reference_detail {

namespace {

// Sends std::cerr nowhere while it lives.
class MutedCerr {
 public:
  MutedCerr() : saved_(std::cerr.rdbuf(&null_)) {}
  ~MutedCerr() { std::cerr.rdbuf(saved_); }
  MutedCerr(const MutedCerr&) = delete;
  MutedCerr& operator=(const MutedCerr&) = delete;

 private:
  struct NullBuffer : std::streambuf {
    int overflow(int c) override { return c; }
  } null_;
  std::streambuf* saved_;
};

}  // namespace

std::shared_ptr<dart::collision::CollisionDetector> make_dart_detector(DartDetector detector) {
  using dart::collision::FCLCollisionDetector;
  switch (detector) {
    case DartDetector::Dart:
      return dart::collision::DARTCollisionDetector::create();
    case DartDetector::Fcl:
      return FCLCollisionDetector::create();  // DART's default: primitives as meshes
    case DartDetector::FclPrimitive: {
      auto fcl = FCLCollisionDetector::create();
      const MutedCerr muted;
      fcl->setPrimitiveShapeType(FCLCollisionDetector::PRIMITIVE);
      return fcl;
    }
    case DartDetector::Ode:
      return dart::collision::OdeCollisionDetector::create();
  }
  return nullptr;
}

}  // namespace reference_detail

namespace {

// One detector of each kind per thread, built on first use (FCL's and ODE's set up state).
dart::collision::CollisionDetector& detector_of(DartDetector d) {
  thread_local std::shared_ptr<dart::collision::CollisionDetector> detectors[4];
  auto& slot = detectors[static_cast<int>(d)];
  if (!slot) slot = make_dart_detector(d);
  return *slot;
}

// A frame holds fixed-size Eigen members that need 16-byte alignment: DART's aligned allocation.
// libdart's SimpleFrame constructor places its virtual base ShapeFrame (alignof 16) at an address
// 8 mod 16 inside the object (DART's own layout, in the library's code, whatever the allocation):
// UBSan's alignment check flags every member call through it. The functions that call members of
// a SimpleFrame are exempt from that one check (BOXPILE_DART_FRAME_CALLS); ASan and every other
// UBSan check stay on, and ShapeNodes (the engine's) do not trip it.
#define BOXPILE_DART_FRAME_CALLS __attribute__((no_sanitize("alignment")))

std::shared_ptr<dart::dynamics::SimpleFrame> world_frame() {
  return dart::common::make_aligned_shared<dart::dynamics::SimpleFrame>(dart::dynamics::Frame::World());
}

BOXPILE_DART_FRAME_CALLS std::shared_ptr<dart::dynamics::SimpleFrame> box_frame(const OrientedBox& box) {
  auto frame = world_frame();
  frame->setShape(std::make_shared<dart::dynamics::BoxShape>(2.0 * box.half));
  frame->setRelativeTransform(dart_transform(box));
  return frame;
}

// The raw contacts between frame a and frame b, each with its normal turned to point from b
// toward a (DART's points toward the contact's first object).
struct RawContact {
  Vec3 point, normal;
  double depth;
};

BOXPILE_DART_FRAME_CALLS std::vector<RawContact> collide(DartDetector d, const dart::dynamics::SimpleFrame& a,
                                const dart::dynamics::SimpleFrame& b) {
  auto& detector = detector_of(d);
  auto group = detector.createCollisionGroup(&a, &b);
  dart::collision::CollisionOption option;  // DART's defaults: contacts on, up to 1000
  dart::collision::CollisionResult result;
  group->collide(option, &result);
  std::vector<RawContact> raw;
  for (const dart::collision::Contact& c : result.getContacts()) {
    const bool a_first = c.collisionObject1->getShapeFrame() == &a;
    raw.push_back({c.point, a_first ? Vec3(c.normal) : Vec3(-c.normal), c.penetrationDepth});
  }
  return raw;
}

// The deepest kMaxManifoldPoints of `all` (FCL's meshes can give more).
Manifold deepest(std::vector<Contact> all) {
  std::stable_sort(all.begin(), all.end(), [](const Contact& x, const Contact& y) { return x.depth > y.depth; });
  Manifold m;
  for (const Contact& c : all) {
    if (m.size() == kMaxManifoldPoints) break;
    m.push_back(c);
  }
  return m;
}

}  // namespace

Manifold dart_box_box(DartDetector detector, const OrientedBox& a, const OrientedBox& b) {
  const auto fa = box_frame(a), fb = box_frame(b);
  std::vector<Contact> all;
  for (const RawContact& r : collide(detector, *fa, *fb)) {
    all.push_back(dart_box_box_contact(detector, a, b, r.point, r.normal, r.depth));
  }
  return deepest(all);
}

BOXPILE_DART_FRAME_CALLS Manifold dart_box_plane(DartDetector detector, const OrientedBox& a, const HalfSpace& plane) {
  const auto fa = box_frame(a);
  std::vector<Contact> all;
  if (dart_detector_takes_planes(detector)) {
    auto fp = world_frame();
    fp->setShape(std::make_shared<dart::dynamics::PlaneShape>(plane.normal, plane.offset));
    for (const RawContact& r : collide(detector, *fa, *fp)) all.push_back(dart_box_plane_contact(r.point, r.normal, r.depth));
  } else {
    const OrientedBox ground = dart_ground_box(plane, a.center);
    const auto fg = box_frame(ground);
    for (const RawContact& r : collide(detector, *fa, *fg)) {
      Contact c = dart_box_box_contact(detector, a, ground, r.point, r.normal, r.depth);
      c.feature = kind_only(FeatureKind::Plane);
      all.push_back(c);
    }
  }
  return deepest(all);
}

}  // namespace boxpile
