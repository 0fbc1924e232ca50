// The scene as an ODE 0.16 world behind the Engine interface. ODE's types stay in the .cpp file.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "boxpile/reference/ode/ode_settings.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// ODE's messages (warnings it carries on after), caught by the handler installed with
// dSetMessageHandler: counted since the process started, with the text of the last one.
struct OdeMessageLog {
  std::uint64_t count = 0;
  std::string last;
};
OdeMessageLog ode_messages();

// ODE reported an error or an internal assertion (dError, dDebug): instead of letting ODE abort
// the process, boxpile's handlers throw this. The engine that hit it cannot be used further. The
// scene loader's ranges (sim/limits.hpp) keep every accepted scene away from these; the command
// line reports one as bad input (exit 2).
class OdeError : public EngineRefused {
 public:
  using EngineRefused::EngineRefused;
};

// Bodies at their centre of mass with one box geom per shape (geom offsets for compounds),
// fixed bodies as static geoms, the ground as a plane geom, contacts as dContactApprox1 joints
// (mu a coefficient) rebuilt every step. See docs/reference-engines.md for the mapping.
class OdeEngine final : public Engine {
 public:
  OdeEngine(const Scene& scene, const OdeSettings& settings = {});
  ~OdeEngine() override;
  OdeEngine(const OdeEngine&) = delete;
  OdeEngine& operator=(const OdeEngine&) = delete;

  std::string_view name() const override { return "ode"; }
  void step() override;
  double time() const override;
  void body_states(std::vector<BodyState>& out) const override;
  void contacts(std::vector<BodyContact>& out) const override;

  // ODE messages caught since this engine was built.
  std::uint64_t messages() const override;
  std::string last_message() const override;

 private:
  struct World;
  void step_world();
  std::unique_ptr<World> world_;
};

}  // namespace boxpile
