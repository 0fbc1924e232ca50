#include "boxpile/validation/core/json_output.hpp"

namespace boxpile {

nlohmann::json to_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json to_json(const Quat& q) { return {q.w(), q.x(), q.y(), q.z()}; }

nlohmann::json to_json(const Contact& c) {
  return {{"position", to_json(c.position)},
          {"normal", to_json(c.normal)},
          {"depth", c.depth},
          {"feature", c.feature.value}};
}

nlohmann::json answer_json(const Manifold& m) {
  nlohmann::json contacts = nlohmann::json::array();
  for (const Contact& c : m) contacts.push_back(to_json(c));
  return {{"contacts", contacts}};
}

namespace {
nlohmann::json query_box_json(const QueryBox& b) {
  return {{"half_extents", to_json(b.half_extents)},
          {"position", to_json(b.pose.position)},
          {"orientation", to_json(b.pose.orientation)}};
}
}  // namespace

nlohmann::json query_json(const ContactQuery& q) {
  nlohmann::json doc = nlohmann::json::object();
  if (!q.name.empty()) doc["name"] = q.name;
  if (!q.note.empty()) doc["note"] = q.note;
  doc["a"] = query_box_json(q.a);
  if (q.b) {
    doc["b"] = query_box_json(*q.b);
  } else {
    doc["b"] = {{"plane", {{"normal", to_json(q.plane->normal)}, {"offset", q.plane->offset}}}};
  }
  if (!q.answers.empty()) {
    nlohmann::json answers = nlohmann::json::object();
    for (const RecordedAnswer& r : q.answers) answers[r.detector] = answer_json(r.contacts);
    doc["answers"] = answers;
  }
  return doc;
}

nlohmann::json bodies_json(const std::vector<BodyState>& states) {
  nlohmann::json bodies = nlohmann::json::array();
  for (const BodyState& s : states) {
    bodies.push_back({{"name", s.name},
                      {"position", to_json(s.position)},
                      {"orientation", to_json(s.orientation)},
                      {"velocity", to_json(s.velocity)},
                      {"angular_velocity", to_json(s.angular_velocity)}});
  }
  return bodies;
}

void write_json_file(const nlohmann::json& doc, OutputFile& out) { out.commit(doc.dump(2) + "\n"); }

}  // namespace boxpile
