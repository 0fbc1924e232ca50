// The penalty method's friction anchors: one per touching contact point, kept from step to step
// by the contact's identity (the two bodies, their shapes and the feature id), created where a
// contact begins and dropped when it ends (Box2D's and qu3e's matching of feature ids, applied to
// anchors instead of warm-start impulses). Two parallel faces in contact tie in the separating-
// axis test, and the reference face can pass from one box to the other between steps, renaming
// every point: a point whose id is new takes over the anchor of the same pair's point that lay
// within kAnchorMatchDistance of it on body A in the last step (as Bullet's persistent manifold
// matches points by distance).
#pragma once

#include <compare>
#include <cstdint>
#include <vector>

#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

struct AnchorKey {
  int a = 0;
  int b = 0;
  int shape_a = 0;
  int shape_b = 0;
  std::uint32_t feature = 0;

  static AnchorKey of(const BodyContact& c) {
    return {c.body_a, c.body_b, c.shape_a, c.shape_b, c.contact.feature.value};
  }
  friend auto operator<=>(const AnchorKey&, const AnchorKey&) = default;
};

// A renamed point is the same point if it lies this close to last step's, on body A: far below
// the spacing of a manifold's points on 0.1-1 m boxes, far above a step's motion of a resting
// point.
inline constexpr double kAnchorMatchDistance = 1e-3;  // m

struct FrictionAnchor {
  AnchorKey key;
  Vec3 on_a = Vec3::Zero();  // this step's contact point on body A, in its axes about its centre of mass
  // The friction spring's two ends: on A, the material point where the contact began (A's
  // axes), so that the spring measures how far A has moved over B even where the contact point
  // itself is a crossing of edges that stays put on B; and on B, below.
  Vec3 tie_a = Vec3::Zero();
  // Where the friction spring is tied: on body B, in its axes relative to its centre of mass
  // (in the world for the ground), so that the anchor moves with B.
  Vec3 on_b = Vec3::Zero();
  bool sliding = false;  // the spring left the static cone and has not come to rest since
};

class FrictionAnchors {
 public:
  void reserve(std::size_t n) {
    previous_.reserve(n);
    current_.reserve(n);
  }
  // Starts a step: the anchors of the last step become the ones to match.
  void begin_step();
  // The anchor of contact `key` at point `on_a` (A's axes) in this step: the last step's if the
  // contact touched then (by id, else by distance), else a new one at `on_b` (`created` says
  // which). Valid until the next call.
  FrictionAnchor& find_or_create(const AnchorKey& key, const Vec3& on_a, const Vec3& on_b, bool& created);
  // Ends a step: contacts that did not touch in it lose their anchors.
  void end_step();

  const std::vector<FrictionAnchor>& anchors() const { return previous_; }

 private:
  std::vector<FrictionAnchor> previous_;  // sorted by key
  std::vector<FrictionAnchor> current_;
};

}  // namespace boxpile
