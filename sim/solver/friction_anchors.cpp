#include "sim/solver/friction_anchors.hpp"

#include <algorithm>

namespace boxpile {

void FrictionAnchors::begin_step() { current_.clear(); }

FrictionAnchor& FrictionAnchors::find_or_create(const AnchorKey& key, const Vec3& on_b, bool& created) {
  auto by_key = [](const FrictionAnchor& anchor, const AnchorKey& k) { return anchor.key < k; };
  const auto it = std::lower_bound(previous_.begin(), previous_.end(), key, by_key);
  created = it == previous_.end() || it->key != key;
  current_.push_back(created ? FrictionAnchor{key, on_b, false} : *it);
  return current_.back();
}

void FrictionAnchors::end_step() {
  std::sort(current_.begin(), current_.end(),
            [](const FrictionAnchor& x, const FrictionAnchor& y) { return x.key < y.key; });
  std::swap(previous_, current_);
}

}  // namespace boxpile
