#include "validation/cli/json_output.hpp"


namespace boxpile {

nlohmann::json to_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json to_json(const Quat& q) { return {q.w(), q.x(), q.y(), q.z()}; }

nlohmann::json to_json(const Contact& c) {
  return {{"position", to_json(c.position)},
          {"normal", to_json(c.normal)},
          {"depth", c.depth},
          {"feature", c.feature.value}};
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
