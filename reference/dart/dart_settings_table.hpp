// DART's settings as rows of the settings vocabulary (validation/engine_settings.hpp): what
// `--set`, sweep grids and `boxpile settings` accept for the engine "dart". Part of
// boxpile::validation (it applies values to an EngineConfig); no DART header.
#pragma once

#include <span>

#include "boxpile/validation/engine_settings.hpp"

namespace boxpile {

std::span<const EngineSetting> dart_engine_settings();

}  // namespace boxpile
