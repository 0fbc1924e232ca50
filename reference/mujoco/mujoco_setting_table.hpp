// MuJoCo's settings as rows of the engine settings table (validation/engine_settings.hpp): each
// writes one field of ReferenceSettings::mujoco. Built into boxpile::validation, which owns
// EngineSetting; the fields and defaults are mujoco_settings.hpp's.
#pragma once

#include <span>

#include "boxpile/validation/engine_settings.hpp"

namespace boxpile {

std::span<const EngineSetting> mujoco_setting_table();

}  // namespace boxpile
