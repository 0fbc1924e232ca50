// JSON forms of boxpile's own types, shared by every command that prints or writes results.
#pragma once

#include <nlohmann/json.hpp>

#include "sim/collision/contact.hpp"
#include "sim/math.hpp"

namespace boxpile {

nlohmann::json to_json(const Vec3& v);
nlohmann::json to_json(const Quat& q);  // [w, x, y, z]
nlohmann::json to_json(const Contact& c);

// Writes `doc` to `path` atomically: a temporary file beside it, then a rename, so a failure
// never leaves a half-written file. Throws std::runtime_error naming the path.
void write_json_file(const nlohmann::json& doc, const std::string& path);

}  // namespace boxpile
