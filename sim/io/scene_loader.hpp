// Loads a scene from JSON (format: docs/scene-format.md). Every problem is an InputError naming
// the file and the JSON path; nothing is half-loaded.
#pragma once

#include <string>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// Reads and validates the scene file at `path`.
Scene load_scene(const std::string& path);

// Parses and validates scene text; `source` names it in messages.
Scene parse_scene(const std::string& text, const std::string& source);

}  // namespace boxpile
