// libFuzzer target: the contact query (`boxpile contacts`): the query loader, then every
// registered detector (validation/contacts/detectors.hpp: ours, ODE's, Bullet's and any added later) on
// what it accepts. What must hold: parse_query throws InputError or returns a query every detector
// answers without crashing or reaching an ODE error, with finite positions and depths and unit
// normals.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "boxpile/reference/ode/ode_engine.hpp"
#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/validation/contacts/detectors.hpp"

namespace {

using namespace boxpile;

// A normal is unit to rounding: far looser than the 1e-15 of a normalised double vector.
constexpr double kUnitTolerance = 1e-9;

void check(std::string_view detector, const Manifold& m) {
  for (const Contact& c : m) {
    const bool ok = c.position.allFinite() && std::isfinite(c.depth) &&
                    std::abs(c.normal.norm() - 1.0) < kUnitTolerance;
    if (!ok) {
      std::fprintf(stderr, "bad contact from %.*s: position (%g %g %g) normal (%g %g %g) depth %g\n",
                   static_cast<int>(detector.size()), detector.data(), c.position.x(), c.position.y(),
                   c.position.z(), c.normal.x(), c.normal.y(), c.normal.z(), c.depth);
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ContactQuery query;
  try {
    query = parse_query(text, "fuzz.json");
  } catch (const InputError&) {
    return 0;
  }
  for (const DetectorInfo& detector : detectors()) {
    try {
      check(detector.name, detector.detect(query, DetectOptions{}));
    } catch (const OdeError& e) {
      std::fprintf(stderr, "accepted query reached an ODE error in %.*s: %s\n", static_cast<int>(detector.name.size()),
                   detector.name.data(), e.what());
      std::abort();
    }
  }
  return 0;
}
