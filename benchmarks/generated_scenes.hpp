// Scenes the benchmarks build in code instead of loading from fixtures/: square pyramids of any
// base (up to 9,455 boxes, too large to keep as files) and the Jenga tower, whose geometry is
// that of the hard catalogue's pyramids and Jenga tower; and scenes in motion: a cube of boxes
// rammed by a heavy box, and heaps of randomly sized and turned boxes falling in layers.
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

// A 4 x 4 x 4 cube of 0.2 m boxes (1 kg; stacked, 1 mm apart side by side) on the ground, rammed by a
// 0.4 m box of 40 kg at 6 m/s along x, its lowest face 1 cm above the ground.
Scene rammed_cube(double duration);

// `count` boxes of half extents 0.1-0.3 m (density 500 kg/m^3, as pile_100), randomly turned,
// in layers of `per_row` x `per_row` on a 1.1 m grid (no two can touch: the largest box's
// bounding sphere has radius 0.52 m), one layer every 1.1 m from 0.6 m up, falling onto the
// ground into a heap. Seeded: the same scene at every run and on every machine.
Scene falling_heap(int count, int per_row, double duration);

}  // namespace boxpile::bench
