// The scene as an MJCF document for MuJoCo 2.2.2, and its loading through a virtual file system
// (no file on disk). Internal to boxpile::reference; docs/reference-engines.md has the mapping.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "boxpile/reference/mujoco/mujoco_settings.hpp"
#include "boxpile/sim/body.hpp"
#include "boxpile/sim/scene.hpp"

struct mjModel_;
struct mjData_;

namespace boxpile::reference_detail {

// Names in the document: body i is "b<i>", its box k the geom "b<i>_<k>", the ground "ground",
// a wire's joints "b<i>_slide" and "b<i>_ball", a free body's joint "b<i>_free".
std::string mujoco_body_name(int body);
std::string mujoco_geom_name(int body, int shape);
inline constexpr const char* kMujocoGround = "ground";

// The damping ratio of a spring-damper whose half oscillation keeps the fraction e of the
// approach speed: e = exp(-zeta pi / sqrt(1 - zeta^2)), so zeta = -ln e / sqrt(pi^2 + ln^2 e).
double damping_ratio_for_restitution(double e);

// The MJCF document of `scene`; `bodies` are make_bodies(scene) (boxpile's mass properties,
// given to MuJoCo explicitly so that every engine shares them).
std::string mujoco_mjcf(const Scene& scene, const std::vector<RigidBody>& bodies, const MujocoSettings& settings);

struct ModelDeleter {
  void operator()(mjModel_* m) const;
};
using ModelPtr = std::unique_ptr<mjModel_, ModelDeleter>;
struct DataDeleter {
  void operator()(mjData_* d) const;
};
using DataPtr = std::unique_ptr<mjData_, DataDeleter>;

// A vector MuJoCo keeps as three numbers (mjtNum is double in Debian's build).
inline Vec3 vec3(const double* p) { return {p[0], p[1], p[2]}; }

// Compiles an MJCF document held in memory; MujocoError with MuJoCo's message if it is refused.
ModelPtr load_mjcf(const std::string& xml);

}  // namespace boxpile::reference_detail
