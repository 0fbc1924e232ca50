// Loads a contact query (`boxpile contacts QUERY.json`): box A against box B or against a plane.
#pragma once

#include <optional>
#include <string>

#include "sim/io/input_error.hpp"
#include "sim/math.hpp"
#include "sim/scene.hpp"

namespace boxpile {

struct QueryBox {
  Vec3 half_extents = Vec3::Constant(0.5);
  Pose pose;
};

struct ContactQuery {
  std::string source;
  QueryBox a;
  std::optional<QueryBox> b;       // box-box when set
  std::optional<HalfSpace> plane;  // box-plane when set (exactly one of b, plane)
};

ContactQuery load_query(const std::string& path);
ContactQuery parse_query(const std::string& text, const std::string& source);

}  // namespace boxpile
