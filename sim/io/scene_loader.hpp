// Loads a scene from JSON (format: docs/scene-format.md). Every problem is an InputError naming
// the file and the JSON path; nothing is half-loaded.
#pragma once

#include <cstddef>
#include <string>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// Caps on what a scene may ask for (sim/limits.hpp); the command line can raise them.
struct LoadLimits {
  std::size_t max_bodies = limits::kDefaultMaxBodies;
  std::size_t max_pairs = limits::kDefaultMaxPairs;            // overlapping pairs at the start
  std::size_t max_input_bytes = limits::kDefaultMaxInputBytes;  // of the file
};

// Reads and validates the scene file at `path`.
Scene load_scene(const std::string& path, const LoadLimits& caps = {});

// Parses and validates scene text; `source` names it in messages.
Scene parse_scene(const std::string& text, const std::string& source, const LoadLimits& caps = {});

}  // namespace boxpile
