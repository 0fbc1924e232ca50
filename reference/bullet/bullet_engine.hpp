// The scene as a Bullet 3.24 (double precision) world behind the Engine interface. Bullet's types
// stay in the .cpp file.
#pragma once

#include <memory>

#include "boxpile/reference/bullet/bullet_settings.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// Rigid bodies at their centre of mass, turned to the principal axes of inertia (Bullet stores a
// diagonal inertia), one btBoxShape per body or a btCompoundShape for several boxes, fixed bodies
// as static bodies, the ground as a btStaticPlaneShape; stepped with stepSimulation(dt, 0) and no
// sleeping. See docs/reference-engines.md for the mapping.
class BulletEngine final : public Engine {
 public:
  BulletEngine(const Scene& scene, const BulletSettings& settings = {});
  ~BulletEngine() override;
  BulletEngine(const BulletEngine&) = delete;
  BulletEngine& operator=(const BulletEngine&) = delete;

  std::string_view name() const override { return "bullet"; }
  void step() override;
  double time() const override;
  void body_states(std::vector<BodyState>& out) const override;
  void contacts(std::vector<BodyContact>& out) const override;

 private:
  struct World;
  std::unique_ptr<World> world_;
};

}  // namespace boxpile
