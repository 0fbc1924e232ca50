#include "boxpile/validation/replay/replay_page.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include "boxpile/validation/core/json_output.hpp"

namespace boxpile {
namespace replay_assets {
extern const std::string_view kPage;
extern const std::string_view kViewer;
}  // namespace replay_assets

namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ThreeJsMissing("cannot read " + path.string() + " (install the Debian package libjs-three, or set BOXPILE_THREE_DIR)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Text placed inside <script>: a "</" could close the element early; "<\/" means the same in
// JavaScript strings and in JSON.
std::string script_safe(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out.push_back(text[i]);
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out.push_back('\\');
  }
  return out;
}

// Replaces the first `marker` at or after `from` and returns where the inserted text ends, so that
// the next marker is searched for after it (never inside inserted text).
std::size_t replace_marker(std::string& page, std::size_t from, std::string_view marker, const std::string& text) {
  const std::size_t at = page.find(marker, from);
  if (at == std::string::npos) throw std::logic_error("replay page template lacks " + std::string(marker));
  page.replace(at, marker.size(), text);
  return at + text.size();
}

}  // namespace

ThreeJs load_three_js() {
  const char* env = std::getenv("BOXPILE_THREE_DIR");
  const fs::path dir = env && *env ? fs::path(env) : fs::path(BOXPILE_THREE_DIR);
  return {read_file(dir / "three.min.js"), read_file(dir / "examples" / "js" / "controls" / "OrbitControls.js")};
}

std::string replay_html(const nlohmann::json& data, const ThreeJs& three) {
  std::string page(replay_assets::kPage);
  std::size_t at = replace_marker(page, 0, "/*@THREE@*/", script_safe(three.three));
  at = replace_marker(page, at, "/*@ORBIT@*/", script_safe(three.orbit_controls));
  at = replace_marker(page, at, "/*@DATA@*/", script_safe(data.dump()));
  replace_marker(page, at, "/*@VIEWER@*/", script_safe(replay_assets::kViewer));
  return page;
}

void write_replay_page(const nlohmann::json& data, const ThreeJs& three, OutputFile& out) {
  out.commit(replay_html(data, three));
}

}  // namespace boxpile
