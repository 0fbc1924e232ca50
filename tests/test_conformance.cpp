// Conformance of our contact generation with ODE 0.16 and Bullet 3.24, and checks of the
// reference engines themselves.
//
// In the manner of MuJoCo's randomised box-box test: many random pairs (fixed seed; BOXPILE_SEED
// and BOXPILE_SAMPLES override it for long runs), invariants checked on every sample, and every
// kind of disagreement counted and gated by a stated limit rather than required never to happen.
// Where we and a reference disagree, brute force decides who is right: the exact least
// penetration over the 15 candidate axes and the exact penetration along each reported normal
// (validation/conform/judge/, the judge of `boxpile conform` too). Set BOXPILE_DUMP_DIR to write every
// disagreement as a contact query; the ones worth keeping are committed under fixtures/contacts/
// with a note, and the fixture test below checks what each engine reports for them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "boxpile/tests/support/engine_scenes.hpp"
#include "boxpile/reference/bullet/bullet_engine.hpp"
#include "boxpile/reference/ode/ode_engine.hpp"
#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/tests/support/geometry.hpp"
#include "boxpile/validation/contacts/contact_diff.hpp"
#include "boxpile/validation/conform/known_biases.hpp"
#include "boxpile/validation/contacts/detectors.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/conform/judge/judge.hpp"

using namespace boxpile;
using namespace boxpile::test;

namespace {

constexpr int kDefaultSamples = 20000;

// --- tolerances -------------------------------------------------------------------------------
// The judge's (validation/conform/judge/judge.hpp): boxes of 0.1-1 m computed in double precision agree
// to rounding (1e-15 m); these sit far above that and far below any physical difference.
constexpr double kNormalTolerance = kJudgeNormalTolerance;      // rad
constexpr double kDepthTolerance = kJudgeDepthTolerance;        // m
constexpr double kRegionTolerance = kJudgeRegionTolerance;      // m
constexpr double kUnitTolerance = kJudgeUnitTolerance;          // |n| - 1
constexpr double kTouchingTolerance = kJudgeTouchingTolerance;  // m

bool is_face(FeatureKind k) { return k == FeatureKind::FaceA || k == FeatureKind::FaceB; }

// Our one deliberate difference from ODE's and Bullet's box-box sets: an edge-edge point followed
// by the clipped points of a face within kEdgeNearFaceCos of its normal (box_box.hpp).
bool is_near_face(const Manifold& own, const SatResult& sat) {
  return sat.kind == FeatureKind::EdgeEdge && own.size() > 1;
}

// Whether a face normal of A or B lies within kEdgeNearFaceCos of n.
bool near_a_face_normal(const BoxPair& p, const Vec3& n) {
  return (p.a.axes.transpose() * n).cwiseAbs().maxCoeff() > kEdgeNearFaceCos ||
         (p.b.axes.transpose() * n).cwiseAbs().maxCoeff() > kEdgeNearFaceCos;
}

// --- brute force ------------------------------------------------------------------------------

enum class Verdict { OwnRight, ReferenceRight, BothAcceptable, BothWrong };

// Which normal is right. Between a face and an edge (`face_bias`), either is right within the
// face-bias band; between two faces or two edges neither detector means to prefer one, so the
// one nearer the least penetration is right (both, when within the touching tolerance).
Verdict arbitrate_normals(const BoxPair& p, const Vec3& n_own, const Vec3& n_ref, bool face_bias) {
  const NormalJudgement own = judge_normal(p.a, p.b, n_own);
  const NormalJudgement ref = judge_normal(p.a, p.b, n_ref);
  if (face_bias) {
    if (own.acceptable && ref.acceptable) return Verdict::BothAcceptable;
    if (own.acceptable) return Verdict::OwnRight;
    if (ref.acceptable) return Verdict::ReferenceRight;
    return Verdict::BothWrong;
  }
  if (std::abs(own.excess - ref.excess) <= kTouchingTolerance) return Verdict::BothAcceptable;
  return own.excess < ref.excess ? Verdict::OwnRight : Verdict::ReferenceRight;
}

// Presence: whoever says "contact" is right when the boxes overlap by more than the touching
// tolerance, whoever says "none" when they are apart by more; in between both are.
Verdict arbitrate_presence(const BoxPair& p, bool own_touches) {
  const double least = true_depth(p.a, p.b);
  if (std::abs(least) <= kTouchingTolerance) return Verdict::BothAcceptable;
  return (least > 0.0) == own_touches ? Verdict::OwnRight : Verdict::ReferenceRight;
}

// --- writing disagreements as contact queries (BOXPILE_DUMP_DIR) ------------------------------

std::string number(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}
std::string json_vec(const Vec3& v) { return "[" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + "]"; }
std::string json_box(const OrientedBox& b) {
  const Quat q(b.axes);
  return "{\"half_extents\": " + json_vec(b.half) + ", \"position\": " + json_vec(b.center) +
         ", \"orientation\": [" + number(q.w()) + ", " + number(q.x()) + ", " + number(q.y()) + ", " +
         number(q.z()) + "]}";
}

class Dumper {
 public:
  Dumper() {
    if (const char* dir = std::getenv("BOXPILE_DUMP_DIR")) dir_ = dir;
  }
  void box_box(const std::string& name, const std::string& note, const BoxPair& p) {
    write(name, note, json_box(p.a), json_box(p.b));
  }
  void box_plane(const std::string& name, const std::string& note, const OrientedBox& a, const HalfSpace& h) {
    write(name, note, json_box(a),
          "{\"plane\": {\"normal\": " + json_vec(h.normal) + ", \"offset\": " + number(h.offset) + "}}");
  }

 private:
  // At most this many files per category prefix, so a long run does not flood the folder.
  static constexpr int kMaxPerCategory = 20;
  void write(const std::string& name, const std::string& note, const std::string& a, const std::string& b) {
    if (dir_.empty()) return;
    const std::string category = name.substr(0, name.rfind('_'));
    if (written_[category]++ >= kMaxPerCategory) return;
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ + "/" + name + ".json") << "{\n  \"name\": \"" << name << "\",\n  \"note\": \"" << note
                                               << "\",\n  \"a\": " << a << ",\n  \"b\": " << b << "\n}\n";
  }
  std::string dir_;
  std::map<std::string, int> written_;
};

// --- box-box ----------------------------------------------------------------------------------

// Every way a reference's set can differ from ours; the first that applies is counted.
enum class Mismatch {
  Invalid,   // the reference's set breaks the convention on its own (see reference_invariants)
  Presence,  // one reports a contact, the other none
  Kind,      // face against edge
  Normal,    // same kind, another normal
  Merged,    // same normal, fewer points because close points merged (Bullet, by design)
  Depth,     // same normal, another deepest depth
  Region,    // same normal, a reference point outside our contact region
  Count,     // same normal, another number of points than min(ours, the reference's cap)
};
constexpr std::array<const char*, 8> kMismatchNames = {"invalid", "presence", "kind", "normal",
                                                       "merged", "depth", "region", "count"};
const char* mismatch_name(Mismatch m) { return kMismatchNames[static_cast<std::size_t>(m)]; }

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::OwnRight: return "own right";
    case Verdict::ReferenceRight: return "reference right";
    case Verdict::BothAcceptable: return "both acceptable";
    case Verdict::BothWrong: return "both wrong";
  }
  return "";
}

// Mismatches allowed, as a fraction of the samples, per kind (see docs/reference-engines.md for
// the measured rates behind them); a kind not listed allows none.
using MismatchGates = std::map<Mismatch, double>;

// A reference detector of the table (validation/contacts/detectors.hpp), what we know of its box-box sets,
// and the mismatches with ours it is allowed.
struct Reference {
  const char* name;
  int max_points;
  bool merges_close_points;  // Bullet's persistent manifold merges points nearer than its threshold
  MismatchGates gates;
};

// Measured over 20,000 (seed 11) and 300,000 (seed 7) samples, as fractions of the samples:
//   invalid    ODE 2.0e-4 / 2.9e-4, Bullet 2.0e-4 / 3.0e-4: an edge-edge point outside the
//              boxes (the closest points of the infinite edge lines, on a deeper edge pair)
//   presence   Bullet 0 / 1.7e-5: a phantom edge contact of depth ~1e-5 between separated
//              boxes (its fudge2 term widens the boxes along edge axes)
//   kind       ODE 3.0e-3 / 3.4e-3, Bullet 2.8e-3 / 3.2e-3: face against edge in a near-tie,
//              both within the face-bias band
//   normal     ODE 4.2e-3 / 4.4e-3, Bullet 4.2e-3 / 4.4e-3: they keep an earlier edge axis
//              unless a later one is 5% shallower; ours is always the shallower
//   merged     Bullet 5.3e-3 / 5.5e-3: points closer than its breaking threshold merged
// Each gate is about twice the larger rate; depth, region and count have none (0 allowed).
const std::vector<Reference> kBoxBoxReferences = {
    {"ode", kMaxManifoldPoints, false,
     {{Mismatch::Invalid, 6e-4}, {Mismatch::Kind, 7e-3}, {Mismatch::Normal, 9e-3}}},
    {"bullet", 4, true,
     {{Mismatch::Invalid, 6e-4},
      {Mismatch::Presence, 1e-4},
      {Mismatch::Kind, 7e-3},
      {Mismatch::Normal, 9e-3},
      {Mismatch::Merged, 1.1e-2}}},
    // MuJoCo 2.2.2's mjc_BoxBox, measured over 20,000 samples (seed 11): kind 9.5e-2 (face against
    // edge, every one within the face-bias band by brute force: its own bias differs), normal
    // 5e-5, depth 3.5e-1 (its face contacts often carry half the penetration as `dist`: checked on
    // the dumped cases, the point ours, its depth ours / 2), region 1.9e-1 (points off our clipped
    // region, e.g. single points where we clip a face), count 3.8e-3. Rates this large are gated
    // near the measured rate (about ten binomial deviations above it), not at twice.
    {"mujoco", kMaxManifoldPoints, false,
     {{Mismatch::Kind, 0.11},
      {Mismatch::Normal, 2e-4},
      {Mismatch::Depth, 0.37},
      {Mismatch::Region, 0.21},
      {Mismatch::Count, 6e-3}}},
    // DART's box-box (DARTCollisionDetector) is a port of ODE's dBoxBox, and so is FCL 0.7's box
    // primitive test: ODE's rates (invalid 4, kind 59, normal 83 of 20,000, seed 11), with at most
    // 4 points (they cull to 4 where ODE keeps 8). Gated as ODE.
    {"dart", 4, false, {{Mismatch::Invalid, 6e-4}, {Mismatch::Kind, 7e-3}, {Mismatch::Normal, 9e-3}}},
    {"fcl", 4, false, {{Mismatch::Invalid, 6e-4}, {Mismatch::Kind, 7e-3}, {Mismatch::Normal, 9e-3}}},
};

// Our near-face edge-edge sets (is_near_face) as a fraction of the samples, measured over 20,000
// (seed 11), 300,000 (seed 7) and 1,000,000 (seed 99) samples: 3.28e-2, 3.43e-2, 3.46e-2. Our own
// detector's rate, so gated on both sides, by five binomial standard deviations of the run's own
// sample count: 2.8% to 4.1% at the default 20,000 samples, wider in the sanitizer stage's shorter
// runs (a wider or narrower angle, or the points gone, shows). Each one must be judged right by
// brute force (deepest depth the penetration along the normal, every point inside both boxes, the
// same set when A and B swap), its normal within kEdgeNearFaceCos of a face normal, and its edge
// point agree with a reference's one point wherever the reference finds the same edge axis.
constexpr double kNearFaceRate = 0.0345;
constexpr double kNearFaceSigmas = 5.0;  // a fair run falls outside about once in 1.7 million

struct Tally {
  int samples = 0;
  int touching = 0;  // both report contacts
  std::map<Mismatch, int> mismatches;
  std::map<std::pair<Mismatch, Verdict>, int> verdicts;
  int edge_fudge = 0;  // Bullet edge-edge depths explained exactly by its fudge2 term
  int near_face = 0;   // our near-face edge-edge sets whose edge point is the reference's one point
  // Largest differences among samples that agree: how far below the tolerances they stay.
  double worst_angle = 0.0, worst_depth = 0.0, worst_region = 0.0;

  int count(Mismatch m) const {
    const auto it = mismatches.find(m);
    return it == mismatches.end() ? 0 : it->second;
  }
  int count(Verdict v) const {
    int n = 0;
    for (const auto& [key, k] : verdicts)
      if (key.second == v) n += k;
    return n;
  }
};

// Why a reference's set is invalid on its own, or empty: more points than the engine allows, a
// normal not unit or not shared by all points, a negative depth, or a midpoint outside either box
// by more than half its depth (it lies depth/2 from each surface).
std::string reference_invalid(const BoxPair& p, const Manifold& m, int max_points) {
  if (m.size() > max_points) return "too many points";
  for (const Contact& c : m) {
    if (std::abs(c.normal.norm() - 1.0) > kUnitTolerance) return "normal not unit";
    if ((c.normal - m[0].normal).norm() > kUnitTolerance) return "normals differ";
    if (c.depth < -kDepthTolerance) return "negative depth";
    if (outside_distance(p.a, c.position) > 0.5 * c.depth + kRegionTolerance) return "point outside A";
    if (outside_distance(p.b, c.position) > 0.5 * c.depth + kRegionTolerance) return "point outside B";
  }
  return "";
}

// The first mismatch between our set and the reference's, if any (Invalid is checked apart).
std::optional<Mismatch> classify(const Reference& ref, const BoxPair& p, const Manifold& own,
                                 const SatResult& sat, const Manifold& theirs, Tally& t) {
  if (own.empty() != theirs.empty()) return Mismatch::Presence;
  if (own.empty()) return std::nullopt;
  ++t.touching;
  if (is_face(sat.kind) != is_face(theirs[0].feature.kind())) return Mismatch::Kind;
  const ContactDiff d = diff_contacts(own, theirs);
  if (*d.normal_angle > kNormalTolerance) return Mismatch::Normal;
  t.worst_angle = std::max(t.worst_angle, *d.normal_angle);

  // Beside the edge point of two nearly aligned boxes we report the face's clipped points too
  // (kEdgeNearFaceCos in box_box.hpp); the references give the edge point alone.
  const bool near_face = is_near_face(own, sat);
  const int expected = near_face ? 1 : std::min(own.size(), ref.max_points);
  if (ref.merges_close_points && theirs.size() < expected) return Mismatch::Merged;

  double depth_error = std::abs(*d.depth_difference);
  if (ref.merges_close_points && sat.kind == FeatureKind::EdgeEdge) {
    const double fudge = bullet_edge_fudge(p.a, p.b, sat.normal);  // validation/conform/known_biases.hpp
    depth_error = std::abs(*d.depth_difference - fudge);
    if (depth_error <= kDepthTolerance) ++t.edge_fudge;
  }
  if (depth_error > kDepthTolerance) return Mismatch::Depth;
  t.worst_depth = std::max(t.worst_depth, depth_error);

  double region = 0.0;
  for (const Contact& c : theirs) region = std::max(region, distance_to_region(own, own[0].normal, c.position));
  if (region > kRegionTolerance) return Mismatch::Region;
  t.worst_region = std::max(t.worst_region, region);

  if (theirs.size() != expected) return Mismatch::Count;
  if (near_face) ++t.near_face;
  return std::nullopt;
}

std::optional<Verdict> arbitrate(Mismatch m, const BoxPair& p, const Manifold& own, const Manifold& theirs) {
  switch (m) {
    case Mismatch::Invalid: return Verdict::OwnRight;
    case Mismatch::Presence: return arbitrate_presence(p, !own.empty());
    case Mismatch::Kind: return arbitrate_normals(p, own[0].normal, theirs[0].normal, /*face_bias=*/true);
    case Mismatch::Normal: return arbitrate_normals(p, own[0].normal, theirs[0].normal, /*face_bias=*/false);
    default: return std::nullopt;  // same normal: nothing for brute force to decide
  }
}

void compare_box_box(const Reference& ref, const BoxPair& p, int k, const Manifold& own, const SatResult& sat,
                     Tally& t, Dumper& dump) {
  const Manifold theirs = find_detector(ref.name).box_box(p.a, p.b, DetectOptions{});
  ++t.samples;
  auto record = [&](Mismatch m, const std::string& why) {
    ++t.mismatches[m];
    if (const auto v = arbitrate(m, p, own, theirs)) ++t.verdicts[{m, *v}];
    dump.box_box(std::string(ref.name) + "_" + mismatch_name(m) + "_" + std::to_string(test_seed(11)) + "_" +
                     std::to_string(k),
                 why, p);
  };
  if (const std::string why = reference_invalid(p, theirs, ref.max_points); !why.empty()) {
    record(Mismatch::Invalid, why);
  }
  if (const auto m = classify(ref, p, own, sat, theirs, t)) record(*m, mismatch_name(*m));
}

void report(const Reference& ref, const Tally& t) {
  std::ostringstream s;
  s << ref.name << ": " << t.samples << " samples, " << t.touching << " touching in both; mismatches:";
  for (const auto& [m, n] : t.mismatches) {
    s << ' ' << mismatch_name(m) << ' ' << n;
    for (const auto& [key, k] : t.verdicts)
      if (key.first == m) s << " (" << verdict_name(key.second) << ' ' << k << ')';
    s << ',';
  }
  if (ref.merges_close_points) s << " edge depths explained by fudge2 " << t.edge_fudge << ',';
  s << " near-face points beside their edge point " << t.near_face << ',';
  s << " worst agreeing angle " << t.worst_angle << " rad, depth " << t.worst_depth << " m, region "
    << t.worst_region << " m";
  WARN(s.str());
}

// Gates of this rate or more sit near the measured rate (MuJoCo's: measured over 20,000 samples),
// not at twice it: a run of fewer samples (the sanitizer build's 200) then also allows three
// binomial deviations of its own count, or a rate measured at 0.35 fails by chance.
constexpr double kNearMeasuredGate = 0.05;

void check_gates(const Tally& t, const MismatchGates& gates) {
  for (const auto& [m, n] : t.mismatches) {
    INFO(mismatch_name(m) << ": " << n << " of " << t.samples);
    const auto g = gates.find(m);
    const double rate = g == gates.end() ? 0.0 : g->second;
    const double samples = static_cast<double>(t.samples);
    const double slack = rate >= kNearMeasuredGate ? 3.0 * std::sqrt(rate * (1.0 - rate) * samples) : 0.0;
    CHECK(n <= rate * samples + slack);
  }
  // Brute force never finds us wrong, nor both of us.
  CHECK(t.count(Verdict::ReferenceRight) == 0);
  CHECK(t.count(Verdict::BothWrong) == 0);
}

}  // namespace

TEST_CASE("our box-box contacts agree with ODE and Bullet on random pairs", "[conformance][box_box]") {
  // Every registered detector but ours that answers box-box queries is a reference here, with
  // what we know of it.
  for (const DetectorInfo& d : detectors()) {
    if (d.name == kOwnDetector || d.box_plane_only) continue;
    INFO("detector " << d.name << " needs a row in kBoxBoxReferences");
    CHECK(std::any_of(kBoxBoxReferences.begin(), kBoxBoxReferences.end(),
                      [&](const Reference& r) { return d.name == r.name; }));
  }
  std::mt19937_64 rng(test_seed(11));
  const int n = test_samples(kDefaultSamples);
  const DetectorInfo& ours = find_detector(kOwnDetector);
  std::vector<Tally> tallies(kBoxBoxReferences.size());
  Dumper dump;
  int near_face = 0, near_face_wrong = 0, near_face_off_axis = 0;
  for (int k = 0; k < n; ++k) {
    const BoxPair p = random_touching_pair(rng);
    const Manifold own = ours.box_box(p.a, p.b, DetectOptions{});
    const SatResult sat = box_box_sat(p.a, p.b);
    if (is_near_face(own, sat)) {
      ++near_face;
      const std::vector<Finding> findings = judge_box_box(p.a, p.b, own, ours.box_box(p.b, p.a, DetectOptions{}));
      if (!findings.empty()) {
        ++near_face_wrong;
        dump.box_box("own_near_face_" + std::to_string(test_seed(11)) + "_" + std::to_string(k), findings[0].why, p);
      }
      if (!near_a_face_normal(p, sat.normal)) ++near_face_off_axis;
    }
    for (std::size_t r = 0; r < kBoxBoxReferences.size(); ++r) {
      compare_box_box(kBoxBoxReferences[r], p, k, own, sat, tallies[r], dump);
    }
  }
  for (std::size_t r = 0; r < kBoxBoxReferences.size(); ++r) {
    const Reference& ref = kBoxBoxReferences[r];
    report(ref, tallies[r]);
    INFO(ref.name);
    CHECK(tallies[r].touching > n / 2);
    check_gates(tallies[r], ref.gates);
  }
  WARN("our near-face edge-edge sets: " << near_face << " of " << n << ", judged wrong " << near_face_wrong
                                        << ", normal not near a face " << near_face_off_axis);
  const double expected = kNearFaceRate * n;
  const double band = kNearFaceSigmas * std::sqrt(expected * (1.0 - kNearFaceRate));
  CHECK(near_face >= expected - band);
  CHECK(near_face <= expected + band);
  CHECK(near_face_wrong == 0);
  CHECK(near_face_off_axis == 0);
}

// --- box-plane --------------------------------------------------------------------------------

namespace {

struct PlaneCase {
  OrientedBox box;
  HalfSpace plane;
};

// A random box and a random plane with the box's deepest vertex between 0.1 of its largest half
// extent above the plane and one largest half extent below it (so some boxes have 5 or more
// vertices below).
PlaneCase random_box_on_plane(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ext(0.1, 1.0);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  std::uniform_real_distribution<double> sink(-0.1, 1.0);
  PlaneCase c;
  c.box = make_box(Vec3(ext(rng), ext(rng), ext(rng)), Vec3(coord(rng), coord(rng), coord(rng)),
                   random_rotation(rng));
  c.plane.normal = random_unit(rng);
  const double depth = sink(rng) * c.box.half.maxCoeff();
  c.plane.offset = c.plane.normal.dot(c.box.center) - c.box.radius_along(c.plane.normal) + depth;
  return c;
}

// Whether each point of `sub` is one of `set`'s points (position and depth within tolerance).
bool is_subset(const Manifold& sub, const Manifold& set) {
  for (const Contact& c : sub) {
    const bool found = std::any_of(set.begin(), set.end(), [&](const Contact& d) {
      return (c.position - d.position).norm() <= kRegionTolerance && std::abs(c.depth - d.depth) <= kDepthTolerance;
    });
    if (!found) return false;
  }
  return true;
}

// Whether the points of m are the deepest m.size() points of `all`.
bool are_deepest(const Manifold& m, const Manifold& all) {
  std::vector<double> depths;
  for (const Contact& c : all) depths.push_back(c.depth);
  std::sort(depths.rbegin(), depths.rend());
  const double cut = depths[static_cast<std::size_t>(m.size() - 1)];
  return std::all_of(m.begin(), m.end(), [&](const Contact& c) { return c.depth >= cut - kDepthTolerance; });
}

// A reference detector's box-plane sets, against ours (every vertex at or below the plane, at
// its depth): what it reports by design, and the rates allowed where it differs from us.
struct PlaneReference {
  const char* name;
  int max_points;       // at most this many points at or below the plane
  bool speculative;     // may also report a vertex a little above the plane, with a negative depth
  bool deepest_depth;   // its deepest depth is always ours
  // Allowed, as fractions of the samples: fewer points than min(ours, max_points) ("missed"),
  // and points other than our deepest ones ("not_deepest").
  double missed = 0.0;
  double not_deepest = 0.0;
};

// Measured over 20,000 (seed 12) and 300,000 (seed 7) samples, gated at about twice the rate:
//   ode               some of our points, at most 4; fewer than min(ours, 4) (1.5% / 1.5%), and so
//                     not our deepest ones (1.6% / 1.4%): fixtures plane_ode_missed_vertex and
//                     plane_deep_six
//   bullet            the deepest vertex alone, and also a vertex a little above the plane (within
//                     its contact breaking threshold) with a negative depth, where we report none
//                     (2.6% / 2.4% of the samples)
//   bullet-multipoint our deepest vertex and the vertices its perturbed iterations add, at most 4:
//                     fewer than min(ours, 4) in 67% / 67% of the samples (gated at 75%: twice is
//                     past 100%), other than our deepest ones in 2.0e-4 / 3.6e-4; speculative
//                     points as Bullet's
//   mujoco            mjc_PlaneBox: our deepest vertices, at most 4 (our deepest 4 where we have 5-8:
//                     800 of 20,000 samples), never a speculative point at margin 0
const std::vector<PlaneReference> kPlaneReferences = {
    {"ode", 4, false, true, 0.03, 0.03},
    {"bullet", 1, true, true},
    {"bullet-multipoint", 4, true, true, 0.75, 8e-4},
    {"mujoco", 4, false, true},
    // dart, fcl: dBoxBox against the ground box (a box of 1e3 m under the plane), at most 4 points
    // culled by spread rather than depth: fewer than min(ours, 4) in 9.5% of the samples (1,899 of
    // 20,000, seed 12), other than our deepest in 5.0% (1,003); both detectors alike. Gated at
    // about twice.
    {"dart", 4, false, true, 0.19, 0.10},
    {"fcl", 4, false, true, 0.19, 0.10},
};

// What is wrong with a reference's set against ours, by name (see PlaneReference); empty when
// nothing is. The point checks hold for every reference: the plane's normal, inside the box up to
// half its depth, at or below the plane only where we have a point too.
std::vector<std::string> plane_mismatches(const PlaneReference& ref, const PlaneCase& c, const Manifold& own,
                                          const Manifold& theirs) {
  std::vector<std::string> found;
  Manifold penetrating;
  for (const Contact& p : theirs) {
    if ((p.normal - c.plane.normal).norm() > kUnitTolerance ||
        outside_distance(c.box, p.position) > 0.5 * std::abs(p.depth) + kRegionTolerance) {
      found.emplace_back("invalid");
    }
    if (p.depth >= 0.0) penetrating.push_back(p);
  }
  if (penetrating.size() < theirs.size() && !ref.speculative) found.emplace_back("speculative");
  if (own.empty() != penetrating.empty()) found.emplace_back("presence");
  if (own.empty() || penetrating.empty()) return found;
  if (!is_subset(penetrating, own)) found.emplace_back("not_subset");
  if (penetrating.size() > ref.max_points) found.emplace_back("too_many");
  if (ref.deepest_depth && std::abs(max_depth(penetrating) - max_depth(own)) > kDepthTolerance) {
    found.emplace_back("depth");
  }
  if (penetrating.size() < std::min(own.size(), ref.max_points)) found.emplace_back("missed");
  if (!are_deepest(penetrating, own)) found.emplace_back("not_deepest");
  return found;
}

}  // namespace

TEST_CASE("our box-plane contacts agree with ODE and Bullet on random poses", "[conformance][box_plane]") {
  for (const DetectorInfo& d : detectors()) {
    if (d.name == kOwnDetector) continue;
    INFO("detector " << d.name << " needs a row in kPlaneReferences");
    CHECK(std::any_of(kPlaneReferences.begin(), kPlaneReferences.end(),
                      [&](const PlaneReference& r) { return d.name == r.name; }));
  }
  std::mt19937_64 rng(test_seed(12));
  const int n = test_samples(kDefaultSamples);
  const DetectorInfo& ours = find_detector(kOwnDetector);
  Dumper dump;
  int touching = 0;
  // Per reference: samples showing each mismatch, and samples with a speculative point.
  std::vector<std::map<std::string, int>> counts(kPlaneReferences.size());
  for (int k = 0; k < n; ++k) {
    const PlaneCase c = random_box_on_plane(rng);
    const Manifold own = ours.box_plane(c.box, c.plane, DetectOptions{});
    if (!own.empty()) ++touching;
    for (std::size_t r = 0; r < kPlaneReferences.size(); ++r) {
      const PlaneReference& ref = kPlaneReferences[r];
      const Manifold theirs = find_detector(ref.name).box_plane(c.box, c.plane, DetectOptions{});
      std::vector<std::string> found = plane_mismatches(ref, c, own, theirs);
      std::sort(found.begin(), found.end());
      found.erase(std::unique(found.begin(), found.end()), found.end());
      for (const std::string& what : found) {
        ++counts[r][what];
        const std::string name = std::string(ref.name) + "_" + what;
        dump.box_plane(name + "_" + std::to_string(test_seed(12)) + "_" + std::to_string(k), name, c.box, c.plane);
      }
      if (std::any_of(theirs.begin(), theirs.end(), [](const Contact& p) { return p.depth < 0.0; })) {
        ++counts[r]["with_speculative"];
      }
    }
  }
  std::ostringstream s;
  s << "box-plane, " << n << " samples, " << touching << " touching:";
  for (std::size_t r = 0; r < kPlaneReferences.size(); ++r) {
    s << ' ' << kPlaneReferences[r].name << " {";
    for (const auto& [what, k] : counts[r]) s << ' ' << what << ' ' << k << ',';
    s << " }";
  }
  WARN(s.str());

  CHECK(touching > n / 2);
  for (std::size_t r = 0; r < kPlaneReferences.size(); ++r) {
    const PlaneReference& ref = kPlaneReferences[r];
    std::map<std::string, int>& found = counts[r];
    INFO(ref.name);
    // Never: a point off the convention, a speculative point from a detector that has none, a
    // contact where we have none (or none where we have one), a point that is not one of ours,
    // more points than it gives, another deepest depth where it keeps ours.
    for (const char* never : {"invalid", "speculative", "presence", "not_subset", "too_many", "depth"}) {
      INFO(never);
      CHECK(found[never] == 0);
    }
    CHECK(found["missed"] <= ref.missed * n);
    CHECK(found["not_deepest"] <= ref.not_deepest * n);
  }
}

// --- fixtures ---------------------------------------------------------------------------------

namespace {

enum class Agreement { Agree, Differ };

constexpr Agreement kAgree = Agreement::Agree;
constexpr Agreement kDiffer = Agreement::Differ;

// What one detector reports for a fixture: its point count, and whether it agrees with us (same
// normal, deepest depth and region, or no contact on both sides).
struct Seen {
  const char* detector;
  int points;
  Agreement agrees = kAgree;
};

// What each registered detector reports for a fixture under fixtures/contacts/ (box_plane_only
// detectors for box-plane fixtures only), and for a box-box disagreement what brute force says.
struct FixtureExpectation {
  const char* name;
  std::vector<Seen> seen;
  std::optional<Verdict> verdict;
};

// MuJoCo (mjc_BoxBox): 5 points for two aligned faces where we clip 4, depths often half ours
// (kDiffer), and a box-plane set that is always our deepest 4 vertices. DART's and FCL's (ports of
// dBoxBox, the ground a box): ODE's sets, capped at 4 points (yaw45_octagon: 4 of our 8).
const std::vector<FixtureExpectation> kFixtures = {
    // The foundation special cases.
    {"aligned_offset", {{"own", 4}, {"ode", 4}, {"dart", 4}, {"fcl", 4}, {"bullet", 4}, {"mujoco", 5, kDiffer}}, {}},
    {"yaw45_octagon", {{"own", 8}, {"ode", 8}, {"dart", 4}, {"fcl", 4}, {"bullet", 4}, {"mujoco", 8, kDiffer}}, {}},  // Bullet's cap: 4 of our 8
    {"crossing_edges", {{"own", 1}, {"ode", 1}, {"dart", 1}, {"fcl", 1}, {"bullet", 1, kDiffer}, {"mujoco", 1}}, {}},  // Bullet's fudge2: 2e-5 m deeper
    {"edge_on_face", {{"own", 2}, {"ode", 2}, {"dart", 2}, {"fcl", 2}, {"bullet", 2}, {"mujoco", 3, kDiffer}}, {}},
    {"vertex_on_face", {{"own", 1}, {"ode", 1}, {"dart", 1}, {"fcl", 1}, {"bullet", 1}, {"mujoco", 1, kDiffer}}, {}},
    {"separated", {{"own", 0}, {"ode", 0}, {"dart", 0}, {"fcl", 0}, {"bullet", 0}, {"mujoco", 0}}, {}},
    {"touching", {{"own", 4}, {"ode", 4}, {"dart", 4}, {"fcl", 4}, {"bullet", 4}, {"mujoco", 5, kDiffer}}, {}},
    {"deep_overlap", {{"own", 4}, {"ode", 4}, {"dart", 4}, {"fcl", 4}, {"bullet", 4}, {"mujoco", 5, kDiffer}}, {}},
    {"parallel_edges", {{"own", 4}, {"ode", 4}, {"dart", 4}, {"fcl", 4}, {"bullet", 2}, {"mujoco", 5, kDiffer}}, {}},  // Bullet merges points 7 mm apart
    {"small_on_large", {{"own", 4}, {"ode", 4}, {"dart", 4}, {"fcl", 4}, {"bullet", 4}, {"mujoco", 5, kDiffer}}, {}},
    {"plane_flat", {{"own", 4}, {"ode", 4}, {"dart", 4}, {"fcl", 4}, {"bullet", 1}, {"bullet-multipoint", 3}, {"mujoco", 4}}, {}},
    {"plane_edge", {{"own", 2}, {"ode", 2}, {"dart", 2}, {"fcl", 2}, {"bullet", 1}, {"bullet-multipoint", 2}, {"mujoco", 2}}, {}},
    {"plane_vertex", {{"own", 1}, {"ode", 1}, {"dart", 1}, {"fcl", 1}, {"bullet", 1}, {"bullet-multipoint", 1}, {"mujoco", 1}}, {}},
    {"plane_tilted", {{"own", 4}, {"ode", 4}, {"dart", 4}, {"fcl", 4}, {"bullet", 1}, {"bullet-multipoint", 3}, {"mujoco", 4}}, {}},
    // Conventions that differ by design.
    {"plane_bullet_speculative",
     {{"own", 0}, {"ode", 0}, {"dart", 0}, {"fcl", 0}, {"bullet", 1, kDiffer}, {"bullet-multipoint", 3, kDiffer}, {"mujoco", 0}}, {}},
    {"plane_deep_six", {{"own", 6}, {"ode", 4}, {"dart", 4}, {"fcl", 4}, {"bullet", 1}, {"bullet-multipoint", 1}, {"mujoco", 4}}, {}},
    {"plane_ode_missed_vertex", {{"own", 4}, {"ode", 3}, {"dart", 3}, {"fcl", 3}, {"bullet", 1}, {"bullet-multipoint", 1}, {"mujoco", 4}}, {}},
    {"bullet_merged_points", {{"own", 3}, {"ode", 3}, {"dart", 3}, {"fcl", 3}, {"bullet", 2}, {"mujoco", 3, kDiffer}}, {}},
    // Our near-face edge-edge set: the references' one edge point, then two of the face's clipped points.
    {"near_face_edge", {{"own", 3}, {"ode", 1}, {"dart", 1}, {"fcl", 1}, {"bullet", 1, kDiffer}, {"mujoco", 3, kDiffer}}, {}},  // Bullet's fudge2: 4e-6 m deeper
    {"face_edge_tie", {{"own", 3}, {"ode", 1, kDiffer}, {"dart", 1, kDiffer}, {"fcl", 1, kDiffer}, {"bullet", 1, kDiffer}, {"mujoco", 3, kDiffer}}, Verdict::BothAcceptable},
    // Where a reference is wrong.
    {"ode_deeper_edge_pair", {{"own", 1}, {"ode", 1, kDiffer}, {"dart", 1, kDiffer}, {"fcl", 1, kDiffer}, {"bullet", 1, kDiffer}, {"mujoco", 2, kDiffer}}, Verdict::OwnRight},
    // Ours: the edge point, then two clipped points of B's face 0.034 rad from its normal (near-face).
    {"ode_edge_point_outside", {{"own", 3}, {"ode", 1, kDiffer}, {"dart", 1, kDiffer}, {"fcl", 1, kDiffer}, {"bullet", 1, kDiffer}, {"mujoco", 3}}, Verdict::OwnRight},
    {"bullet_phantom_edge", {{"own", 0}, {"ode", 0}, {"dart", 0}, {"fcl", 0}, {"bullet", 1, kDiffer}, {"mujoco", 0}}, Verdict::OwnRight},
};

Agreement agreement(const Manifold& own, const Manifold& theirs) {
  if (own.empty() && theirs.empty()) return kAgree;
  if (own.empty() || theirs.empty()) return kDiffer;
  const ContactDiff d = diff_contacts(own, theirs, kRegionTolerance);
  const bool same = *d.normal_angle <= kNormalTolerance && std::abs(*d.depth_difference) <= kDepthTolerance &&
                    (d.other_tested ? d.inside_hull : true);
  double region = 0.0;
  for (const Contact& c : theirs) region = std::max(region, distance_to_region(own, own[0].normal, c.position));
  return same && region <= kRegionTolerance ? kAgree : kDiffer;
}

// Who is right, by brute force, between our set and another detector's that differs from it.
Verdict fixture_verdict(const ContactQuery& q, const Manifold& own, const Manifold& other) {
  const BoxPair p{OrientedBox::from(q.a.pose, q.a.half_extents), OrientedBox::from(q.b->pose, q.b->half_extents)};
  if (own.empty() || other.empty()) return arbitrate_presence(p, !own.empty());
  const bool face_bias = is_face(own[0].feature.kind()) != is_face(other[0].feature.kind());
  return arbitrate_normals(p, own[0].normal, other[0].normal, face_bias);
}

std::string fixture_path(const std::string& name) {
  return std::string(BOXPILE_FIXTURES_DIR) + "/contacts/" + name + ".json";
}

}  // namespace

TEST_CASE("every contact fixture is described, and each detector reports what it says", "[conformance][fixtures]") {
  std::vector<std::string> on_disk;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(BOXPILE_FIXTURES_DIR) + "/contacts")) {
    if (entry.path().extension() == ".json") on_disk.push_back(entry.path().stem().string());
  }
  for (const std::string& name : on_disk) {
    INFO("fixtures/contacts/" << name << ".json needs an entry in kFixtures");
    CHECK(std::any_of(kFixtures.begin(), kFixtures.end(), [&](const auto& f) { return name == f.name; }));
  }

  const DetectorInfo& ours = find_detector(kOwnDetector);
  for (const FixtureExpectation& f : kFixtures) {
    INFO("fixture " << f.name);
    const ContactQuery q = load_query(fixture_path(f.name));
    const Manifold own = ours.detect(q, DetectOptions{});
    std::optional<Verdict> verdict;  // against the first detector that differs from us
    for (const DetectorInfo& d : detectors()) {
      if (d.box_plane_only && q.b) continue;
      INFO("detector " << d.name);
      const auto seen = std::find_if(f.seen.begin(), f.seen.end(), [&](const Seen& e) { return d.name == e.detector; });
      REQUIRE(seen != f.seen.end());
      const Manifold m = d.detect(q, DetectOptions{});
      CHECK(m.size() == seen->points);
      const Agreement agrees = agreement(own, m);
      CHECK((agrees == seen->agrees));
      if (agrees == kDiffer && q.b && !verdict) verdict = fixture_verdict(q, own, m);
    }
    CHECK(f.seen.size() == static_cast<std::size_t>(std::count_if(detectors().begin(), detectors().end(), [&](const DetectorInfo& d) {
            return !d.box_plane_only || !q.b;
          })));
    if (f.verdict) {
      REQUIRE(verdict);
      CHECK(verdict_name(*verdict) == std::string(verdict_name(*f.verdict)));
    }
  }
}

TEST_CASE("Bullet's edge-edge depth exceeds ours by exactly its fudge2 term", "[conformance][fixtures]") {
  // crossing_edges: unit cubes, edges along x (A) and y (B), |A0 x B1| = 1, so Bullet adds
  // 1e-5 (0.5 + 0.5 + 0.5 + 0.5) = 2e-5 m to the true depth 0.01 m.
  const ContactQuery q = load_query(fixture_path("crossing_edges"));
  const OrientedBox a = OrientedBox::from(q.a.pose, q.a.half_extents);
  const OrientedBox b = OrientedBox::from(q.b->pose, q.b->half_extents);
  const Manifold bullet = find_detector("bullet").box_box(a, b, DetectOptions{});
  REQUIRE(bullet.size() == 1);
  CHECK(std::abs(bullet[0].depth - (0.01 + 2e-5)) < 1e-12);
  CHECK(std::abs(find_detector("ode").box_box(a, b, DetectOptions{})[0].depth - 0.01) < 1e-12);
}


// --- the reference engines --------------------------------------------------------------------

namespace {

using test::empty_scene;
using test::l_compound;
using test::run;
using test::states_of;
using test::unit_box;

// The linked-in references whose conventions these cases check alike (MuJoCo's differ in places:
// test_mujoco.cpp; DART's own cases are in test_dart.cpp).
constexpr std::array<const char*, 3> kReferenceEngines = {"ode", "bullet", "dart"};

}  // namespace

TEST_CASE("the engine factory builds our engine and the references and refuses other names", "[reference]") {
  const Scene scene = empty_scene(Effects{}, true);
  CHECK(make_engine("own", scene)->name() == "own");
  CHECK(make_engine("own-impulse", scene)->name() == "own-impulse");
  CHECK(make_engine("own-penalty", scene)->name() == "own-penalty");
  CHECK(make_engine("ode", scene)->name() == "ode");
  CHECK(make_engine("bullet", scene)->name() == "bullet");
  CHECK(make_engine("mujoco", scene)->name() == "mujoco");
  CHECK(make_engine("dart", scene)->name() == "dart");
  CHECK_THROWS_AS(make_engine("odee", scene), UnknownEngine);
  CHECK_THROWS_WITH(make_engine("odee", scene), Catch::Contains("unknown engine \"odee\"") &&
                                                    Catch::Contains("available: own, own-impulse, own-penalty, ode, bullet, mujoco, dart"));
}

TEST_CASE("free fall follows the semi-implicit Euler parabola, only with the gravity effect", "[reference]") {
  // Every engine updates v += g dt, then x += v dt: after n steps z = z0 - g dt^2 n (n + 1) / 2.
  for (const char* name : kReferenceEngines) {
    INFO(name);
    Scene scene = empty_scene(Effects{}, false);
    scene.bodies = {unit_box("box", Vec3(0, 0, 10))};
    const auto falling = make_engine(name, scene);
    const int n = 240;
    run(*falling, n);
    const double dt = scene.time.dt;
    const BodyState s = states_of(*falling)[0];
    CHECK(std::abs(s.position.z() - (10.0 - 9.81 * dt * dt * n * (n + 1) / 2)) < 1e-9);
    CHECK(std::abs(s.velocity.z() + 9.81 * n * dt) < 1e-9);
    CHECK(std::abs(falling->time() - 1.0) < 1e-12);

    scene.effects.gravity = false;
    const auto floating = make_engine(name, scene);
    run(*floating, n);
    CHECK(states_of(*floating)[0].position == Vec3(0, 0, 10));
  }
}

TEST_CASE("a compound's scene frame is reported, its centre of mass moves straight", "[reference]") {
  // No gravity, no torque, no gyroscopic term: the centre of mass moves at v, the angular
  // velocity stays. The reported frame sits at frame_offset from the centre of mass.
  for (const char* name : kReferenceEngines) {
    INFO(name);
    Scene scene = empty_scene(Effects{false, false, false, false, false}, false);
    BodyDesc l = l_compound("l", Vec3(1, 2, 3));
    l.velocity = Vec3(0.5, -0.2, 0.1);
    l.angular_velocity = Vec3(0.3, -0.4, 0.8);
    scene.bodies = {l};
    const RigidBody body = make_bodies(scene)[0];
    const auto engine = make_engine(name, scene);
    const BodyState start = states_of(*engine)[0];
    CHECK((start.position - Vec3(1, 2, 3)).norm() < 1e-12);
    CHECK(std::abs(start.orientation.angularDistance(Quat::Identity())) < 1e-12);
    run(*engine, 240);
    const BodyState s = states_of(*engine)[0];
    const Vec3 com = s.position - s.orientation * body.frame_offset;
    CHECK((com - (body.x + engine->time() * l.velocity)).norm() < 1e-9);
    CHECK((s.velocity - l.velocity).norm() < 1e-9);
    CHECK((s.angular_velocity - l.angular_velocity).norm() < 1e-9);
    CHECK(s.orientation.angularDistance(Quat::Identity()) > 0.5);  // it did turn
  }
}

TEST_CASE("air damping decays velocities as exp(-c t)", "[reference]") {
  for (const char* name : kReferenceEngines) {
    INFO(name);
    Scene scene = empty_scene(Effects{false, false, false, true, false}, false);
    scene.damping = Damping{0.5, 0.3};
    BodyDesc box = unit_box("box", Vec3::Zero());
    box.velocity = Vec3(2, 0, 0);
    box.angular_velocity = Vec3(0, 0, 3);
    scene.bodies = {box};
    const auto engine = make_engine(name, scene);
    run(*engine, 240);
    const BodyState s = states_of(*engine)[0];
    CHECK(std::abs(s.velocity.x() - 2.0 * std::exp(-0.5)) < 1e-9);
    CHECK(std::abs(s.angular_velocity.z() - 3.0 * std::exp(-0.3)) < 1e-9);
  }
}

TEST_CASE("materials combine per pair: a box slides down an incline at g (sin - mu cos)", "[reference]") {
  // Box friction 0.1 on a ground of 0.9: the pair's mu is sqrt(0.1 * 0.9) = 0.3 (a product rule
  // would give 0.09 and a = 4.14 m/s^2). On 30 degrees, a = 9.81 (0.5 - 0.3 cos 30) = 2.356 m/s^2.
  // ODE keeps 4 points under the sliding box and lands within 0.2%. Bullet's box-plane manifold
  // gains one point per step and drops points that slid 0.017 m, so the box rocks on 1-2 points
  // and slides 3.2% slower after 1 s: its bound is looser. DART combines by the smaller mu
  // (test_dart.cpp), so it is not among these.
  const double theta = M_PI / 6;
  const double expected = 9.81 * (std::sin(theta) - 0.3 * std::cos(theta));
  const std::map<std::string, double> tolerance = {{"ode", 0.01}, {"bullet", 0.05}};
  for (const auto& [name, tol] : tolerance) {
    INFO(name);
    Scene scene = empty_scene(Effects{true, true, false, false, false}, true);
    const Vec3 n(-std::sin(theta), 0, std::cos(theta));
    scene.ground = HalfSpace{n, 0.0};
    scene.material = Material{0.9, 0.0, std::nullopt};
    BodyDesc box = unit_box("box", 0.5 * n);
    box.frame.orientation = Quat(Eigen::AngleAxisd(-theta, Vec3::UnitY()));
    box.material = Material{0.1, 0.0, std::nullopt};
    scene.bodies = {box};
    const auto engine = make_engine(name, scene);
    run(*engine, 240);
    const double speed = states_of(*engine)[0].velocity.norm();
    INFO("speed after 1 s " << speed << ", expected " << expected);
    CHECK(std::abs(speed - expected) < tol * expected);
  }
}

TEST_CASE("five stacked cubes stand for 5 s in every reference engine", "[reference]") {
  // Measured on this system: top z - 4.5 = -1e-4 (ODE QuickStep) and -1.3e-4 (Bullet) at dt 1/240,
  // with drift below 2e-3 m: these bounds leave room for noise but fail on any collapse.
  const Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/stack_5.json");
  for (const char* name : kReferenceEngines) {
    INFO(name);
    const auto engine = make_engine(name, scene);
    const int steps = static_cast<int>(step_count(scene.time));
    run(*engine, steps);
    const BodyState top = states_of(*engine).back();
    INFO("top at " << top.position.transpose());
    CHECK(top.position.z() - 4.5 > -1e-3);
    CHECK(top.position.z() - 4.5 < 1e-4);
    CHECK(top.position.head<2>().norm() < 1e-2);
    CHECK(top.velocity.norm() < 1e-2);
    CHECK(engine->messages() == 0);
  }
}

TEST_CASE("a compound rests on the ground with its scene frame where the file put it", "[reference]") {
  const Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/compound_on_ground.json");
  for (const char* name : kReferenceEngines) {
    INFO(name);
    const auto engine = make_engine(name, scene);
    run(*engine, 480);
    const BodyState s = states_of(*engine)[0];
    INFO("frame at " << s.position.transpose());
    CHECK((s.position - Vec3(0, 0, 0.25)).norm() < 1e-3);
    CHECK(s.orientation.angularDistance(Quat::Identity()) < 1e-3);
  }
}

TEST_CASE("a fixed body holds up a box and never moves", "[reference]") {
  // No ground: a fixed 4 x 4 x 1 m slab turned 30 degrees about z (its top face at z = 0), and a
  // unit cube resting on it. The slab reports its pose and zero velocity; the cube stays up.
  Scene scene = empty_scene(Effects{true, true, false, false, false}, false);
  BodyDesc slab;
  slab.name = "slab";
  slab.fixed = true;
  slab.mass = 0.0;
  slab.boxes = {BoxShape{Vec3(2, 2, 0.5), Vec3::Zero(), Quat::Identity()}};
  slab.frame = Pose{Vec3(0, 0, -0.5), Quat(Eigen::AngleAxisd(M_PI / 6, Vec3::UnitZ()))};
  scene.bodies = {slab, unit_box("cube", Vec3(0.3, 0.2, 0.5))};
  for (const char* name : kReferenceEngines) {
    INFO(name);
    const auto engine = make_engine(name, scene);
    run(*engine, 240);
    const std::vector<BodyState> s = states_of(*engine);
    CHECK((s[0].position - slab.frame.position).norm() < 1e-12);
    CHECK(s[0].orientation.angularDistance(slab.frame.orientation) < 1e-12);
    CHECK(s[0].velocity.norm() == 0.0);
    CHECK(std::abs(s[1].position.z() - 0.5) < 1e-3);
    CHECK(s[1].velocity.norm() < 1e-2);
  }
}

TEST_CASE("engine contacts follow our convention", "[reference]") {
  // Two cubes on the ground: every contact's normal points from body_b toward body_a, the
  // ground is always body_b, and positions lie on the touching faces.
  Scene scene = empty_scene(Effects{true, true, false, false, false}, true);
  scene.bodies = {unit_box("low", Vec3(0, 0, 0.5)), unit_box("high", Vec3(0.2, 0.1, 1.5))};
  for (const char* name : kReferenceEngines) {
    INFO(name);
    const auto engine = make_engine(name, scene);
    run(*engine, 10);
    std::vector<BodyContact> contacts;
    engine->contacts(contacts);
    const std::vector<BodyState> states = states_of(*engine);
    int ground = 0, between = 0;
    for (const BodyContact& c : contacts) {
      CHECK(std::abs(c.contact.normal.norm() - 1.0) < 1e-12);
      CHECK(std::abs(c.contact.depth) < 1e-2);
      CHECK(c.body_a != kGround);
      if (c.body_b == kGround) {
        ++ground;
        CHECK((c.contact.normal - Vec3::UnitZ()).norm() < 1e-9);
        CHECK(std::abs(c.contact.position.z()) < 1e-2);
      } else {
        ++between;
        const Vec3 ab = states[static_cast<std::size_t>(c.body_a)].position -
                        states[static_cast<std::size_t>(c.body_b)].position;
        CHECK(c.contact.normal.dot(ab) > 0.9 * ab.norm());
        CHECK(std::abs(c.contact.position.z() - 1.0) < 1e-2);
      }
    }
    CHECK(ground >= 3);
    CHECK(between >= 3);
  }
}

TEST_CASE("runs repeat exactly", "[reference]") {
  // Three cubes dropped turned onto each other: contacts, friction, QuickStep's shuffled order.
  Scene scene = empty_scene(Effects{true, true, true, false, false}, true);
  for (int i = 0; i < 3; ++i) {
    BodyDesc b = unit_box("b" + std::to_string(i), Vec3(0.1 * i, -0.05 * i, 0.6 + 1.2 * i));
    b.frame.orientation = Quat(Eigen::AngleAxisd(0.3 * i, Vec3(1, 2, 3).normalized()));
    scene.bodies.push_back(b);
  }
  // DART's two runs in one process differ in the last bits (measured in the release build: positions
  // equal to 6 digits, not bitwise; the sanitizer build's happened to match): not among these.
  for (const char* name : {"ode", "bullet"}) {
    INFO(name);
    const auto first = make_engine(name, scene);
    run(*first, 480);
    const auto second = make_engine(name, scene);
    run(*second, 480);
    const std::vector<BodyState> s1 = states_of(*first), s2 = states_of(*second);
    for (std::size_t i = 0; i < s1.size(); ++i) {
      CHECK(s1[i].position == s2[i].position);
      CHECK(s1[i].orientation.coeffs() == s2[i].orientation.coeffs());
      CHECK(s1[i].velocity == s2[i].velocity);
    }
    CHECK(s1.back().position.z() < 3.0);  // the boxes fell
  }
}

// --- the diff that `boxpile contacts` prints --------------------------------------------------

namespace {

Manifold points_at(const std::vector<Vec3>& positions, const Vec3& normal, double depth) {
  Manifold m;
  for (const Vec3& p : positions) m.push_back({p, normal, depth, {}});
  return m;
}

}  // namespace

TEST_CASE("convex hulls and distances to them in the contact plane", "[contact_diff]") {
  using V2 = Eigen::Vector2d;
  const auto hull = convex_hull({V2(0, 0), V2(1, 0), V2(0.5, 0.5), V2(1, 1), V2(0, 1), V2(0.5, 0), V2(1, 1)});
  REQUIRE(hull.size() == 4);  // the interior point, the edge midpoint and the repeat are gone
  double area = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const V2& a = hull[i];
    const V2& b = hull[(i + 1) % hull.size()];
    area += 0.5 * (a.x() * b.y() - a.y() * b.x());
  }
  CHECK(std::abs(area - 1.0) < 1e-15);  // counter-clockwise: positive
  CHECK(distance_to_hull(hull, V2(0.3, 0.7)) == 0.0);
  CHECK(std::abs(distance_to_hull(hull, V2(1.5, 0.5)) - 0.5) < 1e-15);
  CHECK(std::abs(distance_to_hull(hull, V2(2, 2)) - std::sqrt(2.0)) < 1e-15);

  const auto segment = convex_hull({V2(0, 0), V2(1, 1), V2(2, 2), V2(0.5, 0.5)});
  REQUIRE(segment.size() == 2);
  CHECK(std::abs(distance_to_hull(segment, V2(1, 0)) - std::sqrt(0.5)) < 1e-15);
  CHECK(std::abs(distance_to_hull(segment, V2(3, 2)) - 1.0) < 1e-15);
  CHECK(convex_hull({V2(1, 2), V2(1, 2)}).size() == 1);
}

TEST_CASE("the contact diff: counts, normal angle, deepest depth, Hausdorff and hull", "[contact_diff]") {
  const Vec3 z = Vec3::UnitZ();
  const Manifold square = points_at({Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)}, z, 0.01);
  SECTION("one point at the centre, a tilted normal, deeper") {
    const double tilt = 1e-3;
    const Manifold centre = points_at({Vec3(0.5, 0.5, 1.2)}, Vec3(std::sin(tilt), 0, std::cos(tilt)), 0.03);
    const ContactDiff d = diff_contacts(square, centre);
    CHECK(d.base_points == 4);
    CHECK(d.other_points == 1);
    CHECK(std::abs(*d.normal_angle - tilt) < 1e-15);
    CHECK(std::abs(*d.depth_difference - 0.02) < 1e-15);
    // Measured in the plane normal to our normal: the height 1.2 does not count.
    CHECK(std::abs(*d.hausdorff - std::sqrt(0.5)) < 1e-15);
    CHECK(d.other_tested);
    CHECK(*d.hull_distance == 0.0);
    CHECK(d.inside_hull);
  }
  SECTION("a point outside our region") {
    const Manifold outside = points_at({Vec3(1.25, 0.5, 1)}, z, 0.01);
    const ContactDiff d = diff_contacts(square, outside);
    CHECK(std::abs(*d.hull_distance - 0.25) < 1e-15);
    CHECK_FALSE(d.inside_hull);
    CHECK(std::abs(distance_to_region(square, z, Vec3(1.25, 0.5, 7)) - 0.25) < 1e-15);
  }
  SECTION("the base is the smaller set: its points are tested against the other's hull") {
    const ContactDiff d = diff_contacts(points_at({Vec3(2, 0.5, 1)}, z, 0.01), square);
    CHECK_FALSE(d.other_tested);
    CHECK(std::abs(*d.hull_distance - 1.0) < 1e-15);
  }
  SECTION("no points on one side") {
    const ContactDiff d = diff_contacts(square, Manifold{});
    CHECK(d.other_points == 0);
    CHECK_FALSE(d.normal_angle);
    CHECK_FALSE(d.hausdorff);
    CHECK(d.inside_hull);
  }
}
