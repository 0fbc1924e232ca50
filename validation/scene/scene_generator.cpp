#include "boxpile/validation/scene/scene_generator.hpp"

#include <cmath>
#include <random>

#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/limits.hpp"

namespace boxpile {
namespace {

using nlohmann::json;

// The most boxes a generated scene may have: what a scene file may load by default.
constexpr long kMaxGeneratedBoxes = static_cast<long>(limits::kDefaultMaxBodies);
constexpr double kMinSize = 0.01, kMaxSize = 200.0;  // m

json generated_box(const std::string& name, double mass, double hx, double hy, double hz, double x, double y, double z) {
  return {{"name", name}, {"mass", mass}, {"half_extents", {hx, hy, hz}}, {"position", {x, y, z}}};
}

int count_in_range(int given, int fallback, const char* flag, int largest) {
  const int n = given == 0 ? fallback : given;
  if (n < 1 || n > largest) {
    throw SceneGeneratorError(std::string("--") + flag + ": must be a whole number in [1, " + std::to_string(largest) +
                              "], got " + std::to_string(n));
  }
  return n;
}

// The most of one count such that `per` of them stay within kMaxGeneratedBoxes.
int most_boxes(long per = 1) { return static_cast<int>(kMaxGeneratedBoxes / per); }

}  // namespace

const std::vector<SceneKind>& scene_kinds() {
  static const std::vector<SceneKind> kinds = {
      {"pyramid", "rows of --base, --base - 1, ..., 1 cubes, each resting on the two below", {"base", "gap"}},
      {"wall", "--height rows of --width bricks (2:1:1), odd rows shifted by half a brick", {"width", "height", "gap"}},
      {"tower", "--height cubes stacked", {"height"}},
      {"grid", "--nx by --ny by --layers cubes --gap apart, the lowest layer on the ground", {"nx", "ny", "layers", "gap"}},
      {"heap", "--count cubes at random orientations (--seed) dropped onto the ground", {"count", "gap", "seed"}},
      {"dominoes", "--count dominoes in a row along x, the first tipped toward the others", {"count"}},
  };
  return kinds;
}

json generate_scene(std::string_view kind, const SceneSizes& z) {
  // A domino is a tenth of the size thick: it stays above the loader's least half extent.
  if (!(z.size >= kMinSize && z.size <= kMaxSize)) {
    throw SceneGeneratorError("--size: must be in [0.01, 200] m, got " + json_input::format_number(z.size));
  }
  if (!(z.mass >= limits::kMinMass && z.mass <= limits::kMaxMass)) {
    throw SceneGeneratorError("--mass: must be in [1e-6, 1e6] kg, got " + json_input::format_number(z.mass));
  }
  if (!(z.gap <= 10 * z.size) || !std::isfinite(z.gap)) {
    throw SceneGeneratorError("--gap: must be in [0, 10 --size] m, got " + json_input::format_number(z.gap));
  }
  const double s = z.size, h = s / 2;
  json bodies = json::array();
  std::string name(kind), note;
  if (kind == "pyramid") {
    const int base = count_in_range(z.base, 5, "base", 400);
    const double gap = z.gap < 0 ? 0.0 : z.gap, pitch = s + gap;
    for (int row = 0; row < base; ++row) {
      const int n = base - row;
      for (int k = 0; k < n; ++k) {
        bodies.push_back(generated_box("r" + std::to_string(row) + "_" + std::to_string(k), z.mass, h, h, h,
                             (k - (n - 1) / 2.0) * pitch, 0.0, h + row * s));
      }
    }
    name += "_" + std::to_string(base);
    note = "A pyramid of " + std::to_string(bodies.size()) + " cubes (base " + std::to_string(base) +
           "), each resting on the two below; its top at " + json_input::format_number(base * s) + " m.";
  } else if (kind == "wall") {
    const int width = count_in_range(z.width, 6, "width", 1000), height = count_in_range(z.height, 4, "height", most_boxes(width));
    const double gap = z.gap < 0 ? 0.0 : z.gap, pitch = 2 * s + gap;
    for (int row = 0; row < height; ++row) {
      const double shift = row % 2 == 0 ? 0.0 : pitch / 2;
      for (int k = 0; k < width; ++k) {
        bodies.push_back(generated_box("r" + std::to_string(row) + "_" + std::to_string(k), z.mass, s, h, h,
                             (k - (width - 1) / 2.0) * pitch + shift, 0.0, h + row * s));
      }
    }
    name += "_" + std::to_string(width) + "x" + std::to_string(height);
    note = "A wall of " + std::to_string(height) + " rows of " + std::to_string(width) +
           " bricks in running bond; its top at " + json_input::format_number(height * s) + " m.";
  } else if (kind == "tower") {
    const int height = count_in_range(z.height, 10, "height", most_boxes());
    for (int k = 0; k < height; ++k) bodies.push_back(generated_box("b" + std::to_string(k), z.mass, h, h, h, 0.0, 0.0, h + k * s));
    name += "_" + std::to_string(height);
    note = "A tower of " + std::to_string(height) + " cubes; its top at " + json_input::format_number(height * s) + " m.";
  } else if (kind == "grid") {
    const int nx = count_in_range(z.nx, 5, "nx", 1000), ny = count_in_range(z.ny, 5, "ny", most_boxes(nx)),
              layers = count_in_range(z.layers, 1, "layers", most_boxes(static_cast<long>(nx) * ny));
    const double gap = z.gap < 0 ? s : z.gap, pitch = s + gap;
    for (int l = 0; l < layers; ++l) {
      for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
          bodies.push_back(generated_box("g" + std::to_string(l) + "_" + std::to_string(j) + "_" + std::to_string(i), z.mass,
                               h, h, h, (i - (nx - 1) / 2.0) * pitch, (j - (ny - 1) / 2.0) * pitch, h + l * pitch));
        }
      }
    }
    name += "_" + std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(layers);
    note = "A grid of " + std::to_string(bodies.size()) + " cubes " + json_input::format_number(gap) +
           " m apart; the upper layers fall onto the lowest.";
  } else if (kind == "heap") {
    const int count = count_in_range(z.count, 20, "count", most_boxes());
    // A cube of edge s at any orientation lies within a sphere of diameter sqrt(3) s: cells of
    // that edge (plus the gap) hold one cube each without overlap.
    const double gap = z.gap < 0 ? 0.05 * s : z.gap, cell = std::sqrt(3.0) * s + gap;
    std::mt19937_64 random(z.seed);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> jitter(-gap / 2, gap / 2);
    for (int k = 0; k < count; ++k) {
      double q[4];
      double norm = 0;
      for (double& c : q) {
        c = normal(random);
        norm += c * c;
      }
      norm = std::sqrt(norm);
      const int i = k % 3 - 1, j = (k / 3) % 3 - 1, layer = k / 9;
      json b = generated_box("h" + std::to_string(k), z.mass, h, h, h, i * cell + jitter(random), j * cell + jitter(random),
                   cell / 2 + layer * cell + jitter(random));
      b["orientation"] = {q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm};
      bodies.push_back(std::move(b));
    }
    name += "_" + std::to_string(count);
    note = "A heap of " + std::to_string(count) + " cubes at random orientations (seed " + std::to_string(z.seed) +
           ") dropped in a column of 3 x 3 cells.";
  } else if (kind == "dominoes") {
    const int count = count_in_range(z.count, 10, "count", most_boxes());
    const double pitch = 0.6 * s;
    for (int k = 0; k < count; ++k) {
      json b = generated_box("d" + std::to_string(k), z.mass, 0.1 * s, 0.25 * s, h, k * pitch, 0.0, h);
      // The first is tipped toward the others: it spins about its bottom edge, about y.
      if (k == 0) b["angular_velocity"] = {0.0, 2.0 / std::sqrt(s), 0.0};
      bodies.push_back(std::move(b));
    }
    name += "_" + std::to_string(count);
    note = "A row of " + std::to_string(count) + " dominoes " + json_input::format_number(pitch) +
           " m apart; the first is tipped toward the others.";
  } else {
    std::string known;
    for (const SceneKind& k : scene_kinds()) known += (known.empty() ? "" : ", ") + std::string(k.name);
    throw SceneGeneratorError("unknown scene kind \"" + std::string(kind) + "\"; known: " + known);
  }
  return {{"name", name},
          {"note", note + " Made by `boxpile scene`."},
          {"gravity", {0, 0, -9.81}},
          {"ground", {{"normal", {0, 0, 1}}, {"offset", 0}}},
          {"material", {{"friction", 0.5}, {"restitution", 0.0}}},
          {"effects", {"gravity", "friction"}},
          {"bodies", std::move(bodies)},
          {"time", {{"dt", 1.0 / 240}, {"duration", 5.0}}}};
}

}  // namespace boxpile
