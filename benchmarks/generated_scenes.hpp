// Scenes the benchmarks build in code instead of loading from fixtures/: square pyramids of any
// base (up to 2,870 boxes, too large to keep as files) and the Jenga tower. Their geometry is
// that of the hard catalogue's pyramids and Jenga tower.
#pragma once

#include "boxpile/sim/scene.hpp"

namespace boxpile::bench {

// The number of boxes in a square pyramid of base n: 1^2 + 2^2 + ... + n^2.
constexpr int square_pyramid_boxes(int base) { return base * (base + 1) * (2 * base + 1) / 6; }

// A square pyramid of unit cubes (1 kg), `base` boxes along each side of the bottom level,
// 5 cm apart in a row; each level is shifted by half a pitch, so each box stands on the corners
// of four below it. On the ground, at rest, gravity and friction (mu 0.5), dt 1/240 s.
Scene square_pyramid(int base, double duration);

// A Jenga-like tower: 18 layers of three 1.5 x 0.5 x 0.3 m blocks (1 kg), side by side, each
// layer crosswise to the one below (54 blocks). At rest on the ground, dt 1/240 s.
Scene jenga_tower(double duration);

}  // namespace boxpile::bench
