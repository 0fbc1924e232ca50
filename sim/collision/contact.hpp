// Contact types shared by every detector (ours, and the ODE and Bullet adapters).
//
// Convention (the same for all engines, so results compare):
//   position  the midpoint between the two surfaces,
//   normal    unit vector from body B toward body A (moving A by depth along it separates them),
//   depth     > 0 when penetrating,
//   feature   an id that stays the same while the same features touch.
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cstdint>

#include "boxpile/sim/math.hpp"

namespace boxpile {

// Which pair of features produced a contact point.
enum class FeatureKind : std::uint8_t {
  FaceA = 0,     // reference face on A, point from B's incident face
  FaceB = 1,     // reference face on B, point from A's incident face
  EdgeEdge = 2,  // an edge of A against an edge of B
  Plane = 3,     // a vertex of A below the plane B
};

// A feature id packs (kind, feature on A, feature on B, sub-feature) into 32 bits:
//   faces are numbered 0..5 as 2*axis + (negative side ? 1 : 0),
//   edges 0..11 as 4*axis + corner, with corner bit 0/1 the signs along the other two axes,
//   vertices 0..7 with bit k set when the vertex lies on the positive side of axis k,
//   sub-feature of a clipped face point: 0..3 an incident-face vertex; 4 + 4*e + p the crossing of
//   incident edge e with reference side plane p; 20 + 4*q + p the crossing of side planes q and p
//   on the incident face (under a corner of the reference face).
struct FeatureId {
  std::uint32_t value = 0;

  static constexpr FeatureId make(FeatureKind kind, int on_a, int on_b, int sub) {
    return {static_cast<std::uint32_t>(kind) << 24 | static_cast<std::uint32_t>(on_a & 0xff) << 16 |
            static_cast<std::uint32_t>(on_b & 0xff) << 8 | static_cast<std::uint32_t>(sub & 0xff)};
  }
  // This id with its sub-feature (0 here) set to `sub`.
  constexpr FeatureId with_sub(int sub) const { return {value | static_cast<std::uint32_t>(sub & 0xff)}; }
  constexpr FeatureKind kind() const { return static_cast<FeatureKind>(value >> 24); }
  constexpr int on_a() const { return static_cast<int>(value >> 16 & 0xff); }
  constexpr int on_b() const { return static_cast<int>(value >> 8 & 0xff); }
  constexpr int sub() const { return static_cast<int>(value & 0xff); }
  friend constexpr bool operator==(FeatureId, FeatureId) = default;
};

struct Contact {
  Vec3 position = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double depth = 0.0;
  FeatureId feature;
};

// A box-box face contact clips a quadrilateral by four planes: at most 8 points. A box-plane
// contact has at most 8 vertices below the plane.
inline constexpr int kMaxManifoldPoints = 8;

// The contact points of one pair of boxes, in fixed storage (no allocation in a step).
class Manifold {
 public:
  int size() const { return count_; }
  bool empty() const { return count_ == 0; }
  void clear() { count_ = 0; }
  // Keeps the first n points (n <= size()).
  void truncate(int n) {
    assert(n >= 0 && n <= count_);
    count_ = n;
  }
  void push_back(const Contact& c) {
    assert(count_ < kMaxManifoldPoints);
    points_[(count_++)] = c;
  }
  const Contact& operator[](int i) const { return points_[i]; }
  Contact& operator[](int i) { return points_[i]; }
  const Contact* begin() const { return points_.data(); }
  const Contact* end() const { return points_.data() + count_; }
  Contact* begin() { return points_.data(); }
  Contact* end() { return points_.data() + count_; }
  // The point of greatest depth (the manifold must not be empty).
  const Contact& deepest() const {
    assert(count_ > 0);
    return *std::max_element(begin(), end(), [](const Contact& x, const Contact& y) { return x.depth < y.depth; });
  }

 private:
  std::array<Contact, kMaxManifoldPoints> points_{};
  int count_ = 0;
};

}  // namespace boxpile
