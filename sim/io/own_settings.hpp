// Our simulator's settings table: every key of a scene's `solver` and `collision` objects
// (SolverSettings, PenaltySettings, CollisionSettings in sim/scene.hpp and sim/collision/
// collide.hpp), declared once: the few every method reads here, each method's in its row of the
// registry (sim/solver/contact_method.hpp). The scene loader reads those objects through it,
// `--set own.KEY` and sweep grids name the same rows, `boxpile settings` and docs/scene-format.md
// list them. A row's key is the name on the command line and in grids; its scene_key says where a
// scene file gives it; its group is the contact method that reads it (a registry row's name;
// empty for every method).
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

// A boolean setting that is one member of one part of the scene (solver or collision).
template <auto Part, auto Member>
Setting<Scene> scene_flag(SettingInfo info) {
  return {std::move(info), [](Scene& s, const nlohmann::json& v) { (s.*Part).*Member = v.get<bool>(); },
          [](const Scene& s) { return nlohmann::json((s.*Part).*Member); }};
}

}  // namespace boxpile
