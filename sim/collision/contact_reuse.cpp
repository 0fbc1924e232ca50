#include "boxpile/sim/collision/contact_reuse.hpp"

#include <utility>

namespace boxpile {

void ContactReuse::reserve(std::size_t bodies, std::size_t contacts, std::size_t pairs, bool enabled) {
  enabled_ = enabled;
  ref_x_.assign(bodies, Vec3::Zero());
  ref_q_.assign(bodies, Quat::Identity());
  stamp_.assign(bodies, 0);
  pairs_.reserve(pairs);
  last_pairs_.reserve(pairs);
  last_contacts_.reserve(contacts);
  same_.reserve(contacts);
}

void ContactReuse::begin(const std::vector<RigidBody>& bodies, std::vector<BodyContact>& contacts) {
  // (Off, no pair is copied and no reference pose is read.)
  for (std::size_t i = 0; enabled_ && i < bodies.size(); ++i) {
    const RigidBody& b = bodies[i];
    // (Stamp 0: no reference pose yet, before the first step.)
    const bool within = stamp_[i] != 0 && (b.x - ref_x_[i]).cwiseAbs().maxCoeff() <= kPoseTolerance &&
                        (b.q.coeffs() - ref_q_[i].coeffs()).cwiseAbs().maxCoeff() <= kPoseTolerance;
    if (!within) {
      ref_x_[i] = b.x;
      ref_q_[i] = b.q;
      ++stamp_[i];
    }
  }
  std::swap(last_contacts_, contacts);
  contacts.clear();
  std::swap(last_pairs_, pairs_);
  pairs_.clear();
  same_.clear();
  cursor_ = 0;
  reused_pairs_ = found_pairs_ = 0;
}

}  // namespace boxpile
