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

// The separation along each face axis of A (k = 0..2) and B (k = 3..5) and each edge axis
// (k = 6 + 3i + j for Ai x Bj), computed in A's frame.
struct AxisTests {
  Mat3 C;
  Mat3 absC;
  Vec3 t;  // cB - cA in A's frame
  Vec3 d;  // cB - cA in world
};

AxisTests prepare(const OrientedBox& a, const OrientedBox& b) {
  AxisTests at;
  at.C = a.axes.transpose() * b.axes;
  at.absC = at.C.cwiseAbs();
  at.d = b.center - a.center;
  at.t = a.axes.transpose() * at.d;
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

// Sutherland-Hodgman: keeps into `out` the part of `in` with sign * x[axis] <= h; new edges lie
// on side plane `plane`. In the reference frame each side plane is a coordinate bound.
void clip(const ClipPolygon& in, int axis, double sign, double h, int plane, ClipPolygon& out) {
  out.n = 0;
  for (int k = 0; k < in.n; ++k) {
    const ClipPoint& cur = in.pts[k];
    const ClipPoint& next = in.pts[(k + 1) % in.n];
    const double dc = sign * cur.p[axis] - h;
    const double dn = sign * next.p[axis] - h;
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
      const Vec3 x = cur.p + s * (next.p - cur.p);
      const int sub = cur.edge_tag < 4 ? 4 + 4 * cur.edge_tag + plane
                                       : 20 + 4 * (cur.edge_tag - 4) + plane;
      // Exiting, the polygon continues along the plane; entering, it follows cur's edge.
      out.pts[out.n++] = {x, sub, dc <= 0.0 ? 4 + plane : cur.edge_tag};
    }
  }
}

// Index of the axis (0..2) of `box` most (anti)parallel to u, with the sign of Bk . u.
int most_aligned_axis(const OrientedBox& box, const Vec3& u) {
  const Vec3 c = box.axes.transpose() * u;
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(c[i]) > std::abs(c[k])) k = i;
  return k;
}

// Face contact: the reference face of `ref` (axis `ref_axis`, outward normal m pointing toward
// `inc`) against the face of `inc` whose outward normal is most opposite to m. The incident face
// is clipped to the reference face's side planes; clip points below the reference face plane
// are contacts, depth = h_ref - m . p, placed midway between p and its projection p + depth m.
void face_contacts(const OrientedBox& ref, const OrientedBox& inc, int ref_axis, const Vec3& m,
                   bool ref_is_a, const CollisionSettings& settings, Manifold& out) {
  const int ref_face = 2 * ref_axis + (m.dot(ref.axes.col(ref_axis)) < 0.0 ? 1 : 0);

  // Incident face: outward normal s Bl with s = -sign(m . Bl), the face most opposite to m.
  const int l = most_aligned_axis(inc, m);
  const double s = -sign_of(m.dot(inc.axes.col(l)));
  const int inc_face = 2 * l + (s < 0.0 ? 1 : 0);
  const int p = (l + 1) % 3;
  const int q = (l + 2) % 3;
  const Vec3 face_center = inc.center + s * inc.half[l] * inc.axes.col(l);
  const Vec3 up = inc.half[p] * inc.axes.col(p);
  const Vec3 uq = inc.half[q] * inc.axes.col(q);

  // The reference frame: side axes u (x) and w (y), outward normal m (z), origin at ref's centre.
  const int ju = (ref_axis + 1) % 3;
  const int jw = (ref_axis + 2) % 3;
  Mat3 frame;  // rows: u, w, m
  frame.row(0) = ref.axes.col(ju).transpose();
  frame.row(1) = ref.axes.col(jw).transpose();
  frame.row(2) = m.transpose();
  const Vec3 c = frame * (face_center - ref.center);
  const Vec3 lp = frame * up;
  const Vec3 lq = frame * uq;

  // Vertices counter-clockwise in (p, q): (+,+), (-,+), (-,-), (+,-); edge k runs k -> k+1.
  ClipPolygon poly, scratch;
  poly.n = 4;
  poly.pts[0] = {c + lp + lq, 0, 0};
  poly.pts[1] = {c - lp + lq, 1, 1};
  poly.pts[2] = {c - lp - lq, 2, 2};
  poly.pts[3] = {c + lp - lq, 3, 3};

  // Side planes of the reference face, planes 0..3: x <= a_u, -x <= a_u, y <= a_w, -y <= a_w.
  clip(poly, 0, 1.0, ref.half[ju], 0, scratch);
  clip(scratch, 0, -1.0, ref.half[ju], 1, poly);
  clip(poly, 1, 1.0, ref.half[jw], 2, scratch);
  clip(scratch, 1, -1.0, ref.half[jw], 3, poly);

  const double h_ref = ref.half[ref_axis];
  const Vec3 normal = ref_is_a ? Vec3(-m) : m;  // from B toward A
  const FeatureKind kind = ref_is_a ? FeatureKind::FaceA : FeatureKind::FaceB;
  for (int k = 0; k < poly.n; ++k) {
    const ClipPoint& cp = poly.pts[k];
    const double depth = h_ref - cp.p.z();
    if (depth < -settings.margin) continue;
    const FeatureId id = ref_is_a ? FeatureId::make(kind, ref_face, inc_face, cp.sub)
                                  : FeatureId::make(kind, inc_face, ref_face, cp.sub);
    // Midway between the point (height z) and its projection on the face (height h_ref).
    const Vec3 local(cp.p.x(), cp.p.y(), cp.p.z() + 0.5 * depth);
    out.push_back({ref.center + frame.transpose() * local, normal, depth, id});
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
Edge extreme_edge(const OrientedBox& box, int i, const Vec3& e) {
  Edge edge{box.center, 4 * i};
  int bit = 0;
  for (int k = 0; k < 3; ++k) {
    if (k == i) continue;
    const double sk = sign_of(box.axes.col(k).dot(e));
    edge.mid += sk * box.half[k] * box.axes.col(k);
    if (sk > 0.0) edge.id |= 1 << bit;
    ++bit;
  }
  return edge;
}

}  // namespace

SatResult box_box_sat(const OrientedBox& a, const OrientedBox& b, double stop_above) {
  const AxisTests at = prepare(a, b);
  const Mat3& C = at.C;
  const Mat3& absC = at.absC;
  const Vec3& t = at.t;

  SatResult face;
  face.separation = -std::numeric_limits<double>::infinity();
  // A's face axes: s = |t_i| - (a_i + sum_j b_j |C_ij|).
  for (int i = 0; i < 3; ++i) {
    const double sep = std::abs(t[i]) - (a.half[i] + absC.row(i).dot(b.half));
    if (sep > face.separation) {
      face = {sep, -sign_of(t[i]) * a.axes.col(i), FeatureKind::FaceA, i, 0};
      if (sep > stop_above) return face;
    }
  }
  // B's face axes: s = |d . Bj| - (b_j + sum_i a_i |C_ij|).
  for (int j = 0; j < 3; ++j) {
    const double dj = at.d.dot(b.axes.col(j));
    const double sep = std::abs(dj) - (b.half[j] + absC.col(j).dot(a.half));
    if (sep > face.separation) {
      face = {sep, -sign_of(dj) * b.axes.col(j), FeatureKind::FaceB, 0, j};
      if (sep > stop_above) return face;
    }
  }

  // Edge axes L = Ai x Bj. In A's frame L = e_i x C_j, so with i1 = i+1, i2 = i+2 (mod 3):
  //   |L| = sqrt(C_i1j^2 + C_i2j^2),  (cB - cA) . L = t_i2 C_i1j - t_i1 C_i2j,
  //   rA = a_i1 |C_i2j| + a_i2 |C_i1j|,  rB = b_j1 |C_ij2| + b_j2 |C_ij1|.
  double edge_sep = -std::numeric_limits<double>::infinity();
  int edge_i = 0, edge_j = 0;
  double edge_len = 1.0, edge_sign = 1.0;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      // |C| <= 1, so the plain root cannot overflow (std::hypot's care costs twice the time).
      const double len = std::sqrt(C(i1, j) * C(i1, j) + C(i2, j) * C(i2, j));
      if (len < kParallelEdgeSin) continue;
      const double dl = t[i2] * C(i1, j) - t[i1] * C(i2, j);
      const double ra = a.half[i1] * absC(i2, j) + a.half[i2] * absC(i1, j);
      const double rb = b.half[j1] * absC(i, j2) + b.half[j2] * absC(i, j1);
      const double sep = (std::abs(dl) - ra - rb) / len;
      if (sep > edge_sep) {
        edge_sep = sep;
        edge_i = i;
        edge_j = j;
        edge_len = len;
        edge_sign = -sign_of(dl);
        if (sep > stop_above) break;
      }
    }
    if (edge_sep > stop_above) break;
  }

  const double scale = std::max(a.half.maxCoeff(), b.half.maxCoeff());
  const double bias = kFaceBiasRelative * std::abs(face.separation) + kFaceBiasAbsolute * scale;
  if (!(edge_sep > face.separation + bias)) return face;
  const Vec3 axis = a.axes.col(edge_i).cross(b.axes.col(edge_j)) / edge_len;
  return {edge_sep, edge_sign * axis, FeatureKind::EdgeEdge, edge_i, edge_j};
}

void collide_box_box(const OrientedBox& a, const OrientedBox& b, const CollisionSettings& settings,
                     Manifold& out) {
  out.clear();
  const SatResult sat = box_box_sat(a, b, settings.margin);
  if (sat.separation > settings.margin) return;

  switch (sat.kind) {
    case FeatureKind::FaceA:
      face_contacts(a, b, sat.axis_a, -sat.normal, /*ref_is_a=*/true, settings, out);
      break;
    case FeatureKind::FaceB:
      face_contacts(b, a, sat.axis_b, sat.normal, /*ref_is_a=*/false, settings, out);
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
      break;
    }
    case FeatureKind::Plane:
      break;  // not produced by the box-box test
  }

  if (settings.reduce_to_four) reduce_to_four(out);
}

}  // namespace boxpile
