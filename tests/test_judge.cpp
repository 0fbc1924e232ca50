// The judge of a collider (validation/conform/judge/): analytic answers for a known pair, our own detector
// judged right on every regime, and colliders that are wrong on purpose caught by exactly the
// kind of failure they commit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/validation/conform/conform_report.hpp"
#include "boxpile/validation/contacts/detectors.hpp"
#include "boxpile/validation/conform/judge/check_collider.hpp"
#include "boxpile/validation/conform/judge/judge.hpp"
#include "boxpile/tests/support/own_collider.hpp"

using namespace boxpile;
using boxpile::test::kOwn;

namespace {

// Two unit cubes, A 0.9 m above B: they overlap by 0.1 m, a face contact with normal +z whose
// four points are the corners of the overlap square at height 0.45 (midway between the faces).
const OrientedBox kLower = make_box(Vec3::Constant(0.5), Vec3::Zero());
const OrientedBox kUpper = make_box(Vec3::Constant(0.5), Vec3(0, 0, 0.9));

Manifold square(const Vec3& normal, double depth, double height = 0.45) {
  Manifold m;
  for (const double x : {-0.5, 0.5}) {
    for (const double y : {-0.5, 0.5}) m.push_back({Vec3(x, y, height), normal, depth, {}});
  }
  return m;
}

bool has(const std::vector<Finding>& f, FailureKind k) {
  return std::any_of(f.begin(), f.end(), [k](const Finding& x) { return x.kind == k; });
}

CheckOptions samples_only(int n) {
  CheckOptions o;
  o.samples = n;
  o.seed = 5;
  return o;
}

}  // namespace

TEST_CASE("the judge on two stacked cubes: right answer, reversed normal, wrong depth, points off",
          "[judge]") {
  CHECK(std::abs(true_depth(kUpper, kLower) - 0.1) < 1e-15);
  CHECK(judge_box_box(kUpper, kLower, square(Vec3::UnitZ(), 0.1)).empty());

  const auto reversed = judge_box_box(kUpper, kLower, square(-Vec3::UnitZ(), 0.1));
  REQUIRE(has(reversed, FailureKind::Normal));
  CHECK(reversed[0].error > 1.0);  // moving A down never separates it: a large excess

  const auto shallow = judge_box_box(kUpper, kLower, square(Vec3::UnitZ(), 0.09));
  REQUIRE(shallow.size() == 1);
  CHECK(shallow[0].kind == FailureKind::Depth);
  CHECK(std::abs(shallow[0].error - 0.01) < 1e-15);

  // Points on A's top face: 0.5 m above the overlap, outside B by 0.45 m beyond half the depth.
  const auto high = judge_box_box(kUpper, kLower, square(Vec3::UnitZ(), 0.1, 1.4));
  REQUIRE(high.size() == 1);
  CHECK(high[0].kind == FailureKind::Outside);
  CHECK(std::abs(high[0].error - (1.4 - 0.5 - 0.05)) < 1e-12);

  CHECK(has(judge_box_box(kUpper, kLower, Manifold{}), FailureKind::Missed));
  const OrientedBox apart = make_box(Vec3::Constant(0.5), Vec3(0, 0, 1.2));
  CHECK(judge_box_box(apart, kLower, Manifold{}).empty());
  CHECK(has(judge_box_box(apart, kLower, square(Vec3::UnitZ(), 0.0, 0.6)), FailureKind::Phantom));
}

TEST_CASE("the judge of box-plane answers: deepest vertex, the plane's normal, points below", "[judge]") {
  // A unit cube turned 45 degrees about x, its lowest edge 0.05 m below the plane z = 0.
  const double half_diagonal = std::sqrt(0.5);
  const OrientedBox box = make_box(Vec3::Constant(0.5), Vec3(0, 0, half_diagonal - 0.05),
                                   Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX())));
  const HalfSpace ground;
  CHECK(std::abs(true_depth(box, ground) - 0.05) < 1e-12);
  Manifold edge;
  for (const double x : {-0.5, 0.5}) edge.push_back({Vec3(x, 0, -0.025), Vec3::UnitZ(), 0.05, {}});
  CHECK(judge_box_plane(box, ground, edge).empty());
  Manifold tilted = edge;
  for (Contact& c : tilted) c.normal = Vec3(0, 0.1, 1).normalized();
  CHECK(has(judge_box_plane(box, ground, tilted), FailureKind::Normal));
  CHECK(has(judge_box_plane(box, ground, Manifold{}), FailureKind::Missed));
}

TEST_CASE("every regime draws the pairs it names", "[judge]") {
  std::mt19937_64 rng(3);
  const int n = 300;
  for (const Regime r : all_regimes()) {
    INFO(regime_name(r));
    int overlapping = 0, edge_edge = 0, face_points = 0, grazing = 0;
    for (int k = 0; k < n; ++k) {
      const BoxPair p = random_pair(r, rng);
      const double depth = true_depth(p.a, p.b);
      if (depth > 0.0) ++overlapping;
      if (std::abs(depth) <= 2e-3 * std::min(p.a.half.minCoeff(), p.b.half.minCoeff()) + 1e-15) ++grazing;
      Manifold m;
      collide_box_box(p.a, p.b, CollisionSettings{}, m);
      if (!m.empty() && m[0].feature.kind() == FeatureKind::EdgeEdge) ++edge_edge;
      if (m.size() >= 3) ++face_points;
    }
    switch (r) {
      case Regime::Far: CHECK(overlapping == 0); break;
      case Regime::Deep: CHECK(overlapping == n); break;
      case Regime::EdgeEdge: CHECK(edge_edge == n); break;
      case Regime::Parallel: CHECK(face_points == n); break;
      case Regime::Touching:
        CHECK(grazing == n);
        CHECK(overlapping > n / 3);
        CHECK(overlapping < 2 * n / 3);
        break;
      default: CHECK(overlapping > n / 2); break;
    }
  }
}

TEST_CASE("our own detector is judged right on every regime and every contact fixture", "[judge]") {
  CheckOptions options = samples_only(1400);
  options.cases = load_cases(std::string(BOXPILE_FIXTURES_DIR) + "/contacts");
  const CheckResult r = check_collider(kOwn, options);
  CHECK(r.queries == 1400 + static_cast<int>(options.cases.size()));
  CHECK(r.touching > r.queries / 2);
  for (const FailedCase& c : r.failures) {
    INFO(c.name << ": " << c.findings[0].why);
    CHECK(c.findings.empty());
  }
  CHECK(r.within_gates());
}

TEST_CASE("colliders wrong on purpose fail by the kind of their fault, on every affected query", "[judge]") {
  const CheckOptions options = samples_only(700);
  const CheckResult truth = check_collider(kOwn, options);
  REQUIRE(truth.failures.empty());

  SECTION("no contact ever: every overlapping pair is missed") {
    const CheckResult r = check_collider([](const ContactQuery&) { return Manifold{}; }, options);
    CHECK(r.count(FailureKind::Missed) == truth.touching);
    CHECK_FALSE(r.within_gates());
  }
  SECTION("the normal from A toward B") {
    const CheckResult r = check_collider(
        [](const ContactQuery& q) {
          Manifold m = kOwn(q);
          for (Contact& c : m) c.normal = -c.normal;
          return m;
        },
        options);
    // Every overlapping pair but a few where A sits deep inside B (its centre near B's): then
    // moving A either way separates them alike, and the reversed normal is right too.
    CHECK(r.count(FailureKind::Normal) >= truth.touching * 98 / 100);
    CHECK(r.count(FailureKind::Normal) <= truth.touching);
  }
  SECTION("depths 1% too deep") {
    const CheckResult r = check_collider(
        [](const ContactQuery& q) {
          Manifold m = kOwn(q);
          for (Contact& c : m) c.depth *= 1.01;
          return m;
        },
        options);
    CHECK(r.count(FailureKind::Depth) >= truth.touching * 9 / 10);
    CHECK(r.count(FailureKind::Normal) == 0);
  }
  SECTION("a contact at the centre of A even when apart") {
    const CheckResult r = check_collider(
        [](const ContactQuery& q) {
          Manifold m = kOwn(q);
          if (m.empty()) m.push_back({q.a.pose.position, Vec3::UnitZ(), 0.0, {}});
          return m;
        },
        options);
    CHECK(truth.apart > options.samples / 7);  // the far regime at least
    CHECK(r.count(FailureKind::Phantom) == truth.apart);
  }
  SECTION("answers that depend on which box is A") {
    const CheckResult r = check_collider(
        [](const ContactQuery& q) {
          Manifold m = kOwn(q);
          if (q.b && q.a.half_extents.x() < q.b->half_extents.x()) {
            for (Contact& c : m) c.position += 1e-4 * c.normal.unitOrthogonal();
          }
          return m;
        },
        options);
    CHECK(r.count(FailureKind::Swap) > truth.touching / 4);
  }
}

TEST_CASE("conform judges every registered detector on each failing query", "[judge]") {
  // A collider that never answers fails every fixture whose boxes overlap; each of those queries
  // then goes through the detector table and the judge (validation/conform/conform_report.hpp).
  ConformRun run;
  run.options = samples_only(0);
  run.options.cases = load_cases(std::string(BOXPILE_FIXTURES_DIR) + "/contacts");
  run.result = check_collider([](const ContactQuery&) { return Manifold{}; }, run.options);
  REQUIRE(run.result.failures.size() == static_cast<std::size_t>(run.result.touching));
  judge_detectors(run);
  REQUIRE(run.detectors.size() == run.result.failures.size());
  auto findings_of = [](const std::vector<DetectorFindings>& judged, const std::string& name) {
    const auto it = std::find_if(judged.begin(), judged.end(), [&](const DetectorFindings& d) { return d.detector == name; });
    REQUIRE(it != judged.end());
    return it->findings;
  };
  bool crossing_seen = false;
  for (std::size_t k = 0; k < run.detectors.size(); ++k) {
    const FailedCase& c = run.result.failures[k];
    INFO(c.name);
    const bool plane = !c.query.b;
    // Every detector that answers the query's kind, in table order; ours is always right.
    const auto answering = std::count_if(detectors().begin(), detectors().end(),
                                         [&](const DetectorInfo& d) { return plane || !d.box_plane_only; });
    CHECK(run.detectors[k].size() == static_cast<std::size_t>(answering));
    CHECK(findings_of(run.detectors[k], "own").empty());
    if (c.name == "crossing_edges") {
      // Bullet's fudge2 makes its edge-edge depth 2e-5 m too deep, ODE's is exact.
      crossing_seen = true;
      const std::vector<Finding> bullet = findings_of(run.detectors[k], "bullet");
      CHECK(std::any_of(bullet.begin(), bullet.end(), [](const Finding& f) {
        return f.kind == FailureKind::Depth && std::abs(f.error - 2e-5) < 1e-9;
      }));
      CHECK(findings_of(run.detectors[k], "ode").empty());
    }
  }
  CHECK(crossing_seen);
}
