// Shared helpers for the contact tests: seeds and point checks. Box construction, point-set
// distances, the random pose pairs and the brute-force quantities (directional penetration, least
// penetration) are the library's judge (validation/conform/judge/), computed without the code under test.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/validation/conform/judge/brute_force.hpp"
#include "boxpile/validation/conform/judge/pose_sampler.hpp"

namespace boxpile::test {

inline Quat axis_angle(const Vec3& axis, double angle) {
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

// Seeds and sample counts: fixed by default so CI is repeatable; BOXPILE_SEED and BOXPILE_SAMPLES
// override them for long runs.
inline std::uint64_t test_seed(std::uint64_t fallback) {
  const char* s = std::getenv("BOXPILE_SEED");
  return s ? std::strtoull(s, nullptr, 10) : fallback;
}
inline int test_samples(int fallback) {
  const char* s = std::getenv("BOXPILE_SAMPLES");
  return s ? std::atoi(s) : fallback;
}
// Steps of the long drift runs: BOXPILE_LONG_RUN_STEPS shortens them where every step costs tens
// of times more (the sanitizer stage of .ci/run; the release stage runs them in full).
// A value that is no positive integer is an error, not a run of no steps (which would pass).
inline int test_long_run_steps(int fallback) {
  const char* s = std::getenv("BOXPILE_LONG_RUN_STEPS");
  if (!s) return fallback;
  const int steps = std::atoi(s);
  if (steps <= 0) throw std::invalid_argument(std::string("BOXPILE_LONG_RUN_STEPS must be a positive integer, got ") + s);
  return steps;
}

// Steps of each catalogue and example scene's run: BOXPILE_SCENE_STEPS runs only the first ones
// where every step costs tens of times more (the sanitizer stage of .ci/run, where the whole runs
// were half of the stage's time; the release stage runs every scene in full and holds the
// verdicts). None when unset; a value that is no positive integer is an error.
inline std::optional<long> test_scene_steps() {
  const char* s = std::getenv("BOXPILE_SCENE_STEPS");
  if (!s) return std::nullopt;
  const long steps = std::atol(s);
  if (steps <= 0) throw std::invalid_argument(std::string("BOXPILE_SCENE_STEPS must be a positive integer, got ") + s);
  return steps;
}

// The manifold has exactly the expected points, each matched by one contact within tol. For use
// inside Catch2 tests (the file including this must include catch.hpp first).
#ifdef REQUIRE
inline void require_points(const Manifold& m, const std::vector<Vec3>& expected, double tol) {
  REQUIRE(m.size() == static_cast<int>(expected.size()));
  for (const Vec3& e : expected) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Contact& c : m) nearest = std::min(nearest, (c.position - e).norm());
    INFO("expected point " << e.transpose());
    CHECK(nearest < tol);
  }
}
#endif

inline double max_depth(const Manifold& m) {
  double d = -std::numeric_limits<double>::infinity();
  for (const Contact& c : m) d = std::max(d, c.depth);
  return d;
}

}  // namespace boxpile::test
