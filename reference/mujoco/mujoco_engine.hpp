// The scene as a MuJoCo 2.2.2 model behind the Engine interface. MuJoCo's types stay in the .cpp
// files of reference/mujoco/.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "boxpile/reference/mujoco/mujoco_messages.hpp"
#include "boxpile/reference/mujoco/mujoco_settings.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// One MuJoCo body per scene body in the scene's body frame (boxpile's mass properties given
// explicitly), a free joint (or, on a wire, a slide and a ball joint; none for a fixed body), a
// box geom per box, the ground as a plane geom; compiled from an MJCF document generated in
// memory and stepped with mj_step. See docs/reference-engines.md for the mapping.
class MujocoEngine final : public Engine {
 public:
  // MujocoError when MuJoCo refuses the model, or when the scene asks for what these settings
  // cannot do (the gyroscopic effect off under an integrator other than Euler).
  MujocoEngine(const Scene& scene, const MujocoSettings& settings = {});
  ~MujocoEngine() override;
  MujocoEngine(const MujocoEngine&) = delete;
  MujocoEngine& operator=(const MujocoEngine&) = delete;

  std::string_view name() const override { return "mujoco"; }
  // MujocoError when MuJoCo reports an error or a warning that leaves the run wrong (a bad
  // number in qpos, qvel or qacc, after which MuJoCo resets the state; a full contact or
  // constraint list).
  void step() override;
  double time() const override;
  void body_states(std::vector<BodyState>& out) const override;
  void contacts(std::vector<BodyContact>& out) const override;

  // MuJoCo warnings caught since this engine was built.
  std::uint64_t messages() const override;
  std::string last_message() const override;

 private:
  struct World;
  std::unique_ptr<World> world_;
};

}  // namespace boxpile
