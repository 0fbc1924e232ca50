// Loads a contact query (`boxpile contacts QUERY.json`): box A against box B or against a plane,
// and a collider's answer to one (`boxpile conform`'s line protocol, docs/conform.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/math.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

struct QueryBox {
  Vec3 half_extents = Vec3::Constant(0.5);
  Pose pose;

  OrientedBox box() const { return OrientedBox::from(pose, half_extents); }
};

// A contact set some detector gave for the query, kept in the query file (`boxpile conform`
// saves each failing query with the collider's answer, and `boxpile contacts` shows it).
struct RecordedAnswer {
  std::string detector;
  Manifold contacts;
};

struct ContactQuery {
  std::string source;
  std::string name;  // optional, for a fixture or a saved failure
  std::string note;  // optional: why the query exists
  QueryBox a;
  std::optional<QueryBox> b;       // box-box when set
  std::optional<HalfSpace> plane;  // box-plane when set (exactly one of b, plane)
  std::vector<RecordedAnswer> answers;
};

ContactQuery load_query(const std::string& path, std::size_t max_bytes = limits::kDefaultMaxInputBytes);
ContactQuery parse_query(const std::string& text, const std::string& source);

// A collider's answer: {"contacts": [{"position": [x, y, z], "normal": [x, y, z], "depth": d}, ...]}
// with at most kMaxManifoldPoints contacts ("feature", a whole number, is optional). Normals are
// kept as given (not normalised): judging them is the point. InputError names `source` and the
// JSON path.
Manifold parse_answer(const std::string& text, const std::string& source);

}  // namespace boxpile
