// The scene as a DART 6.12 world behind the Engine interface. DART's types stay in the .cpp file.
#pragma once

#include <memory>

#include "boxpile/reference/dart/dart_settings.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// One skeleton per body: a FreeJoint and one body node at the centre of mass with a box shape
// node per box (inertia from our mass properties); fixed bodies and the ground as immobile
// skeletons on a WeldJoint; a body on a wire as a chain (prismatic carriage, ball joint at the
// anchor). The contact detector and LCP solver come from DartSettings. See
// docs/reference-engines.md ("DART 6.12") for the mapping.
class DartEngine final : public Engine {
 public:
  DartEngine(const Scene& scene, const DartSettings& settings = {});
  ~DartEngine() override;
  DartEngine(const DartEngine&) = delete;
  DartEngine& operator=(const DartEngine&) = delete;

  std::string_view name() const override { return "dart"; }
  void step() override;
  double time() const override;
  void body_states(std::vector<BodyState>& out) const override;
  void contacts(std::vector<BodyContact>& out) const override;

 private:
  struct World;
  std::unique_ptr<World> world_;
};

}  // namespace boxpile
