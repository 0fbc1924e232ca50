// Islands: the step's contacts split into sets that share no moving body. Two contacts are in one
// island when a chain of contacts between moving bodies joins them (the ground and fixed bodies
// join nothing: nothing they are given moves them). No impulse of one island reaches a body of
// another, so each island's loops run on their own, in any order or at the same time on several
// threads, and give the same result as if the others were not there. The contact set is ordered
// island by island (each island keeping the search's order), so an island is one range of it.
#pragma once

#include <algorithm>
#include <numeric>
#include <span>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/solver/body_groups.hpp"

namespace boxpile {

class Islands {
 public:
  void reserve(std::size_t bodies, std::size_t contacts) {
    groups_.reserve(bodies, contacts);
    search_order_.reserve(contacts);
    moving_.reserve(contacts);
    order_.reserve(contacts);
    start_.reserve(contacts + 1);
    by_size_.reserve(contacts);
  }

  // Sorts the contact set into islands: order() then lists the contacts' indices island by island.
  void find(const std::vector<BodyContact>& contacts, const std::vector<RigidBody>& bodies) {
    search_order_.resize(contacts.size());
    std::iota(search_order_.begin(), search_order_.end(), 0);
    // Each contact's moving bodies found once, into a compact array that the sort's three sweeps
    // read (each would otherwise read the contact and both bodies' flags again).
    moving_.resize(contacts.size());
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const BodyContact& c = contacts[k];
      const bool a_moves = !bodies[c.body_a].fixed;
      const bool b_moves = c.body_b != kGround && !bodies[c.body_b].fixed;
      moving_[k] = MovingBodies::of(c.body_a, c.body_b, a_moves, b_moves);
    }
    auto moving = [&](int k) { return moving_[static_cast<std::size_t>(k)]; };
    groups_.sort(std::span<const int>(search_order_), bodies.size(), moving, order_);
    start_.assign(1, 0);
    for (int i = 0; i < groups_.count(); ++i)
      start_.push_back(start_.back() + static_cast<int>(groups_.group(order_, i).size()));
    // The largest first, so that a pool's threads share the rest while one takes it.
    by_size_.resize(static_cast<std::size_t>(count()));
    std::iota(by_size_.begin(), by_size_.end(), 0);
    // (std::sort with the island's number deciding ties: std::stable_sort would allocate its buffer.)
    std::sort(by_size_.begin(), by_size_.end(), [&](int a, int b) {
      const int size_a = end(a) - begin(a), size_b = end(b) - begin(b);
      return size_a > size_b || (size_a == size_b && a < b);
    });
  }

  // The search's index of each contact, island by island.
  const std::vector<int>& order() const { return order_; }
  int count() const { return static_cast<int>(start_.size()) - 1; }
  // Island i as a range of positions in order(): [begin(i), end(i)).
  int begin(int i) const { return start_[static_cast<std::size_t>(i)]; }
  int end(int i) const { return start_[static_cast<std::size_t>(i) + 1]; }
  // The islands from the most contacts to the fewest (the order of a parallel loop over them;
  // the results do not depend on it).
  const std::vector<int>& by_size() const { return by_size_; }

 private:
  BodyGroups groups_;
  std::vector<int> search_order_;  // 0, 1, ..., the contacts as the search found them
  std::vector<MovingBodies> moving_;  // per contact, its moving bodies
  std::vector<int> order_;
  std::vector<int> start_;
  std::vector<int> by_size_;
};

}  // namespace boxpile
