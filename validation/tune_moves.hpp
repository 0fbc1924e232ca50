// The engines' own knobs that `boxpile stability --tune` tries, engine by engine, cheapest first:
// the settings a user of that engine would reach for when a scene fails (ODE's exact LCP stepper,
// Bullet's continuous collision, MuJoCo's stiffer contacts and no-slip passes, DART's iterative
// LCP, Jolt's sharp edges, Rapier's stiffer contacts and continuous collision). Each move is a
// set of the engine's settings (by the names of `boxpile settings`), some scaled with the scene
// (a length from its smallest box, a time from its step). docs/stability.md lists them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/scene.hpp"

namespace boxpile {

struct TuneMove {
  std::string label;  // "stepper world": what the tables and the terminal show
  std::string why;    // one line: what it changes in the engine
  // The settings it sets, for this scene run at time step `dt`.
  nlohmann::json settings;
  // Cheaper than the defaults (DART's PGS against its Dantzig LCP): tried on a passing cell too,
  // where it can only be kept if it still passes at less cost.
  bool cheaper = false;
  // The ladder's solver passes still apply with this move (false for ODE's dWorldStep, which
  // has no passes: the ladder then halves the time step alone).
  bool ladder_passes = true;
};

// The moves of `engine` for `scene` at time step `dt`, cheapest first ({} for an engine with
// none: our own, whose search is the time step alone).
std::vector<TuneMove> tune_moves(std::string_view engine, const Scene& scene, double dt);

// The engines that have moves (for the test that every move's keys are in the engine's table).
std::vector<std::string> engines_with_tune_moves();

}  // namespace boxpile
