#include "boxpile/validation/detectors.hpp"

#include <string>

namespace boxpile {

const DetectorInfo& find_detector(std::string_view name) {
  for (const DetectorInfo& d : detectors()) {
    if (d.name == name) return d;
  }
  std::string known;
  for (const DetectorInfo& d : detectors()) known += (known.empty() ? "" : ", ") + d.name;
  throw UnknownDetector("unknown detector \"" + std::string(name) + "\" (known: " + known + ")");
}

Collider detector_collider(std::string_view name, const DetectOptions& options) {
  const DetectorInfo& d = find_detector(name);
  return [&d, options](const ContactQuery& q) { return d.detect(q, options); };
}

}  // namespace boxpile
