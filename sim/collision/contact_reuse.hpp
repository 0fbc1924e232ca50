// Contacts of bodies at rest, kept from one step to the next.
//
// A body at rest in a stack, a pyramid or a Jenga tower moves by rounding alone from step to step
// (a few ulps of its position and orientation), so its contacts with another body at rest come out
// of the narrow phase the same each step, to within that rounding. The world keeps each pair's
// contacts with the poses it found them at; while neither body has moved beyond kPoseTolerance
// from those poses and the pair's margin is the same, the pair's contacts are copied from the
// last step instead of found again. A contact that lands at the same index as last step's also
// tells the solver that what it derived from it (offsets, collision matrices) still holds.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

class ContactReuse {
 public:
  // How far (m, and in each quaternion coefficient) a body may move from the pose its contacts
  // were found at before they are found again: far above the rounding of a body at rest (1e-16
  // to 1e-15), far below anything a contact's depth or the penetration slop (1e-4 m) can tell.
  static constexpr double kPoseTolerance = 1e-12;

  // Sizes the storage for `bodies` bodies and about `contacts` contacts and `pairs` pairs a step;
  // `enabled` false finds every pair's contacts at every step.
  void reserve(std::size_t bodies, std::size_t contacts, std::size_t pairs, bool enabled);

  // Starts a step's contact search: compares each body's pose with the one its contacts were found
  // at (a body beyond the tolerance gets a new reference pose), and makes `contacts` (last step's
  // contact set) the set pairs are copied from; `contacts` is left empty for this step's.
  void begin(const std::vector<RigidBody>& bodies, std::vector<BodyContact>& contacts);

  // Appends the contacts of the pair (a, b) (b = kGround for the ground) at `margin` to `out`:
  // copied from last step when last step's search had the pair at about the same place, with both
  // bodies within the tolerance and the same margin, else found by `find` (which appends them).
  // Pairs must be asked in the order of the search.
  template <class Find>
  void pair(int a, int b, double margin, std::vector<BodyContact>& out, Find&& find);
  // Whether the pair (a, b), asked `place`-th in this step's search (counting from 0), will be
  // copied by pair(): what pair() decides, known ahead, so that the pairs it will not copy can be
  // found beforehand (on several threads).
  bool copies(int a, int b, double margin, std::size_t place) const {
    const Pair* last = enabled_ ? last_step_pair(a, b, place) : nullptr;
    return last != nullptr && last->stamp_a == stamp(a) && last->stamp_b == stamp(b) &&
           std::abs(last->margin - margin) <= kPoseTolerance;
  }

  // Per contact of this step's set: 1 when it is last step's contact at the same index, found at
  // poses within the tolerance of both bodies' present ones.
  const std::vector<char>& same_as_last_step() const { return same_; }
  // Pairs copied and pairs found in the last step.
  int reused_pairs() const { return reused_pairs_; }
  int found_pairs() const { return found_pairs_; }

 private:
  struct Pair {
    int a = 0, b = 0;
    std::uint32_t stamp_a = 0, stamp_b = 0;  // the bodies' pose stamps when the contacts were found
    double margin = 0.0;
    int first = 0, count = 0;  // its contacts in the set
  };
  std::uint32_t stamp(int body) const { return body == kGround ? 0 : stamp_[static_cast<std::size_t>(body)]; }
  // Last step's record of the pair (a, b), looked for at `place` in last step's search and then
  // within kSearchWindow places either side (a body that crossed another in the broadphase's order
  // moves the pairs after it by a few places); nullptr when it is not there.
  static constexpr std::size_t kSearchWindow = 16;
  const Pair* last_step_pair(int a, int b, std::size_t place) const {
    const std::size_t n = last_pairs_.size();
    auto is = [&](std::size_t k) { return k < n && last_pairs_[k].a == a && last_pairs_[k].b == b; };
    if (is(place)) return &last_pairs_[place];
    for (std::size_t d = 1; d <= kSearchWindow; ++d) {
      if (is(place + d)) return &last_pairs_[place + d];
      if (place >= d && is(place - d)) return &last_pairs_[place - d];
    }
    return nullptr;
  }

  std::vector<Vec3> ref_x_;
  std::vector<Quat> ref_q_;
  std::vector<std::uint32_t> stamp_;  // per body, bumped each time it takes a new reference pose
  std::vector<Pair> pairs_, last_pairs_;
  std::vector<BodyContact> last_contacts_;
  std::vector<char> same_;
  std::size_t cursor_ = 0;  // this step's pair count so far: the place in last step's search
  int reused_pairs_ = 0, found_pairs_ = 0;
  bool enabled_ = true;
};

template <class Find>
void ContactReuse::pair(int a, int b, double margin, std::vector<BodyContact>& out, Find&& find) {
  const int first = static_cast<int>(out.size());
  const Pair* last = enabled_ ? last_step_pair(a, b, cursor_) : nullptr;
  const bool same_pair = copies(a, b, margin, cursor_++);
  Pair p{a, b, stamp(a), stamp(b), margin, first, 0};
  if (same_pair) {
    const auto from = last_contacts_.begin() + last->first;
    out.insert(out.end(), from, from + last->count);
    p.margin = last->margin;  // still the margin the contacts were found at
    same_.insert(same_.end(), static_cast<std::size_t>(last->count), last->first == first ? 1 : 0);
    ++reused_pairs_;
  } else {
    find();
    same_.insert(same_.end(), out.size() - static_cast<std::size_t>(first), 0);
    ++found_pairs_;
  }
  p.count = static_cast<int>(out.size()) - first;
  pairs_.push_back(p);
}

}  // namespace boxpile
