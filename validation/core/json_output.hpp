// JSON forms of boxpile's own types, shared by every command that prints or writes results.
#pragma once

#include <nlohmann/json.hpp>

#include <vector>

#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/sim/math.hpp"
#include "boxpile/validation/core/output_safety.hpp"

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

// Writes `doc` into an output checked and staged before the run (validation/core/output_safety.hpp):
// whole or not at all. Throws OutputError naming the path.
void write_json_file(const nlohmann::json& doc, OutputFile& out);

}  // namespace boxpile
