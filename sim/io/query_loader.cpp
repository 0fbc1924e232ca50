#include "boxpile/sim/io/query_loader.hpp"

#include "boxpile/sim/io/json_input.hpp"

namespace boxpile {
namespace {

using json_input::JsonNode;

// {"half_extents": [..], "position": [..], "orientation": [w, x, y, z]}; orientation optional.
QueryBox read_query_box(const JsonNode& node) {
  node.expect_object({"half_extents", "position", "orientation"});
  QueryBox box;
  box.half_extents = json_input::read_half_extents(node.at("half_extents"), limits::kMinQueryHalfExtent);
  box.pose.position = json_input::read_vec3(node.at("position"));
  if (const auto q = node.find("orientation")) {
    box.pose.orientation = json_input::read_orientation(*q);
  }
  return box;
}

Contact read_answer_contact(const JsonNode& node) {
  node.expect_object({"position", "normal", "depth", "feature"});
  Contact c;
  c.position = json_input::read_vec3(node.at("position"));
  c.normal = json_input::read_vec3(node.at("normal"));
  c.depth = node.at("depth").number();
  c.feature.value = static_cast<std::uint32_t>(node.integer_or("feature", 0));
  return c;
}

Manifold read_answer(const JsonNode& node) {
  node.expect_object({"contacts"});
  const JsonNode contacts = node.at("contacts");
  const std::size_t n = contacts.array_size();
  if (n > static_cast<std::size_t>(kMaxManifoldPoints)) {
    contacts.fail("has " + std::to_string(n) + " contacts; a box pair has at most " +
                  std::to_string(kMaxManifoldPoints));
  }
  Manifold m;
  for (std::size_t i = 0; i < n; ++i) m.push_back(read_answer_contact(contacts.element(i)));
  return m;
}

// {"detector": {"contacts": [...]}, ...}: answers saved beside the query.
std::vector<RecordedAnswer> read_answers(const JsonNode& node) {
  if (!node.json().is_object()) node.fail("must be an object of detector names to answers");
  std::vector<RecordedAnswer> answers;
  for (const auto& [name, value] : node.json().items()) answers.push_back({name, read_answer(node.at(name))});
  return answers;
}

}  // namespace

Manifold parse_answer(const std::string& text, const std::string& source) {
  const nlohmann::json doc = json_input::parse(text, source);
  return read_answer(JsonNode(doc, source));
}

ContactQuery parse_query(const std::string& text, const std::string& source) {
  const nlohmann::json doc = json_input::parse(text, source);
  const JsonNode root(doc, source);
  // "name" and "note" document a fixture (what it is, why it exists); "answers" keeps contact
  // sets detectors gave for it.
  root.expect_object({"name", "note", "a", "b", "answers"});
  ContactQuery query;
  query.source = source;
  query.name = root.string_or("name", "");
  query.note = root.string_or("note", "");
  if (const auto answers = root.find("answers")) query.answers = read_answers(*answers);
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

ContactQuery load_query(const std::string& path, std::size_t max_bytes) {
  return parse_query(json_input::read_text_file(path, max_bytes), path);
}

}  // namespace boxpile
