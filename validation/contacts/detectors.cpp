#include "boxpile/validation/contacts/detectors.hpp"

#include <algorithm>
#include <string>

namespace boxpile {

const DetectorInfo& find_detector(std::string_view name) {
  for (const DetectorInfo& d : detectors()) {
    if (d.name == name) return d;
  }
  std::string known, hyphens(name);
  for (const DetectorInfo& d : detectors()) known += (known.empty() ? "" : ", ") + d.name;
  std::replace(hyphens.begin(), hyphens.end(), '_', '-');
  for (const DetectorInfo& d : detectors()) {
    // The names of engines and detectors are spelt with hyphens (bullet_multipoint was once).
    if (hyphens != name && d.name == hyphens) {
      throw UnknownDetector("unknown detector \"" + std::string(name) + "\": did you mean \"" + hyphens +
                            "\"? (names are spelt with hyphens; known: " + known + ")");
    }
  }
  throw UnknownDetector("unknown detector \"" + std::string(name) + "\" (known: " + known + ")");
}

Collider detector_collider(std::string_view name, const DetectOptions& options) {
  const DetectorInfo& d = find_detector(name);
  return [&d, options](const ContactQuery& q) { return d.detect(q, options); };
}

}  // namespace boxpile
