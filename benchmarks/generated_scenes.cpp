#include "generated_scenes.hpp"

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

namespace boxpile::bench {
namespace {

// Gravity and friction on a ground plane at z = 0, the default material, at rest.
Scene resting_scene(std::string name, std::string note, double duration) {
  Scene s;
  s.name = std::move(name);
  s.note = std::move(note);
  s.ground = HalfSpace{Vec3::UnitZ(), 0.0};
  s.effects = Effects{.gravity = true, .friction = true, .restitution = false, .damping = false, .gyroscopic = false};
  s.time.duration = duration;
  return s;
}

BodyDesc block(std::string name, const Vec3& half, const Vec3& position, const Quat& q = Quat::Identity()) {
  BodyDesc b;
  b.name = std::move(name);
  b.mass = 1.0;
  b.boxes = {BoxShape{half, Vec3::Zero(), Quat::Identity()}};
  b.frame = {position, q};
  return b;
}

// Body names like "l2_0_3" (GCC 12 warns falsely about chained std::string additions).
template <typename... Ints>
std::string indexed_name(char prefix, Ints... indices) {
  std::string name(1, prefix);
  const char* sep = "";
  for (int i : {indices...}) {
    name.append(sep).append(std::to_string(i));
    sep = "_";
  }
  return name;
}

constexpr double kPyramidGap = 0.05;  // m between neighbours in a row: no side contacts at rest

// A uniform number in [lo, hi) from the generator's 32 bits: std::uniform_real_distribution's
// values are left to the library, and the benchmark's scenes must be the same everywhere.
double uniform(std::mt19937& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967296.0);
}

// A random rotation: a point drawn uniformly in the unit 4-ball (by rejection), normalised.
Quat random_rotation(std::mt19937& rng) {
  for (;;) {
    const Eigen::Vector4d q(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    const double n = q.norm();
    if (n > 0.1 && n <= 1.0) return Quat(q.x() / n, q.y() / n, q.z() / n, q.w() / n);
  }
}

}  // namespace

Scene square_pyramid(int base, double duration) {
  Scene s = resting_scene("pyramid_" + std::to_string(base),
                          "A square pyramid of base " + std::to_string(base) + " unit cubes.", duration);
  const double pitch = 1.0 + kPyramidGap;
  for (int level = 0; level < base; ++level) {
    const int n = base - level;
    const double first = -0.5 * (n - 1) * pitch;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        s.bodies.push_back(block(indexed_name('l', level, i, j),
                                 Vec3::Constant(0.5), Vec3(first + i * pitch, first + j * pitch, 0.5 + level)));
  }
  return s;
}

Scene jenga_tower(double duration) {
  Scene s = resting_scene("jenga", "18 crosswise layers of three 1.5 x 0.5 x 0.3 m blocks.", duration);
  const Vec3 half(0.75, 0.25, 0.15);
  const Quat across(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
  for (int layer = 0; layer < 18; ++layer) {
    const double z = half.z() * (2 * layer + 1);
    for (int k = 0; k < 3; ++k) {
      const double offset = (k - 1) * 2 * half.y();
      const std::string name = indexed_name('j', layer, k);
      if (layer % 2 == 0)
        s.bodies.push_back(block(name, half, Vec3(0.0, offset, z)));
      else
        s.bodies.push_back(block(name, half, Vec3(offset, 0.0, z), across));
    }
  }
  return s;
}

Scene rammed_cube(double duration) {
  Scene s = resting_scene("rammed_cube", "A 4 x 4 x 4 cube of 0.2 m boxes rammed by a 40 kg box at 6 m/s.", duration);
  constexpr int kSide = 4;
  constexpr double kHalf = 0.1;            // m
  constexpr double kPitch = 2 * kHalf + 1e-3;  // m: side by side 1 mm apart, stacked touching
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j)
      for (int k = 0; k < kSide; ++k)
        s.bodies.push_back(block(indexed_name('c', i, j, k), Vec3::Constant(kHalf),
                                 Vec3(i * kPitch + kHalf, (j - 0.5 * (kSide - 1)) * kPitch, kHalf * (2 * k + 1))));
  constexpr double kRamHalf = 0.2;  // m
  BodyDesc ram = block("ram", Vec3::Constant(kRamHalf), Vec3(-0.5, 0.0, kRamHalf + 0.01));
  ram.mass = 40.0;
  ram.velocity = Vec3(6.0, 0.0, 0.0);
  s.bodies.push_back(std::move(ram));
  return s;
}

Scene falling_heap(int count, int per_row, double duration) {
  Scene s = resting_scene("heap_" + std::to_string(count),
                          std::to_string(count) + " randomly sized and turned boxes falling in layers.", duration);
  constexpr double kPitch = 1.1;    // m, grid spacing and height between layers
  constexpr double kDensity = 500;  // kg/m^3
  std::mt19937 rng(static_cast<std::uint32_t>(count));
  for (int k = 0; k < count; ++k) {
    const int layer = k / (per_row * per_row), cell = k % (per_row * per_row);
    const Vec3 half(uniform(rng, 0.1, 0.3), uniform(rng, 0.1, 0.3), uniform(rng, 0.1, 0.3));
    const double first = -0.5 * (per_row - 1) * kPitch;
    BodyDesc b = block(indexed_name('h', k), half,
                       Vec3(first + (cell % per_row) * kPitch, first + (cell / per_row) * kPitch, 0.6 + layer * kPitch),
                       random_rotation(rng));
    b.mass = kDensity * 8.0 * half.prod();
    s.bodies.push_back(std::move(b));
  }
  return s;
}

}  // namespace boxpile::bench
