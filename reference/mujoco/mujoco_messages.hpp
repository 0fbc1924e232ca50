// MuJoCo's error and warning handlers, routed: an error (mju_error, which by default prints and
// exits the process) becomes a MujocoError exception naming the engine; a warning is counted with
// its text. Internal to boxpile::reference.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "boxpile/sim/engine.hpp"

namespace boxpile {

// MuJoCo reported an error (a bad model, a full arena, an internal check), or a run reached a
// state MuJoCo would silently reset (a non-finite qacc): the engine that hit it cannot be used
// further. The command line reports it as an engine failure naming "mujoco".
class MujocoError : public EngineRefused {
 public:
  using EngineRefused::EngineRefused;
};

// MuJoCo's warnings (mju_warning) caught since the process started, with the last text.
struct MujocoMessageLog {
  std::uint64_t count = 0;
  std::string last;
};
MujocoMessageLog mujoco_messages();

namespace reference_detail {
// Installs the handlers once per process (MuJoCo's are global function pointers).
void ensure_mujoco_handlers();
}  // namespace reference_detail

}  // namespace boxpile
