// Every engine that can run a scene, by name: the one place the CLI and the tests build engines.
#pragma once

#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "boxpile/reference/settings.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// An engine name that is unknown, or known but not yet available; what() says which and lists
// the engines that can be used.
class UnknownEngine : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Every engine name, available or not, in the order help texts list them: the engines linked
// in, then those run over the protocol (validation/process_engines.hpp). A span stays valid
// until an engine is added (--engine-cmd).
std::span<const std::string_view> engine_names();
// The names make_engine() can build.
std::span<const std::string_view> available_engine_names();
// The engines linked into boxpile (own, own-impulse, own-penalty, ode, bullet).
std::span<const std::string_view> linked_engine_names();

// Throws UnknownEngine unless make_engine() can build `name` (to check a list before any run).
void check_engine_name(std::string_view name);

// The engine `name` built from `scene` (the reference engines take `settings`; an engine over
// the protocol runs at its own defaults); UnknownEngine for a name that is not available.
std::unique_ptr<Engine> make_engine(std::string_view name, const Scene& scene,
                                    const ReferenceSettings& settings = {});

}  // namespace boxpile
