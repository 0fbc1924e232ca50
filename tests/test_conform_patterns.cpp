// What `boxpile conform` makes of a collider's failures beyond counting them
// (validation/conform/judge/contact_kind.hpp, systematic.hpp, the float32 tolerances, --keep, and the
// references' known biases): colliders wrong on purpose in one way each, named for that way.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "boxpile/validation/conform/conform_report.hpp"
#include "boxpile/validation/contacts/detectors.hpp"
#include "boxpile/validation/conform/judge/check_collider.hpp"
#include "boxpile/validation/conform/judge/contact_kind.hpp"
#include "boxpile/validation/conform/judge/systematic.hpp"
#include "boxpile/validation/conform/known_biases.hpp"
#include "boxpile/tests/support/own_collider.hpp"

using namespace boxpile;
using boxpile::test::kOwn;

namespace {

CheckOptions samples(int n) {
  CheckOptions o;
  o.samples = n;
  o.seed = 5;
  return o;
}

// Our detector with one change made to every answer.
template <class Change>
Collider changed(Change change) {
  return [change](const ContactQuery& q) {
    Manifold m = kOwn(q);
    change(q, m);
    return m;
  };
}

const SystematicError* pattern(const std::vector<SystematicError>& found, const std::string& name) {
  const auto it = std::find_if(found.begin(), found.end(), [&](const SystematicError& e) { return e.pattern == name; });
  return it == found.end() ? nullptr : &*it;
}

double rounded(double x) { return static_cast<double>(static_cast<float>(x)); }
Vec3 rounded(const Vec3& v) { return v.cast<float>().cast<double>(); }

QueryBox rounded(const QueryBox& b) {
  QueryBox r = b;
  r.half_extents = rounded(b.half_extents);
  r.pose.position = rounded(b.pose.position);
  r.pose.orientation = Quat(b.pose.orientation.coeffs().cast<float>().cast<double>().eval()).normalized();
  return r;
}

// A single-precision collider: the query read into floats, our detector, the answer written as floats.
Manifold float32_own(const ContactQuery& q) {
  ContactQuery f = q;
  f.a = rounded(q.a);
  if (q.b) f.b = rounded(*q.b);
  if (q.plane) f.plane->offset = rounded(q.plane->offset);
  Manifold m = kOwn(f);
  for (Contact& c : m) {
    c.position = rounded(c.position);
    c.normal = rounded(c.normal);
    c.depth = rounded(c.depth);
  }
  return m;
}

}  // namespace

TEST_CASE("contact kinds follow the geometry of each regime", "[judge][patterns]") {
  const CheckResult r = check_collider(kOwn, samples(1400));
  REQUIRE(r.failing == 0);
  auto regime = [&](const std::string& name) {
    const auto it = std::find_if(r.by_regime.begin(), r.by_regime.end(), [&](const auto& t) { return t.first == name; });
    REQUIRE(it != r.by_regime.end());
    return it->second;
  };
  CHECK(regime("edge_edge").queries == 200);
  // Every query lands in one kind; the far pairs are all apart.
  int total = 0;
  for (const auto& [kind, t] : r.by_contact) total += t.queries;
  CHECK(total == r.queries);
  CHECK(r.by_contact.at(ContactKind::Apart).queries >= 200);
  CHECK(!r.by_contact.contains(ContactKind::BoxPlane));

  std::mt19937_64 rng(3);
  int edge_edge = 0, face_face = 0;
  for (int k = 0; k < 200; ++k) {
    const BoxPair e = random_pair(Regime::EdgeEdge, rng);
    edge_edge += contact_kind(e.a, e.b) == ContactKind::EdgeEdge;
    const BoxPair p = random_pair(Regime::Parallel, rng);
    face_face += contact_kind(p.a, p.b) == ContactKind::FaceFace;
  }
  // Two edges crossing near their middles, turned 45 degrees: edge against edge, as our detector
  // finds them (test_judge.cpp); faces on parallel faces: face-face.
  CHECK(edge_edge == 200);
  CHECK(face_face == 200);
  // A unit cube resting on a corner, an edge, a face of another.
  const OrientedBox floor = make_box(Vec3::Constant(0.5), Vec3::Zero());
  CHECK(contact_kind(make_box(Vec3::Constant(0.5), Vec3(0.1, 0.2, 0.99)), floor) == ContactKind::FaceFace);
  const Quat on_edge(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()));
  CHECK(contact_kind(make_box(Vec3::Constant(0.5), Vec3(0, 0, 0.5 + std::sqrt(0.5) - 0.01), on_edge), floor) ==
        ContactKind::FaceEdge);
  const Quat on_corner = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3::UnitZ());
  const OrientedBox corner = make_box(Vec3::Constant(0.5), Vec3::Zero(), on_corner);
  const double reach = corner.radius_along(Vec3::UnitZ());
  CHECK(contact_kind(make_box(Vec3::Constant(0.5), Vec3(0, 0, 0.5 + reach - 0.01), on_corner), floor) ==
        ContactKind::Vertex);
  CHECK(contact_kind(make_box(Vec3::Constant(0.5), Vec3(0, 0, 1.1)), floor) == ContactKind::Apart);
}

TEST_CASE("a collider whose depths are 10% short is named by its ratio", "[judge][patterns]") {
  const CheckResult r = check_collider(changed([](const ContactQuery&, Manifold& m) {
                                         for (Contact& c : m) c.depth *= 0.9;
                                       }),
                                       samples(700));
  REQUIRE(r.count(FailureKind::Depth) > 300);
  const std::vector<SystematicError> found = find_systematic(r);
  const SystematicError* e = pattern(found, "depth_ratio");
  REQUIRE(e);
  CHECK(std::abs(e->value - 0.9) < 1e-12);
  CHECK(e->spread < 1e-9);
  CHECK(e->count == r.count(FailureKind::Depth));
  CHECK(e->of == e->count);
  CHECK(e->text.find("depth 0.9 of the truth") == 0);
  CHECK(!pattern(found, "depth_offset"));
  CHECK(!pattern(found, "reversed_normals"));
}

TEST_CASE("a constant depth offset and points off the midway plane are named by their size", "[judge][patterns]") {
  const CheckResult deeper = check_collider(changed([](const ContactQuery&, Manifold& m) {
                                              for (Contact& c : m) c.depth += 1e-3;
                                            }),
                                            samples(700));
  const std::vector<SystematicError> deeper_found = find_systematic(deeper);
  const SystematicError* e = pattern(deeper_found, "depth_offset");
  REQUIRE(e);
  CHECK(std::abs(e->value - 1e-3) < 1e-9);
  CHECK(e->count >= 0.99 * e->of);

  // Each point 1.5 depths toward A: outside B by a depth, half of which the judge allows.
  const CheckResult off = check_collider(changed([](const ContactQuery&, Manifold& m) {
                                           for (Contact& c : m) c.position += 1.5 * c.depth * c.normal;
                                         }),
                                         samples(700));
  REQUIRE(off.count(FailureKind::Outside) > 200);
  const std::vector<SystematicError> off_found = find_systematic(off);
  const SystematicError* p = pattern(off_found, "position_fraction");
  REQUIRE(p);
  CHECK(std::abs(p->value - 1.5) < 1e-6);
  CHECK(p->text.find("toward A") != std::string::npos);
}

TEST_CASE("edge-edge normals reversed are named for edge-edge alone", "[judge][patterns]") {
  const CheckResult r = check_collider(changed([](const ContactQuery&, Manifold& m) {
                                         if (m.empty() || m[0].feature.kind() != FeatureKind::EdgeEdge) return;
                                         for (Contact& c : m) c.normal = -c.normal;
                                       }),
                                       samples(1400));
  const std::vector<SystematicError> found = find_systematic(r);
  const auto reversed = std::count_if(found.begin(), found.end(),
                                      [](const SystematicError& e) { return e.pattern == "reversed_normals"; });
  CHECK(reversed == 1);
  const SystematicError* e = pattern(found, "reversed_normals");
  REQUIRE(e);
  CHECK(e->contact == "edge-edge");
  // The edge_edge regime alone gives 200 such queries; our detector's kind and the judge's agree
  // but near the face-bias band's edge.
  CHECK(e->count >= 200);
  CHECK(e->count >= 0.97 * e->of);
  CHECK(r.by_contact.at(ContactKind::EdgeEdge).reversed == e->count);
}

TEST_CASE("float32 tolerances pass a single-precision collider that float64 fails", "[judge][patterns]") {
  CheckOptions o = samples(1400);
  o.cases = load_cases(std::string(BOXPILE_FIXTURES_DIR) + "/contacts");
  const CheckResult strict = check_collider(float32_own, o);
  CHECK(strict.failing > strict.queries / 2);
  o.tolerances = float32_tolerances();
  const CheckResult loose = check_collider(float32_own, o);
  for (const FailedCase& c : loose.failures) {
    INFO(c.name << ": " << c.findings[0].why);
    CHECK(c.findings.empty());
  }
  CHECK(loose.failing == 0);
  // The tolerances grow with the query: 64 roundoffs of its scale.
  const JudgeTolerances at_100m = float32_tolerances().at_scale(100.0);
  CHECK(at_100m.depth == Approx(100.0 * 64 * 0x1p-24));
  CHECK(float32_tolerances().at_scale(1e-4).depth == kJudgeDepthTolerance);
}

TEST_CASE("keep bounds the failures kept whole, the counts stay whole", "[judge][patterns]") {
  CheckOptions o = samples(700);
  o.keep = 5;
  int seen = 0;
  o.on_failure = [&seen](const FailedCase&) { ++seen; };
  const CheckResult r = check_collider([](const ContactQuery&) { return Manifold{}; }, o);
  CHECK(r.count(FailureKind::Missed) == r.touching);
  CHECK(seen == r.failing);
  CHECK(static_cast<int>(r.symptoms.size()) == r.failing);
  CHECK(r.failures.size() == 5);
  CHECK(r.saved(FailureKind::Missed) == 5);
  // The worst five: the largest overlaps relative to the query's scale, in query order.
  double least_kept = 1e9;
  for (const FailedCase& c : r.failures) least_kept = std::min(least_kept, c.relative_error(FailureKind::Missed));
  CHECK(std::is_sorted(r.failures.begin(), r.failures.end(),
                       [](const FailedCase& x, const FailedCase& y) { return x.index < y.index; }));
  o.keep = 0;
  CHECK(check_collider([](const ContactQuery&) { return Manifold{}; }, o).failures.empty());
  o.keep = 10'000;
  const CheckResult all = check_collider([](const ContactQuery&) { return Manifold{}; }, o);
  REQUIRE(static_cast<int>(all.failures.size()) == all.failing);
  int above = 0;
  for (const FailedCase& c : all.failures) above += c.relative_error(FailureKind::Missed) > least_kept;
  CHECK(above <= 4);
}

TEST_CASE("a reference wrong only within its known bias is counted apart", "[judge][patterns]") {
  // A collider 10% short on every depth: Bullet is "also wrong" on the edge-edge queries, by its
  // fudge2 term alone, and so no witness that they are hard.
  ConformRun run;
  run.options = samples(700);
  run.options.regimes = {Regime::EdgeEdge};
  run_conform(run, changed([](const ContactQuery&, Manifold& m) {
                for (Contact& c : m) c.depth *= 0.9;
              }));
  REQUIRE(run.result.failing == 700);
  const auto tally = [&](const std::string& name) {
    const auto it = std::find_if(run.detector_tallies.begin(), run.detector_tallies.end(),
                                 [&](const DetectorTally& t) { return t.detector == name; });
    REQUIRE(it != run.detector_tallies.end());
    return *it;
  };
  CHECK(tally("own").wrong == 0);
  CHECK(tally("own").within_bias == 0);
  CHECK(tally("ode").wrong == 0);
  const DetectorTally bullet = tally("bullet");
  CHECK(bullet.judged == 700);
  CHECK(bullet.wrong == 0);
  CHECK(bullet.within_bias == 700);
  CHECK(bullet.biases.at("edge-edge depth + fudge2") == 700);
  // Every bias row names a registered detector.
  for (const KnownBias& b : known_biases()) CHECK_NOTHROW(find_detector(b.detector));
}
