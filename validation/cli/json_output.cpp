#include "validation/cli/json_output.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

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

void write_json_file(const nlohmann::json& doc, const std::string& path) {
  write_text_file(doc.dump(2) + '\n', path);
}

void write_text_file(const std::string& text, const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path temp = target.parent_path() / (".tmp-" + target.filename().string());
  {
    std::ofstream os(temp);
    if (!os) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
    os << text;
    if (!os.flush()) {
      std::error_code ignored;
      fs::remove(temp, ignored);
      throw std::runtime_error(path + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw std::runtime_error(path + ": cannot write: " + ec.message());
  }
}

}  // namespace boxpile
