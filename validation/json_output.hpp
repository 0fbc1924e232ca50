// JSON forms of boxpile's own types, shared by every command that prints or writes results.
#pragma once

#include <nlohmann/json.hpp>

#include <vector>

#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/sim/math.hpp"

namespace boxpile {

nlohmann::json to_json(const Vec3& v);
nlohmann::json to_json(const Quat& q);  // [w, x, y, z]
nlohmann::json to_json(const Contact& c);
// {"contacts": [...]}: an answer of the line protocol (docs/conform.md).
nlohmann::json answer_json(const Manifold& m);
// A query as query files hold it and the line protocol sends it: name and note when set, a, b
// (a box or {"plane": ...}), and the recorded answers when there are any. Numbers read back as
// the same doubles.
nlohmann::json query_json(const ContactQuery& q);
// Body states as every output file writes them: name, position, orientation, velocity,
// angular_velocity.
nlohmann::json bodies_json(const std::vector<BodyState>& states);

// Writes `doc` to `path` atomically: a temporary file beside it, then a rename, so a failure
// never leaves a half-written file. Throws std::runtime_error naming the path.
void write_json_file(const nlohmann::json& doc, const std::string& path);
// The same for any text.
void write_text_file(const std::string& text, const std::string& path);

}  // namespace boxpile
