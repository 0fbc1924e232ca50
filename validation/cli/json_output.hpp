// JSON forms of boxpile's own types, shared by every command that prints or writes results.
#pragma once

#include <nlohmann/json.hpp>

#include <vector>

#include "sim/collision/contact.hpp"
#include "sim/engine.hpp"
#include "sim/math.hpp"
#include "validation/output_safety.hpp"

namespace boxpile {

nlohmann::json to_json(const Vec3& v);
nlohmann::json to_json(const Quat& q);  // [w, x, y, z]
nlohmann::json to_json(const Contact& c);
// Body states as every output file writes them: name, position, orientation, velocity,
// angular_velocity.
nlohmann::json bodies_json(const std::vector<BodyState>& states);

// Writes `doc` into an output checked and staged before the run (validation/output_safety.hpp):
// whole or not at all. Throws OutputError naming the path.
void write_json_file(const nlohmann::json& doc, OutputFile& out);

}  // namespace boxpile
