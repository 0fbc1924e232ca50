// Scenes of boxes in the usual arrangements, made in code: `boxpile scene KIND` writes them as
// scene files (docs/scene-format.md). Every arrangement is built so that no two boxes overlap and
// its heights are known exactly (each kind's comment says them).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace boxpile {

// A size that the kind does not take, or out of its range; what() names the flag.
class SceneGeneratorError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct SceneSizes {
  int base = 0;      // pyramid: boxes in the bottom row (default 5)
  int width = 0;     // wall: bricks per row (default 6)
  int height = 0;    // wall: rows (default 4); tower: boxes (default 10)
  int nx = 0, ny = 0, layers = 0;  // grid: boxes along x and y, and layers (defaults 5, 5, 1)
  int count = 0;     // heap: boxes (default 20); dominoes: dominoes (default 10)
  double size = 1.0;  // m: a box's edge (a brick's height and depth, a domino's height)
  double gap = -1.0;  // m between neighbours in a row or grid; negative: the kind's default
  double mass = 1.0;  // kg of each box
  std::uint64_t seed = 1;  // heap: the random orientations and places
};

// The kinds, in the order help lists them, and what each builds.
struct SceneKind {
  std::string_view name;
  std::string_view description;
  std::vector<std::string_view> sizes;  // the SceneSizes flags it takes ("base", "height", ...)
};
const std::vector<SceneKind>& scene_kinds();

// The scene file of `kind` with `sizes` (zero counts take the kind's defaults): every box on or
// above the ground z = 0, none overlapping. SceneGeneratorError for an unknown kind or a size out
// of range.
//   pyramid   rows of base, base-1, ..., 1 cubes, each resting on the two below: base(base+1)/2
//             boxes, the top face at base * size.
//   wall      height rows of width bricks (2 size x size x size), odd rows shifted by half a
//             brick: width * height bricks, the top at height * size.
//   tower     height cubes stacked: the top at height * size.
//   grid      nx x ny x layers cubes `gap` apart (default size), the lowest layer on the ground:
//             the top at layers * size + (layers - 1) * gap.
//   heap      count cubes at random orientations, each in its own cell of a column of cells
//             (3 x 3 across) of edge sqrt(3) size + gap, dropped onto the ground.
//   dominoes  count dominoes (0.2 x 0.5 x 1 of size) standing 0.6 size apart along x, the first
//             tipped toward the others: the tops at size.
nlohmann::json generate_scene(std::string_view kind, const SceneSizes& sizes);

}  // namespace boxpile
