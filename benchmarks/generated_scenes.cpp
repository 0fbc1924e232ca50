#include "generated_scenes.hpp"

#include <cmath>
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

}  // namespace boxpile::bench
