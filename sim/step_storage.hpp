// How much per-step storage a world reserves when it is built, so that stepping allocates
// nothing (tests/test_allocations.cpp counts the allocations of 1,000 steps of pile_100). A
// scene that needs more grows its storage once, at the step that first needs it, and keeps it.
#pragma once

#include <cstddef>

namespace boxpile {

struct StepStorage {
  // Contact points per body: a box of a square pyramid rests on four and carries four, 12 points
  // per body on average (measured); a pile has about 4.
  static constexpr std::size_t kContactsPerBody = 16;
  // Broadphase pairs per body: each pair counts for two bodies; a pyramid's box has 8 neighbours.
  static constexpr std::size_t kPairsPerBody = 8;
  // Collision events recorded over a whole run, per body (pile_100 records 22 per body in 1,000
  // steps).
  static constexpr std::size_t kEventsPerBody = 64;

  std::size_t bodies = 0;
  std::size_t contacts() const { return kContactsPerBody * bodies; }
  std::size_t pairs() const { return kPairsPerBody * bodies; }
  std::size_t events() const { return kEventsPerBody * bodies; }
};

}  // namespace boxpile
