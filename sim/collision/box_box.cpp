// Box-box contacts by the separating-axis test, then face clipping or an edge-edge point.
//
// Notation: box A has centre cA, unit axes A0, A1, A2 and half extents a; box B likewise with b.
// C = A^T B holds C_ij = Ai . Bj, and t = A^T (cB - cA) is B's centre in A's frame. For a unit
// axis L the projected radii are rA(L) = sum_i a_i |Ai . L|, rB(L) = sum_j b_j |Bj . L|, and the
// boxes are separated along L by s(L) = |(cB - cA) . L| - rA(L) - rB(L) (Eberly, "Game Physics",
// 2nd ed., sec. 5.3, Table 5.1). The 15 candidate axes are A's face normals, B's, and the nine
// edge directions Ai x Bj. If s(L) > 0 for any L the boxes are apart; otherwise the axis with the
// largest s (least penetration) is the contact normal and -s is the depth (Erleben's thesis,
// sec. 9.1, pp. 178-183).
#include "boxpile/sim/collision/box_box.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "boxpile/sim/collision/reduce.hpp"

namespace boxpile {
namespace {

// Edge pairs with |Ai x Bj| = sin(angle) below this are treated as parallel and their axis is
// skipped: the cross product is then (nearly) a face normal already tested, and normalising a
// near-zero vector would turn rounding noise into a false axis.
constexpr double kParallelEdgeSin = 1e-6;

// Faces win over edges on near-ties: an edge axis is taken only when it separates more than the
// best face axis by this fraction of the face's depth plus an absolute part scaled by box size.
// This keeps a resting stack on its 4-point face contacts instead of flickering to one-point edge
// contacts from frame to frame (frame coherence), at the price of a face depth at most 5% deeper
// than the exact least penetration in such ties.
constexpr double kFaceBiasRelative = 0.05;
constexpr double kFaceBiasAbsolute = 1e-6;  // times the largest half extent of the two boxes

inline double sign_of(double x) { return x < 0.0 ? -1.0 : 1.0; }

// Whether num / sqrt(len2) > bar (len2 > 0), without the root and without a branch.
inline bool exceeds(double num, double len2, double bar) {
  const double num2 = num * num, bar2_len2 = bar * bar * len2;
  return bar >= 0.0 ? (num > 0.0) & (num2 > bar2_len2) : (num >= 0.0) | (num2 < bar2_len2);
}

// The separation along each face axis of A (k = 0..2) and B (k = 3..5) and each edge axis
// (k = 6 + 3i + j for Ai x Bj), computed in A's frame.
struct AxisTests {
  Mat3 C;
  Vec3 t;  // cB - cA in A's frame
  Vec3 d;  // cB - cA in world
};

// Scalar dot products: Eigen's packet product of two 3x3 matrices costs more at this size.
//
// AxisTests must stay in registers. The loops over axes here and in the test are unrolled
// (#pragma GCC unroll 3) so that every index into it is a constant before the compiler's scalar
// replacement runs, and nothing indexes it by a variable (the best face's centre offset comes
// from a copy per face axis, the incident cosines are recomputed from the axes). Otherwise the
// struct lives in memory, its entries are written one by one, and the vectorised test reads two
// of them back as one pair: a stalled store-to-load forward, some 10 ns per query (perf showed
// two of them).
inline AxisTests prepare(const OrientedBox& a, const OrientedBox& b) {
  AxisTests at;
#pragma GCC unroll 3
  for (int j = 0; j < 3; ++j)
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) at.C(i, j) = a.axes.col(i).dot(b.axes.col(j));
  at.d = b.center - a.center;
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) at.t[i] = a.axes.col(i).dot(at.d);
  return at;
}

// A vertex or clip point of the incident face in the reference face's frame (x, y along its
// two side axes, z along its outward normal, origin at the reference box's centre), with the id
// of the feature that made it.
struct ClipPoint {
  Vec3 p;
  int sub;       // see FeatureId: 0..3 vertex, 4 + 4e + p edge crossing, 20 + 4q + p plane corner
  int edge_tag;  // the edge from this point to the next: 0..3 incident edge, 4 + p side plane p
};

// A polygon of at most 8 points: a quadrilateral clipped by four planes.
struct ClipPolygon {
  std::array<ClipPoint, 8> pts;
  int n = 0;
};

// Sutherland-Hodgman: keeps into `out` the part of `in` whose signed distances `dist` beyond
// side plane `plane` are <= 0; new edges lie on that plane.
void clip(const ClipPolygon& in, const std::array<double, 8>& dist, int plane, ClipPolygon& out) {
  out.n = 0;
  for (int k = 0; k < in.n; ++k) {
    const int k_next = k + 1 < in.n ? k + 1 : 0;  // no integer division
    const ClipPoint& cur = in.pts[k];
    const double dc = dist[k];
    const double dn = dist[k_next];
    if (dc <= 0.0) {
      // The edge leaving cur keeps its tag, unless cur lies on the plane and the polygon leaves
      // along it, or exits through it below.
      out.pts[out.n++] = cur;
      if (dc == 0.0 && dn > 0.0) out.pts[out.n - 1].edge_tag = 4 + plane;
    }
    // A crossing strictly between the two points; a point lying on the plane is itself kept
    // (once) and makes no second, identical crossing.
    if ((dc < 0.0 && dn > 0.0) || (dc > 0.0 && dn < 0.0)) {
      const double s = dc / (dc - dn);
      const Vec3 x = cur.p + s * (in.pts[k_next].p - cur.p);
      const int sub = cur.edge_tag < 4 ? 4 + 4 * cur.edge_tag + plane
                                       : 20 + 4 * (cur.edge_tag - 4) + plane;
      // Exiting, the polygon continues along the plane; entering, it follows cur's edge.
      out.pts[out.n++] = {x, sub, dc <= 0.0 ? 4 + plane : cur.edge_tag};
    }
  }
}

// Clips `*cur` by the side plane sign * x[axis] <= h (in the reference frame each side plane is a
// coordinate bound) into `*spare` and swaps the two, or leaves both alone when no point lies
// outside (the clip would copy the polygon and its tags unchanged). Each point's distance beyond
// the plane is computed once, for both.
void clip_side(ClipPolygon*& cur, ClipPolygon*& spare, int axis, double sign, double h, int plane) {
  std::array<double, 8> dist;
  bool any_outside = false;
  for (int k = 0; k < cur->n; ++k) {
    dist[k] = sign * cur->pts[k].p[axis] - h;
    any_outside |= dist[k] > 0.0;
  }
  if (!any_outside) return;
  clip(*cur, dist, plane, *spare);
  std::swap(cur, spare);
}

// Face contact: the reference face of `ref` (axis `ref_axis`, outward normal m pointing toward
// `inc`) against the face of `inc` whose outward normal is most opposite to m. `cos_inc` holds
// I_k . R_ref_axis for inc's axes I_k (a row or column of C, see face_manifold). The
// incident face is clipped to the reference face's side planes; clip points below the reference
// face plane are contacts, depth = h_ref - m . p, placed midway between p and its projection
// p + depth m.
void face_contacts(const OrientedBox& ref, const OrientedBox& inc, const Vec3& cos_inc, int ref_axis,
                   const Vec3& m, bool ref_is_a, const CollisionSettings& settings, Manifold& out) {
  // m = sgn * ref axis: the reference face is on the positive (sgn = 1) or negative side.
  const double sgn = sign_of(m.dot(ref.axes.col(ref_axis)));
  const int ref_face = 2 * ref_axis + (sgn < 0.0 ? 1 : 0);

  // Incident face: the axis l of inc most (anti)parallel to m, m . I_k = sgn cos_inc[k]; its
  // outward normal s I_l with s = -sign(m . I_l), the face most opposite to m.
  int l = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(cos_inc[k]) > std::abs(cos_inc[l])) l = k;
  const double s = -sign_of(sgn * cos_inc[l]);
  const int inc_face = 2 * l + (s < 0.0 ? 1 : 0);
  const int p = (l + 1) % 3;
  const int q = (l + 2) % 3;

  // The face frame: side axes u (x) and w (y) of ref, outward normal m (z), origin at ref's
  // centre. The incident face's centre and half edges are mapped from world coordinates (the
  // same numbers whichever box is the reference).
  const int ju = (ref_axis + 1) % 3;
  const int jw = (ref_axis + 2) % 3;
  Mat3 frame;  // rows: u, w, m
  frame.row(0) = ref.axes.col(ju).transpose();
  frame.row(1) = ref.axes.col(jw).transpose();
  frame.row(2) = m.transpose();
  const Vec3 c = frame * (inc.center + s * inc.half[l] * inc.axes.col(l) - ref.center);
  const Vec3 lp = frame * (inc.half[p] * inc.axes.col(p));
  const Vec3 lq = frame * (inc.half[q] * inc.axes.col(q));

  // Vertices counter-clockwise in (p, q): (+,+), (-,+), (-,-), (+,-); edge k runs k -> k+1.
  ClipPolygon first, second;
  ClipPolygon* poly = &first;
  ClipPolygon* spare = &second;
  poly->n = 4;
  poly->pts[0] = {c + lp + lq, 0, 0};
  poly->pts[1] = {c - lp + lq, 1, 1};
  poly->pts[2] = {c - lp - lq, 2, 2};
  poly->pts[3] = {c + lp - lq, 3, 3};

  // Side planes of the reference face, planes 0..3: x <= a_u, -x <= a_u, y <= a_w, -y <= a_w.
  clip_side(poly, spare, 0, 1.0, ref.half[ju], 0);
  clip_side(poly, spare, 0, -1.0, ref.half[ju], 1);
  clip_side(poly, spare, 1, 1.0, ref.half[jw], 2);
  clip_side(poly, spare, 1, -1.0, ref.half[jw], 3);

  const double h_ref = ref.half[ref_axis];
  const Vec3 normal = ref_is_a ? Vec3(-m) : m;  // from B toward A
  const FeatureKind kind = ref_is_a ? FeatureKind::FaceA : FeatureKind::FaceB;
  for (int k = 0; k < poly->n; ++k) {
    const ClipPoint& cp = poly->pts[k];
    const double depth = h_ref - cp.p.z();
    if (depth < -settings.margin) continue;
    const FeatureId id = ref_is_a ? FeatureId::make(kind, ref_face, inc_face, cp.sub)
                                  : FeatureId::make(kind, inc_face, ref_face, cp.sub);
    // Midway between the point (height z) and its projection on the face (height h_ref).
    const Vec3 local(cp.p.x(), cp.p.y(), cp.p.z() + 0.5 * depth);
    const Vec3 position = ref.center + frame.transpose() * local;
    out.push_back({position, normal, depth, id});
  }
}

// Closest points of segments p + s u (|s| <= hu) and q + t v (|t| <= hv), u and v unit and not
// parallel: the unclamped line solution, then each parameter clamped with the other recomputed.
void closest_points(const Vec3& p, const Vec3& u, double hu, const Vec3& q, const Vec3& v,
                    double hv, Vec3& on_p, Vec3& on_q) {
  const Vec3 w = p - q;
  const double uv = u.dot(v);
  const double denom = 1.0 - uv * uv;  // > 0: parallel edges never reach here
  double s = (uv * v.dot(w) - u.dot(w)) / denom;
  s = std::clamp(s, -hu, hu);
  double t = std::clamp(v.dot(w + s * u), -hv, hv);
  s = std::clamp(u.dot(q + t * v - p), -hu, hu);
  on_p = p + s * u;
  on_q = q + t * v;
}

// The edge of `box` parallel to axis i that is extreme along direction e (ties to the positive
// side), with its id 4i + corner.
struct Edge {
  Vec3 mid;
  int id;
};
// The other two axes are taken in increasing order (the order of the corner bits, and of the sum).
inline Edge extreme_edge(const OrientedBox& box, int i, const Vec3& e) {
  const std::array<int, 2> others{i == 0 ? 1 : 0, i == 2 ? 1 : 2};
  Edge edge{box.center, 4 * i};
  for (int bit = 0; bit < 2; ++bit) {
    const int k = others[bit];
    const double sk = sign_of(box.axes.col(k).dot(e));
    edge.mid += sk * box.half[k] * box.axes.col(k);
    edge.id |= static_cast<int>(sk > 0.0) << bit;
  }
  return edge;
}

}  // namespace

namespace {

// Inlined into its two callers: the matrices of `prepare` then stay in registers instead of being
// stored and reloaded across a call (a stalled store-to-load forward at every query). The best face
// axis, found before the edge axes, is also written to `best_face_out` when given (the near-face
// edge-edge contacts need it, without a second pass over the faces).
[[gnu::always_inline]] inline SatResult separating_axis_test(const OrientedBox& a,
                                                             const OrientedBox& b,
                                                             const AxisTests& at, double stop_above,
                                                             SatResult* best_face_out = nullptr) {
  const Mat3& C = at.C;
  // |C_ij| where it is used: a stored |C| was again written in pairs and read at other offsets.
  const auto absC = [&C](int i, int j) { return std::abs(C(i, j)); };
  const Vec3& t = at.t;

  // Face axes, k = 0..2 for A's and 3..5 for B's.
  //   A's: s = |t_i| - (a_i + sum_j b_j |C_ij|);  B's: s = |d . Bj| - (b_j + sum_i a_i |C_ij|).
  // Rows and columns of |C| by scalars, each summed in the order Eigen's dot product of three
  // terms sums them (the same bits as before).
  std::array<double, 6> face_sep;
  std::array<double, 6> face_offset;  // (cB - cA) along the axis: t_i, then d . Bj
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
    face_offset[i] = t[i];
    const double rb = absC(i, 0) * b.half[0] + (absC(i, 1) * b.half[1] + absC(i, 2) * b.half[2]);
    face_sep[i] = std::abs(t[i]) - (a.half[i] + rb);
  }
#pragma GCC unroll 3
  for (int j = 0; j < 3; ++j) {
    const double offset_b = at.d.dot(b.axes.col(j));
    face_offset[3 + j] = offset_b;
    const double ra = (absC(0, j) * a.half[0] + absC(1, j) * a.half[1]) + absC(2, j) * a.half[2];
    face_sep[3 + j] = std::abs(offset_b) - (b.half[j] + ra);
  }
  // The largest separation, the first on a tie (A's faces before B's), chosen by selects and a
  // maximum: which face wins is data, and a branch per face mispredicted. All six are compared
  // even past `stop_above` (the boxes are apart then, and the largest is still a lower bound).
  int best_face = 0;
  double best_sep = face_sep[0];
#pragma GCC unroll 5
  for (int k = 1; k < 6; ++k) {
    best_face = face_sep[k] > best_sep ? k : best_face;
    best_sep = std::max(best_sep, face_sep[k]);
  }
  const bool on_a = best_face < 3;
  const int face_axis = on_a ? best_face : best_face - 3;
  const Mat3& axes = on_a ? a.axes : b.axes;
  SatResult face;
  face.separation = best_sep;
  face.normal = -sign_of(face_offset[best_face]) * axes.col(face_axis);
  face.kind = on_a ? FeatureKind::FaceA : FeatureKind::FaceB;
  face.axis_a = on_a ? face_axis : 0;
  face.axis_b = on_a ? 0 : face_axis;
  if (best_face_out) *best_face_out = face;
  if (face.separation > stop_above) return face;

  // Edge axes L = Ai x Bj, k = 3i + j. In A's frame L = e_i x C_j, so with i1 = i+1, i2 = i+2
  // (mod 3):
  //   |L| = sqrt(C_i1j^2 + C_i2j^2),  (cB - cA) . L = t_i2 C_i1j - t_i1 C_i2j,
  //   rA = a_i1 |C_i2j| + a_i2 |C_i1j|,  rB = b_j1 |C_ij2| + b_j2 |C_ij1|.
  // An edge axis matters only if it separates more than the face axis plus the face bias (it
  // then wins) or more than `stop_above` (the test stops). All nine numerators
  // num = |(cB - cA) . L| - rA - rB and squared lengths are computed first, unrolled so that
  // every index is a constant, and each axis compared with that bar by squares (num / |L| > bar)
  // without a branch: a bit per axis that can matter. Only those (rarely more than one) take the
  // root and the division, in axis order. The bar only rises during that scan, so an axis below
  // it at the start can never matter later.
  const double scale = std::max(a.half.maxCoeff(), b.half.maxCoeff());
  const double bias = kFaceBiasRelative * std::abs(face.separation) + kFaceBiasAbsolute * scale;
  const double edge_bar = std::min(face.separation + bias, stop_above);
  std::array<double, 9> dl, num, len2;
  unsigned candidates = 0;
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
#pragma GCC unroll 3
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const int k = 3 * i + j;
      len2[k] = C(i1, j) * C(i1, j) + C(i2, j) * C(i2, j);
      dl[k] = t[i2] * C(i1, j) - t[i1] * C(i2, j);
      const double ra = a.half[i1] * absC(i2, j) + a.half[i2] * absC(i1, j);
      const double rb = b.half[j1] * absC(i, j2) + b.half[j2] * absC(i, j1);
      num[k] = std::abs(dl[k]) - ra - rb;
      const bool edges_cross = len2[k] >= kParallelEdgeSin * kParallelEdgeSin;
      candidates |= static_cast<unsigned>(edges_cross & exceeds(num[k], len2[k], edge_bar)) << k;
    }
  }

  double edge_sep = -std::numeric_limits<double>::infinity();
  int edge_k = -1;
  double edge_len = 1.0;
  for (; candidates != 0; candidates &= candidates - 1) {
    const int k = std::countr_zero(candidates);
    if (!exceeds(num[k], len2[k], std::max(edge_bar, edge_sep))) continue;
    // |C| <= 1, so the plain root cannot overflow (std::hypot's care costs twice the time).
    edge_len = std::sqrt(len2[k]);
    edge_sep = num[k] / edge_len;
    edge_k = k;
    if (edge_sep > stop_above) break;
  }

  if (!(edge_sep > face.separation + bias)) return face;
  const int edge_i = edge_k / 3, edge_j = edge_k % 3;
  const Vec3 axis = a.axes.col(edge_i).cross(b.axes.col(edge_j)) / edge_len;
  return {edge_sep, -sign_of(dl[edge_k]) * axis, FeatureKind::EdgeEdge, edge_i, edge_j};
}

}  // namespace

SatResult box_box_sat(const OrientedBox& a, const OrientedBox& b, double stop_above) {
  return separating_axis_test(a, b, prepare(a, b), stop_above);
}

namespace {
// The clipped points of the reference face `sat` names (FaceA or FaceB). The incident box's
// cosines I_k . R to the reference axis R, a row or a column of C, are recomputed from the axes by
// the same dot products (the same bits): read from C by a variable index they would keep C in
// memory (see prepare).
void face_manifold(const OrientedBox& a, const OrientedBox& b, const SatResult& sat, const CollisionSettings& settings,
                   Manifold& out) {
  Vec3 cos_inc;
  if (sat.kind == FeatureKind::FaceA) {
    for (int k = 0; k < 3; ++k) cos_inc[k] = a.axes.col(sat.axis_a).dot(b.axes.col(k));
    face_contacts(a, b, cos_inc, sat.axis_a, -sat.normal, /*ref_is_a=*/true, settings, out);
  } else {
    for (int k = 0; k < 3; ++k) cos_inc[k] = a.axes.col(k).dot(b.axes.col(sat.axis_b));
    face_contacts(b, a, cos_inc, sat.axis_b, sat.normal, /*ref_is_a=*/false, settings, out);
  }
}

// A clipped face point this close to the edge-edge point, as a fraction of the smallest edge of
// the two boxes, is the same corner: the clipped polygon has a vertex where the incident edge
// crosses the reference face's side, which is the edge-edge crossing itself. A second point there
// holds nothing more and slows the resting passes (pile_100's steps cost 15% more with it).
constexpr double kSameCornerPerEdge = 0.01;

// Beside the edge-edge point (out[0]) of two nearly aligned boxes, the clipped points of the best
// face (kEdgeNearFaceCos) but the one at the edge point's corner, in the edge point's normal: each
// point's depth is its gap along that normal (the face depth times the cosine between the
// normals), never more than the edge point's, the pair's penetration along it.
// `face` is the best face axis the separating-axis test met on its way to the edge axis.
void add_near_face_points(const OrientedBox& a, const OrientedBox& b, const SatResult& sat,
                          const SatResult& face, const CollisionSettings& settings, Manifold& out) {
  const double cos_nf = std::abs(face.normal.dot(sat.normal));
  if (cos_nf <= kEdgeNearFaceCos) return;
  Manifold face_points;
  face_manifold(a, b, face, settings, face_points);
  const Contact edge = out[0];
  const double same_corner = kSameCornerPerEdge * 2.0 * std::min(a.half.minCoeff(), b.half.minCoeff());
  for (int i = 0; i < face_points.size() && out.size() < kMaxManifoldPoints; ++i) {
    Contact c = face_points[i];
    if ((c.position - edge.position).squaredNorm() < same_corner * same_corner) continue;
    c.normal = sat.normal;  // one normal per manifold
    c.depth = std::min(c.depth * cos_nf, edge.depth);
    out.push_back(c);
  }
}
}  // namespace

void collide_box_box(const OrientedBox& a, const OrientedBox& b, const CollisionSettings& settings,
                     Manifold& out) {
  out.clear();
  const AxisTests at = prepare(a, b);
  SatResult best_face;
  const SatResult sat = separating_axis_test(a, b, at, settings.margin, &best_face);
  if (sat.separation > settings.margin) return;

  switch (sat.kind) {
    case FeatureKind::FaceA:
    case FeatureKind::FaceB:
      face_manifold(a, b, sat, settings, out);
      break;
    case FeatureKind::EdgeEdge: {
      // A's edge along Ai extreme toward B (along -n), B's edge along Bj extreme toward A (+n).
      const Edge ea = extreme_edge(a, sat.axis_a, -sat.normal);
      const Edge eb = extreme_edge(b, sat.axis_b, sat.normal);
      Vec3 pa, pb;
      closest_points(ea.mid, a.axes.col(sat.axis_a), a.half[sat.axis_a], eb.mid,
                     b.axes.col(sat.axis_b), b.half[sat.axis_b], pa, pb);
      out.push_back({0.5 * (pa + pb), sat.normal, -sat.separation,
                     FeatureId::make(FeatureKind::EdgeEdge, ea.id, eb.id, 0)});
      add_near_face_points(a, b, sat, best_face, settings, out);
      break;
    }
    case FeatureKind::Plane:
      break;  // not produced by the box-box test
  }

  if (settings.reduce_to_four) reduce_to_four(out);
}

}  // namespace boxpile
