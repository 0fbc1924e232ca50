// JSON forms of boxpile's own types, shared by every command that prints or writes results.
#pragma once

#include <nlohmann/json.hpp>

#include <vector>

#include "sim/collision/contact.hpp"
#include "sim/engine.hpp"
#include "sim/math.hpp"

namespace boxpile {

nlohmann::json to_json(const Vec3& v);
nlohmann::json to_json(const Quat& q);  // [w, x, y, z]
nlohmann::json to_json(const Contact& c);
// Body states as every output file writes them: name, position, orientation, velocity,
// angular_velocity.
nlohmann::json bodies_json(const std::vector<BodyState>& states);

// Writes `doc` to `path` atomically: a temporary file beside it, then a rename, so a failure
// never leaves a half-written file. Throws std::runtime_error naming the path.
void write_json_file(const nlohmann::json& doc, const std::string& path);
// The same for any text.
void write_text_file(const std::string& text, const std::string& path);

}  // namespace boxpile
