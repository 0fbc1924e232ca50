#include "sim/io/query_loader.hpp"

#include "sim/io/json_input.hpp"

namespace boxpile {
namespace {

using json_input::JsonNode;

// {"half_extents": [..], "position": [..], "orientation": [w, x, y, z]}; orientation optional.
QueryBox read_query_box(const JsonNode& node) {
  node.expect_object({"half_extents", "position", "orientation"});
  QueryBox box;
  box.half_extents = json_input::read_half_extents(node.at("half_extents"));
  box.pose.position = json_input::read_vec3(node.at("position"));
  if (const auto q = node.find("orientation")) {
    box.pose.orientation = json_input::read_orientation(*q);
  }
  return box;
}

}  // namespace

ContactQuery parse_query(const std::string& text, const std::string& source) {
  const nlohmann::json doc = json_input::parse(text, source);
  const JsonNode root(doc, source);
  // "name" and "note" document a fixture (what it is, why it exists); the query ignores them.
  root.expect_object({"name", "note", "a", "b"});
  root.string_or("name", "");
  root.string_or("note", "");

  ContactQuery query;
  query.source = source;
  query.a = read_query_box(root.at("a"));
  const JsonNode b = root.at("b");
  if (b.has("plane")) {
    b.expect_object({"plane"});
    query.plane = json_input::read_half_space(b.at("plane"));
  } else {
    query.b = read_query_box(b);
  }
  return query;
}

ContactQuery load_query(const std::string& path) {
  return parse_query(json_input::read_text_file(path), path);
}

}  // namespace boxpile
