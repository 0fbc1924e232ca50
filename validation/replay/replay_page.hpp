// The replay page: one self-contained HTML file that shows recordings of a scene in a browser,
// offline (three.js, the viewer and the data are all inside it). docs/viewer.md shows it.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "boxpile/validation/core/output_safety.hpp"

namespace boxpile {

// three.js cannot be found or read (the Debian package libjs-three is missing).
class ThreeJsMissing : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The two classic scripts of three.js the page inlines.
struct ThreeJs {
  std::string three;           // three.min.js
  std::string orbit_controls;  // examples/js/controls/OrbitControls.js
};

// Reads three.js from $BOXPILE_THREE_DIR when set, else from where libjs-three installs it
// (found at build time); ThreeJsMissing names the files tried.
ThreeJs load_three_js();

// The page for `data` (validation/replay/replay_data.hpp).
std::string replay_html(const nlohmann::json& data, const ThreeJs& three);

// Writes the page into `out`, checked and staged before the work (validation/core/output_safety.hpp).
void write_replay_page(const nlohmann::json& data, const ThreeJs& three, OutputFile& out);

}  // namespace boxpile
