#include "boxpile/validation/conform/judge/pose_sampler.hpp"

#include "boxpile/validation/conform/judge/brute_force.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace boxpile {
namespace {

// Extents of the conformance suite's boxes, m: small enough to stay near unit scale, far from
// degenerate.
constexpr double kMinHalf = 0.1, kMaxHalf = 1.0;

// A's centre at `lo` to `lo + span` times the sum of both boxes' radii along a random direction from B.
// The order of the draws is the conformance suite's: its recorded rates depend on it.
BoxPair pair_at_reach(std::mt19937_64& rng, double lo, double span, double min_half, double max_half) {
  std::uniform_real_distribution<double> ext(min_half, max_half);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BoxPair p;
  p.b = make_box(Vec3(ext(rng), ext(rng), ext(rng)), Vec3::Zero(), random_rotation(rng));
  const Vec3 ha(ext(rng), ext(rng), ext(rng));
  const Quat qa = random_rotation(rng);
  const Vec3 dir = random_unit(rng);
  const OrientedBox probe = make_box(ha, Vec3::Zero(), qa);
  const double reach = probe.radius_along(dir) + p.b.radius_along(dir);
  p.a = make_box(ha, dir * reach * (lo + span * unit(rng)), qa);
  return p;
}

// Turns and moves both boxes by one random rigid motion: a pair built in a convenient frame
// keeps its geometry and loses its alignment with the world axes.
BoxPair randomly_placed(const BoxPair& p, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  const Quat q = random_rotation(rng);
  const Vec3 t(coord(rng), coord(rng), coord(rng));
  const Quat qa(p.a.axes), qb(p.b.axes);
  return {make_box(p.a.half, q * p.a.center + t, q * qa), make_box(p.b.half, q * p.b.center + t, q * qb)};
}

Vec3 random_half(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ext(kMinHalf, kMaxHalf);
  return Vec3(ext(rng), ext(rng), ext(rng));
}

// Shallow overlaps, as a fraction of the smaller box's smallest half extent.
constexpr double kMaxShallowDepth = 0.05;
// Turns about the vertical keep a horizontal edge horizontal, and turns of up to this about the
// edge's own axis keep it the lowest (or highest) feature of a box turned 45 degrees, rad.
constexpr double kMaxEdgeTilt = 0.3;

// B turned 45 degrees about x (its top is an edge along x), A turned 45 degrees about y (its
// bottom is an edge along y), each tilted a little about its edge and turned about the vertical,
// A above B with the edges crossing near their middles.
BoxPair edge_on_edge(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), tilt(-kMaxEdgeTilt, kMaxEdgeTilt);
  const double quarter = std::numbers::pi / 4;
  const Vec3 hb = random_half(rng), ha = random_half(rng);
  const Quat qb = Quat(Eigen::AngleAxisd(tilt(rng), Vec3::UnitZ())) *
                  Quat(Eigen::AngleAxisd(quarter + tilt(rng), Vec3::UnitX()));
  const Quat qa = Quat(Eigen::AngleAxisd(tilt(rng), Vec3::UnitZ())) *
                  Quat(Eigen::AngleAxisd(quarter + tilt(rng), Vec3::UnitY()));
  // The middles of B's top edge and of A's bottom edge (from A's centre); A's edge is moved onto
  // B's, shifted along both edges by up to a quarter of their half lengths, and sunk by `depth`.
  const Vec3 top_b = qb * Vec3(0, hb.y(), hb.z());
  const Vec3 bottom_a = qa * Vec3(ha.x(), 0, -ha.z());
  const double near_middle = 0.25;
  const Vec3 shift = near_middle * (hb.x() * (2 * unit(rng) - 1) * (qb * Vec3::UnitX()) +
                                    ha.y() * (2 * unit(rng) - 1) * (qa * Vec3::UnitY()));
  const double depth = kMaxShallowDepth * std::min(ha.minCoeff(), hb.minCoeff()) * unit(rng);
  const BoxPair p{make_box(ha, top_b - bottom_a + shift - depth * Vec3::UnitZ(), qa), make_box(hb, Vec3::Zero(), qb)};
  return randomly_placed(p, rng);
}

// A on top of B, both upright, A turned about the vertical only, overlapping by a shallow depth
// and shifted sideways by up to half the sum of their half extents.
BoxPair face_on_face(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  const Vec3 hb = random_half(rng), ha = random_half(rng);
  const Quat qa(Eigen::AngleAxisd(std::numbers::pi * sym(rng), Vec3::UnitZ()));
  const double depth = kMaxShallowDepth * std::min(ha.minCoeff(), hb.minCoeff()) * unit(rng);
  const double reach = make_box(ha, Vec3::Zero(), qa).radius_along(Vec3::UnitZ()) + hb.z();
  const double shift = 0.5;
  const Vec3 offset(shift * (ha.x() + hb.x()) * sym(rng) / std::sqrt(2.0),
                    shift * (ha.y() + hb.y()) * sym(rng) / std::sqrt(2.0), reach - depth);
  return randomly_placed({make_box(ha, offset, qa), make_box(hb, Vec3::Zero())}, rng);
}

// Grazing contact: a mixed pair slid along its direction until the true depth is within this
// fraction of the smaller box's smallest half extent of zero, on either side.
constexpr double kGrazingDepth = 2e-3;
// Bisection steps: the reach halves each step, 60 leave 1e-18 of it (below rounding).
constexpr int kBisectionSteps = 60;

// The true depth falls as A moves away along the direction (each axis's overlap does), so
// bisection finds the distance with the depth wanted.
BoxPair grazing_pair(std::mt19937_64& rng) {
  BoxPair p = pair_at_reach(rng, 0.4, 0.65, kMinHalf, kMaxHalf);
  std::uniform_real_distribution<double> sym(-1.0, 1.0);
  const double target = kGrazingDepth * std::min(p.a.half.minCoeff(), p.b.half.minCoeff()) * sym(rng);
  const Vec3 dir = (p.a.center - p.b.center).normalized();
  double near = 0.0, far = p.a.radius_along(dir) + p.b.radius_along(dir) + 1.0;
  for (int k = 0; k < kBisectionSteps; ++k) {
    const double mid = 0.5 * (near + far);
    p.a.center = p.b.center + mid * dir;
    (least_penetration(p.a, p.b, candidate_axes(p.a, p.b)) > target ? near : far) = mid;
  }
  p.a.center = p.b.center + near * dir;
  return p;
}

// Millimetre or decametre boxes: the conformance suite's pair scaled by 1e-2 or 1e2.
BoxPair scaled_pair(std::mt19937_64& rng) {
  std::bernoulli_distribution small(0.5);
  const double scale = small(rng) ? 1e-2 : 1e2;
  BoxPair p = pair_at_reach(rng, 0.4, 0.65, kMinHalf, kMaxHalf);
  for (OrientedBox* box : {&p.a, &p.b}) {
    box->half *= scale;
    box->center *= scale;
  }
  return p;
}

constexpr std::array<Regime, 7> kRegimes = {Regime::Mixed,    Regime::Touching, Regime::Deep, Regime::EdgeEdge,
                                            Regime::Parallel, Regime::Scaled,   Regime::Far};
constexpr std::array<std::string_view, 7> kRegimeNames = {"mixed",    "touching", "deep", "edge_edge",
                                                          "parallel", "scaled",   "far"};

}  // namespace

Quat random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Quat q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized();
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

BoxPair random_touching_pair(std::mt19937_64& rng) { return pair_at_reach(rng, 0.4, 0.65, kMinHalf, kMaxHalf); }

std::span<const Regime> all_regimes() { return kRegimes; }

std::string_view regime_name(Regime r) { return kRegimeNames[static_cast<std::size_t>(r)]; }

std::optional<Regime> regime_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kRegimes.size(); ++i) {
    if (kRegimeNames[i] == name) return kRegimes[i];
  }
  return std::nullopt;
}

BoxPair random_pair(Regime regime, std::mt19937_64& rng) {
  switch (regime) {
    case Regime::Mixed: return random_touching_pair(rng);
    case Regime::Touching: return grazing_pair(rng);
    case Regime::Deep: return pair_at_reach(rng, 0.05, 0.45, kMinHalf, kMaxHalf);
    case Regime::EdgeEdge: return edge_on_edge(rng);
    case Regime::Parallel: return face_on_face(rng);
    case Regime::Scaled: return scaled_pair(rng);
    case Regime::Far: return pair_at_reach(rng, 1.5, 1.5, kMinHalf, kMaxHalf);
  }
  return random_touching_pair(rng);
}

}  // namespace boxpile
