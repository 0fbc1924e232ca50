// Random box pairs for judging a box-box collider, by regime: the generator of the conformance
// suite and of `boxpile conform`. Seeded; the same seed gives the same pairs on every machine
// that uses the same standard library.
#pragma once

#include <optional>
#include <random>
#include <span>
#include <string_view>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

struct BoxPair {
  OrientedBox a, b;
};

// Uniformly random rotations (Shoemake's method through a normalised 4D Gaussian).
Quat random_rotation(std::mt19937_64& rng);
Vec3 random_unit(std::mt19937_64& rng);

inline OrientedBox make_box(const Vec3& half, const Vec3& center, const Quat& q = Quat::Identity()) {
  return OrientedBox::from({center, q}, half);
}

// A random pair of boxes that mostly touch or overlap: extents in [0.1, 1] m, random
// orientations, A's centre in a random direction from B's, at 0.4 to 1.05 times the sum of their
// radii along that direction (so about one pair in five is apart). The conformance suite's pairs.
BoxPair random_touching_pair(std::mt19937_64& rng);

// The kinds of pairs `boxpile conform` and check_collider() draw, each stressing one part of a
// collider:
enum class Regime {
  Mixed,     // random_touching_pair: overlapping, touching and apart, any orientation
  Touching,  // grazing: the true depth within 0.2% of the smaller box's size of zero, either side
  Deep,      // A's centre at 0.05 to 0.5 of the reach: deep overlap
  EdgeEdge,  // two edges crossing (each box turned 45 degrees onto an edge), shallow
  Parallel,  // face on face with parallel faces (turned about the normal only): clipping
  Scaled,    // mixed pairs at millimetre (0.001-0.01 m) or decametre (10-100 m) size
  Far,       // A's centre at 1.5 to 3 times the reach: always apart
};
std::span<const Regime> all_regimes();
std::string_view regime_name(Regime r);
std::optional<Regime> regime_from_name(std::string_view name);

BoxPair random_pair(Regime regime, std::mt19937_64& rng);

}  // namespace boxpile
