#include "boxpile/sim/solver/friction_anchors.hpp"

#include <algorithm>

namespace boxpile {

void FrictionAnchors::begin_step() { current_.clear(); }

FrictionAnchor& FrictionAnchors::find_or_create(const AnchorKey& key, const Vec3& on_a, const Vec3& on_b,
                                                bool& created) {
  auto by_key = [](const FrictionAnchor& anchor, const AnchorKey& k) { return anchor.key < k; };
  const auto it = std::lower_bound(previous_.begin(), previous_.end(), key, by_key);
  const FrictionAnchor* match = it != previous_.end() && it->key == key ? &*it : nullptr;
  if (!match) {
    // The same pair's anchors are contiguous (sorted by bodies first): the nearest within reach.
    const AnchorKey pair_start{key.a, key.b, 0, 0, 0};
    double nearest = kAnchorMatchDistance;
    for (auto p = std::lower_bound(previous_.begin(), previous_.end(), pair_start, by_key);
         p != previous_.end() && p->key.a == key.a && p->key.b == key.b; ++p) {
      const double d = (p->on_a - on_a).norm();
      if (d < nearest) {
        nearest = d;
        match = &*p;
      }
    }
  }
  created = match == nullptr;
  current_.push_back(created ? FrictionAnchor{key, on_a, on_a, on_b, false} : *match);
  current_.back().key = key;
  current_.back().on_a = on_a;
  return current_.back();
}

void FrictionAnchors::end_step() {
  std::sort(current_.begin(), current_.end(),
            [](const FrictionAnchor& x, const FrictionAnchor& y) { return x.key < y.key; });
  std::swap(previous_, current_);
}

}  // namespace boxpile
