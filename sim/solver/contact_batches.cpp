#include "boxpile/sim/solver/contact_batches.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

// The four-lane vectors are passed between inlined helpers only; GCC and Clang note that passing
// them by value to a function compiled without AVX would change the calling convention.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace boxpile {

namespace {

using d4 = double __attribute__((vector_size(32)));
using i4 = std::int64_t __attribute__((vector_size(32)));

struct V3 {
  d4 x, y, z;
};

[[gnu::always_inline]] inline d4 load(const double* p) {
  d4 r;
  std::memcpy(&r, p, sizeof r);
  return r;
}
[[gnu::always_inline]] inline i4 load_mask(const std::int64_t* p) {
  i4 r;
  std::memcpy(&r, p, sizeof r);
  return r;
}
[[gnu::always_inline]] inline void store(double* p, d4 v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline V3 load3(const double (*p)[kBatchLanes]) { return {load(p[0]), load(p[1]), load(p[2])}; }
[[gnu::always_inline]] inline d4 splat(double x) { return d4{x, x, x, x}; }
// Lane by lane, a where m is all ones, b where it is zero (m a comparison's result).
[[gnu::always_inline]] inline d4 select(i4 m, d4 a, d4 b) { return (d4)((m & (i4)a) | (~m & (i4)b)); }
[[gnu::always_inline]] inline V3 select(i4 m, const V3& a, const V3& b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}
// Comparisons, lane by lane, as masks (cast: GCC and Clang name the result's element type apart).
[[gnu::always_inline]] inline i4 lt(d4 a, d4 b) { return (i4)(a < b); }
[[gnu::always_inline]] inline i4 le(d4 a, d4 b) { return (i4)(a <= b); }
[[gnu::always_inline]] inline i4 eq(d4 a, d4 b) { return (i4)(a == b); }
// std::max(a, b) and std::min(a, b), lane by lane.
[[gnu::always_inline]] inline d4 max(d4 a, d4 b) { return select(lt(a, b), b, a); }
[[gnu::always_inline]] inline d4 min(d4 a, d4 b) { return select(lt(b, a), b, a); }
[[gnu::always_inline]] inline d4 dot(const V3& a, const V3& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
[[gnu::always_inline]] inline V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
[[gnu::always_inline]] inline V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
[[gnu::always_inline]] inline V3 operator*(d4 s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
// A row-major 3x3 matrix (9 fields) times v.
[[gnu::always_inline]] inline V3 product(const double (*m)[kBatchLanes], const V3& v) {
  return {(load(m[0]) * v.x + load(m[1]) * v.y) + load(m[2]) * v.z,
          (load(m[3]) * v.x + load(m[4]) * v.y) + load(m[5]) * v.z,
          (load(m[6]) * v.x + load(m[7]) * v.y) + load(m[8]) * v.z};
}
// A symmetric 3x3 matrix given by its upper triangle (6 fields) times v.
[[gnu::always_inline]] inline V3 symmetric_product(const double (*m)[kBatchLanes], const V3& v) {
  const d4 m00 = load(m[0]), m01 = load(m[1]), m02 = load(m[2]), m11 = load(m[3]), m12 = load(m[4]), m22 = load(m[5]);
  return {(m00 * v.x + m01 * v.y) + m02 * v.z, (m01 * v.x + m11 * v.y) + m12 * v.z, (m02 * v.x + m12 * v.y) + m22 * v.z};
}
[[gnu::always_inline]] inline bool any(i4 m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }
[[gnu::always_inline]] inline std::uint64_t count(i4 minus_counts) {
  return static_cast<std::uint64_t>(-(minus_counts[0] + minus_counts[1] + minus_counts[2] + minus_counts[3]));
}

// Rows r0..r3 (four values of one body each) to columns (one value of the four bodies each); its
// own inverse.
[[gnu::always_inline]] inline void transpose(d4& r0, d4& r1, d4& r2, d4& r3) {
  const d4 t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6), t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
  const d4 t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6), t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
  r0 = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  r1 = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  r2 = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  r3 = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// Four bodies' velocities, lane by lane.
struct BodyLanes {
  V3 v, omega;
};

static_assert(sizeof(BatchVelocity) == 2 * sizeof(d4));

[[gnu::always_inline]] inline BodyLanes gather(const BatchVelocities& vel, const int* body) {
  d4 q[2][kBatchLanes];  // q[half][lane]: the lane's body's doubles 4 half .. 4 half + 3
  for (int l = 0; l < kBatchLanes; ++l) {
    const char* from = reinterpret_cast<const char*>(&vel.at(body[l]));
    std::memcpy(&q[0][l], from, sizeof(d4));
    std::memcpy(&q[1][l], from + sizeof(d4), sizeof(d4));
  }
  transpose(q[0][0], q[0][1], q[0][2], q[0][3]);
  transpose(q[1][0], q[1][1], q[1][2], q[1][3]);
  // Now q[h][m] holds double 4 h + m of every lane: v x y z, omega x | omega y z.
  return {{q[0][0], q[0][1], q[0][2]}, {q[0][3], q[1][0], q[1][1]}};
}

[[gnu::always_inline]] inline void scatter(BatchVelocities& vel, const int* body, const BodyLanes& s, i4 write) {
  const d4 zero = splat(0.0);
  d4 q[2][kBatchLanes] = {{s.v.x, s.v.y, s.v.z, s.omega.x}, {s.omega.y, s.omega.z, zero, zero}};
  transpose(q[0][0], q[0][1], q[0][2], q[0][3]);
  transpose(q[1][0], q[1][1], q[1][2], q[1][3]);
  for (int l = 0; l < kBatchLanes; ++l) {
    if (!write[l]) continue;
    char* to = reinterpret_cast<char*>(&vel.at(body[l]));
    std::memcpy(to, &q[0][l], sizeof(d4));
    std::memcpy(to + sizeof(d4), &q[1][l], sizeof(d4));
  }
}

[[gnu::always_inline]] inline double pass_lanes(std::span<ContactBatch> batches, BatchVelocities& vel, double e,
                                                ImpulseCounters& counters) {
  const d4 zero = splat(0.0);
  d4 residual = zero;
  i4 impulses = {}, frictional_updates = {}, sliding = {};  // minus the counts, lane by lane
  for (ContactBatch& c : batches) {
    const i4 real = load_mask(c.real);
    const i4 frictional = load_mask(c.frictional);  // zero in empty lanes
    BodyLanes A = gather(vel, c.a), B = gather(vel, c.b);
    const V3 n = load3(c.n);
    // The velocity of A's point relative to B's (a ground lane's B side is zero: W and velocities).
    const V3 u = (A.v + product(c.Wa, A.omega)) - (B.v + product(c.Wb, B.omega));
    const d4 un = dot(n, u);
    const d4 gap_speed = load(c.gap_speed);
    // allow_gap(c, 0, dt) - n . u, the contact loop's residual.
    residual = max(residual, select(real, min(zero, gap_speed) - un, zero));
    // The target: allow_gap(c, -e u_n(start) or 0, dt).
    const d4 start_un = load(c.start_un);
    const d4 target = min(select(lt(start_un, zero), splat(-e) * start_un, zero), gap_speed);

    const V3 J_old = load3(c.acc);
    const V3 rhs = target * n - u;
    // Sticking: the total impulse that brings the point to u_n = target with no sliding.
    const V3 J_stick = J_old + symmetric_product(c.Kinv, rhs);
    const d4 jn = dot(J_stick, n);
    const V3 jt = J_stick - jn * n;
    const d4 mu = load(c.friction);
    const d4 limit = mu * jn;
    const i4 sticks = le(zero, jn) & le(dot(jt, jt), limit * limit);
    V3 J = J_stick;
    const i4 slides = frictional & ~sticks;
    if (any(slides)) {
      const i4 slide_zero = load_mask(c.slide_zero);
      // Not sliding when the phase began: the sticking impulse clamped radially onto the cone.
      const d4 jn_clamped = max(zero, jn);
      d4 scale = zero;
      const i4 radial = slides & slide_zero;
      if (any(radial)) {
        for (int l = 0; l < kBatchLanes; ++l) {
          if (!radial[l]) continue;
          const double norm = std::sqrt(jt.x[l] * jt.x[l] + jt.y[l] * jt.y[l] + jt.z[l] * jt.z[l]);
          scale[l] = jn_clamped[l] > 0.0 && norm > 0.0 ? std::min(1.0, mu[l] * jn_clamped[l] / norm) : 0.0;
        }
      }
      const V3 J_radial = jn_clamped * n + scale * jt;
      // Sliding along the phase's direction t: J = J_n (n - mu t), J_n set by the target.
      const d4 denom = load(c.denom);
      const d4 jn_slide =
          select(lt(zero, denom), max(zero, ((target - un) + dot(load3(c.Kn), J_old)) / denom), zero);
      const V3 J_slide = jn_slide * load3(c.dir);
      J = select(sticks, J_stick, select(slide_zero, J_radial, J_slide));
    }
    const i4 frictionless = real & ~frictional;
    if (any(frictionless)) {
      const d4 jn_old = dot(J_old, n);
      const d4 jn_new = max(zero, jn_old + (target - un) / load(c.nKn));
      J = select(frictional, J, jn_new * n);
    }
    J = select(real, J, J_old);
    store(c.acc[0], J.x);
    store(c.acc[1], J.y);
    store(c.acc[2], J.z);
    impulses += real;
    frictional_updates += frictional;
    sliding += slides;

    const V3 j = J - J_old;
    const i4 nonzero = ~(eq(j.x, zero) & eq(j.y, zero) & eq(j.z, zero));
    if (!any(nonzero)) continue;
    const d4 ma = load(c.ma), mb = load(c.mb);
    A.v = A.v + ma * j;
    A.omega = A.omega + product(c.Ma, j);
    B.v = B.v - mb * j;
    B.omega = B.omega - product(c.Mb, j);
    scatter(vel, c.a, A, nonzero & load_mask(c.push_a));
    scatter(vel, c.b, B, nonzero & load_mask(c.push_b));
  }
  counters.normal_impulses += count(impulses);
  counters.friction_evaluations += count(frictional_updates);
  counters.sliding += count(sliding);
  return std::max(std::max(residual[0], residual[1]), std::max(residual[2], residual[3]));
}

[[gnu::target("avx2")]] double pass_avx2(std::span<ContactBatch> batches, BatchVelocities& vel, double e,
                                         ImpulseCounters& counters) {
  return pass_lanes(batches, vel, e, counters);
}

double pass_baseline(std::span<ContactBatch> batches, BatchVelocities& vel, double e, ImpulseCounters& counters) {
  return pass_lanes(batches, vel, e, counters);
}

// Lane l of `batch` for contact `index`, its bodies' inverse masses and inertias from `sb`.
void fill_lane(ContactBatch& batch, int l, int index, const SolverContact& c, const SolverBodyArray& sb, double dt,
               bool friction) {
  auto put3 = [&](double (*f)[kBatchLanes], const Vec3& v) {
    for (int k = 0; k < 3; ++k) f[k][l] = v[k];
  };
  auto put9 = [&](double (*f)[kBatchLanes], const Mat3& m) {
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) f[3 * i + k][l] = m(i, k);
  };
  const bool ground = c.b == kGround;
  const SolverBody& A = sb.state(c.a);
  const SolverBody& B = sb.state(c.b);
  const bool a_moves = A.inv_mass != 0.0, b_moves = !ground && B.inv_mass != 0.0;
  put3(batch.n, c.n);
  put9(batch.Wa, c.Wa);
  put9(batch.Wb, ground ? Mat3::Zero() : c.Wb);
  put9(batch.Ma, a_moves ? Mat3(A.inv_inertia * cross_matrix(c.ra)) : Mat3::Zero());
  put9(batch.Mb, b_moves ? Mat3(B.inv_inertia * cross_matrix(c.rb)) : Mat3::Zero());
  batch.ma[l] = a_moves ? A.inv_mass : 0.0;
  batch.mb[l] = b_moves ? B.inv_mass : 0.0;
  const Mat3& Ki = c.Kinv;
  const double upper[6] = {Ki(0, 0), Ki(0, 1), Ki(0, 2), Ki(1, 1), Ki(1, 2), Ki(2, 2)};
  for (int k = 0; k < 6; ++k) batch.Kinv[k][l] = upper[k];
  const Vec3 Kn = c.K * c.n;
  put3(batch.Kn, Kn);
  batch.nKn[l] = c.n.dot(Kn);
  const Vec3 dir = c.n - c.friction * c.slide_dir;
  put3(batch.dir, dir);
  batch.denom[l] = c.n.dot(c.K * dir);
  batch.friction[l] = c.friction;
  batch.gap_speed[l] = c.depth < 0.0 ? c.depth / dt : std::numeric_limits<double>::infinity();
  batch.start_un[l] = c.start_un;
  put3(batch.acc, c.accumulated);
  batch.real[l] = -1;
  batch.frictional[l] = friction && c.friction > 0.0 ? -1 : 0;
  batch.slide_zero[l] = c.slide_dir.isZero() ? -1 : 0;
  batch.push_a[l] = a_moves ? -1 : 0;
  batch.push_b[l] = b_moves ? -1 : 0;
  batch.a[l] = c.a;
  batch.b[l] = c.b;
  batch.contact[l] = index;
}

// An empty lane: the ground against itself, no impulse, nothing written.
void empty_lane(ContactBatch& batch, int l) {
  for (auto* f : {batch.n, batch.Kn, batch.dir, batch.acc})
    for (int k = 0; k < 3; ++k) f[k][l] = 0.0;
  for (auto* f : {batch.Wa, batch.Wb, batch.Ma, batch.Mb})
    for (int k = 0; k < 9; ++k) f[k][l] = 0.0;
  for (int k = 0; k < 6; ++k) batch.Kinv[k][l] = 0.0;
  batch.n[2][l] = 1.0;
  batch.ma[l] = batch.mb[l] = 0.0;
  batch.nKn[l] = 1.0;
  batch.denom[l] = 1.0;
  batch.friction[l] = 0.0;
  batch.gap_speed[l] = std::numeric_limits<double>::infinity();
  batch.start_un[l] = 0.0;
  batch.real[l] = batch.frictional[l] = batch.slide_zero[l] = batch.push_a[l] = batch.push_b[l] = 0;
  batch.a[l] = batch.b[l] = kGround;
  batch.contact[l] = -1;
}

}  // namespace

bool contact_batches_use_avx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
}

void BatchVelocities::gather(const SolverBodyArray& sb, int count) {
  velocity_.resize(static_cast<std::size_t>(count) + 1);
  touched_.assign(static_cast<std::size_t>(count) + 1, 0);
  for (int i = -1; i < count; ++i) {
    const SolverBody& s = sb.state(i);
    BatchVelocity& to = at(i);
    for (int k = 0; k < 3; ++k) {
      to.v[k] = s.v[k];
      to.omega[k] = s.omega[k];
    }
  }
}

void BatchVelocities::scatter(SolverBodyArray& sb, const std::vector<RigidBody>& bodies) const {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!touched_[i + 1]) continue;
    const int body = static_cast<int>(i);
    const RigidBody& b = bodies[i];
    SolverBody& s = sb.state(body);
    const BatchVelocity& from = at(body);
    s.v = Vec3(from.v[0], from.v[1], from.v[2]);
    s.omega = Vec3(from.omega[0], from.omega[1], from.omega[2]);
    s.P = b.mass * s.v;
    s.L = b.R * b.inertia_body * b.R.transpose() * s.omega;
  }
}

void ContactBatches::build(std::span<const SolverContact> contacts, const SolverBodyArray& sb, double dt,
                           bool friction, bool fill_always) {
  // Each contact's batch and lane first; the lanes are filled only when the batches pay. The
  // batches of earlier steps are reused (every field of a lane is written): no allocation once the
  // vectors have grown, and no clearing of the 2 kB of a batch.
  used_ = 0;
  filled_ = false;
  contacts_ = contacts.size();
  lanes_.clear();
  slot_.clear();
  if (after_.size() < sb.size()) after_.assign(sb.size(), 0);
  std::size_t first_free = 0;  // no batch before it has a free lane
  auto moving = [&](int body) { return body != kGround && sb.state(body).inv_mass != 0.0; };
  for (const SolverContact& c : contacts) {
    const bool a_moves = moving(c.a), b_moves = moving(c.b);
    // The first batch after every batch that holds one of its moving bodies, with a free lane.
    std::size_t k = std::max({a_moves ? after_[static_cast<std::size_t>(c.a + 1)] : std::size_t{0},
                              b_moves ? after_[static_cast<std::size_t>(c.b + 1)] : std::size_t{0}, first_free});
    while (k < used_ && lanes_[k] == kBatchLanes) ++k;
    if (k == used_) {
      lanes_.push_back(0);
      ++used_;
    }
    slot_.push_back(static_cast<int>(k) * kBatchLanes + lanes_[k]++);
    while (first_free < used_ && lanes_[first_free] == kBatchLanes) ++first_free;
    if (a_moves) after_[static_cast<std::size_t>(c.a + 1)] = k + 1;
    if (b_moves) after_[static_cast<std::size_t>(c.b + 1)] = k + 1;
  }
  // Cleared for the next group: only the bodies of this one were set.
  for (const SolverContact& c : contacts) {
    after_[static_cast<std::size_t>(c.a + 1)] = 0;
    after_[static_cast<std::size_t>(c.b + 1)] = 0;
  }
  if (!pays() && !fill_always) return;
  filled_ = true;
  while (batches_.size() < used_) batches_.emplace_back();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const int slot = slot_[i];
    fill_lane(batches_[static_cast<std::size_t>(slot / kBatchLanes)], slot % kBatchLanes, static_cast<int>(i),
              contacts[i], sb, dt, friction);
  }
  for (std::size_t k = 0; k < used_; ++k)
    for (int l = lanes_[k]; l < kBatchLanes; ++l) empty_lane(batches_[k], l);
}

void ContactBatches::touch_bodies(BatchVelocities& velocities) const {
  for (const ContactBatch& batch : all())
    for (int l = 0; l < kBatchLanes; ++l) {
      if (batch.push_a[l]) velocities.touch(batch.a[l]);
      if (batch.push_b[l]) velocities.touch(batch.b[l]);
    }
}

double ContactBatches::pass(BatchVelocities& velocities, double e, ImpulseCounters& counters, bool avx2) {
  const std::span<ContactBatch> batches(batches_.data(), filled_ ? used_ : 0);
  return avx2 ? pass_avx2(batches, velocities, e, counters) : pass_baseline(batches, velocities, e, counters);
}

void ContactBatches::finish(std::span<SolverContact> contacts) const {
  for (const ContactBatch& batch : all())
    for (int l = 0; l < kBatchLanes; ++l) {
      if (batch.contact[l] < 0) continue;
      SolverContact& c = contacts[static_cast<std::size_t>(batch.contact[l])];
      c.accumulated = Vec3(batch.acc[0][l], batch.acc[1][l], batch.acc[2][l]);
    }
}

void ContactBatches::order(std::vector<int>& out) const {
  out.clear();
  for (const ContactBatch& batch : all())
    for (int l = 0; l < kBatchLanes; ++l)
      if (batch.contact[l] >= 0) out.push_back(batch.contact[l]);
}

}  // namespace boxpile
