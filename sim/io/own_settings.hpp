// Our simulator's settings table: every key of a scene's `solver` and `collision` objects
// (SolverSettings, PenaltySettings, CollisionSettings in sim/scene.hpp and sim/collision/
// collide.hpp), declared once. The scene loader reads those objects through it, `--set own.KEY`
// and sweep grids name the same rows, `boxpile settings` and docs/scene-format.md list them.
// A row's key is the name on the command line and in grids; its scene_key says where a scene
// file gives it; its group is the contact method that reads it ("impulse", "penalty"; empty for
// both).
#pragma once

#include <optional>
#include <string_view>

#include "boxpile/sim/io/setting.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// The most penalty steps one scene step may be split into: beyond it a run of seconds takes
// hours, and a step that short is better asked for with a smaller dt.
inline constexpr int kMaxPenaltySubsteps = 100000;
// Penalty springs: softer than this holds nothing up; stiffer needs steps far below any dt the
// scene accepts (N/m, and N s/m for the damper).
inline constexpr double kSoftestSpring = 1e-6;
inline constexpr double kStiffestSpring = 1e12;

// The settings our engine reads from a Scene (a row sets and reads the scene's solver and
// collision fields; the scene's bodies are left alone).
const SettingsTable<Scene>& own_settings_table();

// The contact method whose group a setting belongs to; none for the settings of both.
std::optional<ContactSolver> setting_group_method(const SettingInfo& setting);
// "impulse" or "penalty".
std::string_view method_name(ContactSolver method);

}  // namespace boxpile
