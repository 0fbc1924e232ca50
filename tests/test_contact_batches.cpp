// The contact loop's batches (solver.contact_batches): four lanes give what each contact's update
// alone gives in the search's order, to the bit, on AVX2 and on the baseline's code alike; the
// impulses are the sequential loop's, to rounding; no batch holds a moving body twice and each body
// meets its contacts in order; and scenes follow the sequential loop's trajectories to rounding.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/metrics.hpp"
#include "boxpile/sim/solver/contact_batches.hpp"
#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/world.hpp"

using namespace boxpile;

namespace {

// A random tangle of contacts among a few boxes, the ground and a fixed box: touching, apart
// (speculative), sliding and sticking at the phase's start, with and without friction, so that
// every branch of resting_impulse is taken.
struct Tangle {
  std::vector<RigidBody> bodies;
  std::vector<SolverContact> contacts;
};

Tangle make_tangle(unsigned seed, int body_count, int contact_count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto vec = [&](double scale) -> Vec3 { return Vec3(unit(rng), unit(rng), unit(rng)) * scale; };
  Tangle t;
  for (int i = 0; i < body_count; ++i) {
    const Vec3 half(0.2 + 0.1 * unit(rng), 0.2 + 0.1 * unit(rng), 0.1 + 0.05 * unit(rng));
    const Quat q = Quat(Eigen::AngleAxisd(3.0 * unit(rng), vec(1.0).normalized()));
    const bool fixed = i == body_count - 1;
    t.bodies.push_back(make_body("b" + std::to_string(i), {BoxShape{half, Vec3::Zero(), Quat::Identity()}},
                                 1.0 + unit(rng) * 0.5, Pose{vec(2.0), q}, vec(1.0), vec(2.0), Material{}, fixed));
  }
  std::uniform_int_distribution<int> pick(0, body_count - 1);
  for (int k = 0; k < contact_count; ++k) {
    SolverContact c;
    c.a = pick(rng);
    if (t.bodies[static_cast<std::size_t>(c.a)].fixed) c.a = 0;
    c.b = k % 3 == 0 ? kGround : pick(rng);
    if (c.b == c.a) c.b = kGround;
    const RigidBody& a = t.bodies[static_cast<std::size_t>(c.a)];
    const RigidBody ground_body = [] {
      RigidBody g;
      g.fixed = true;
      return g;
    }();
    const RigidBody& b = c.b == kGround ? ground_body : t.bodies[static_cast<std::size_t>(c.b)];
    const Vec3 p = a.x + vec(0.3);
    // Most points approach (the normal against their relative velocity), a fifth of them head on
    // (no sliding at the phase's start), some separate.
    const Vec3 u = a.v + a.omega.cross(p - a.x) - (b.v + b.omega.cross(p - b.x));
    if (k % 5 == 0)
      c.n = -u.normalized();
    else if (k % 6 == 5)
      c.n = Vec3(vec(1.0).normalized());
    else
      c.n = -(u + vec(0.5 * u.norm())).normalized();
    c.ra = p - a.x;
    c.rb = p - b.x;
    c.Wa = cross_matrix(c.ra).transpose();
    c.Wb = cross_matrix(c.rb).transpose();
    c.depth = k % 4 == 1 ? -1e-4 * (1.0 + unit(rng)) : 1e-4 * (1.0 + unit(rng));
    c.friction = k % 7 == 3 ? 0.0 : k % 2 == 1 ? 2.0 : 0.3 + 0.3 * unit(rng);
    const Mat3 Ka = a.fixed ? Mat3::Zero() : collision_matrix_share(a, c.ra);
    const Mat3 Kb = b.fixed ? Mat3::Zero() : collision_matrix_share(b, c.rb);
    set_collision_matrix(c, Ka + Kb);
    t.contacts.push_back(c);
  }
  return t;
}

// The tangle of `seed` (its size grows with it) with its resting phase begun, and its bodies as
// the sequential loop and the batches see them.
struct Started {
  Tangle t;
  int bodies = 0;
  SolverBodyArray start;
  BatchVelocities velocities;
};

Started start_tangle(unsigned seed) {
  Started s;
  s.t = make_tangle(seed, 3 + static_cast<int>(seed % 9), 5 + static_cast<int>(seed * 7 % 60));
  s.bodies = static_cast<int>(s.t.bodies.size());
  s.start.gather(s.t.bodies);
  for (SolverContact& c : s.t.contacts) begin_resting_phase(c, s.start.relative_velocity(c));
  s.velocities.gather(s.start, s.bodies);
  return s;
}

bool same_counters(const ImpulseCounters& a, const ImpulseCounters& b) {
  return a.normal_impulses == b.normal_impulses && a.friction_evaluations == b.friction_evaluations &&
         a.sliding == b.sliding;
}

// One contact of a batch updated alone, the batches' arithmetic written out for one lane: the
// oracle for the four-lane code (a lane's result must not depend on its neighbours).
double reference_update(ContactBatch& c, int l, BatchVelocities& vel, double e, ImpulseCounters& counters) {
  auto row = [&](const double (*m)[kBatchLanes], int i, const double* x) {
    return (m[3 * i][l] * x[0] + m[3 * i + 1][l] * x[1]) + m[3 * i + 2][l] * x[2];
  };
  auto dot = [](const double* a, const double* b) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; };
  BatchVelocity& A = vel.at(c.a[l]);
  BatchVelocity& B = vel.at(c.b[l]);
  double u[3], n[3], J_old[3], rhs[3], J[3];
  for (int k = 0; k < 3; ++k) {
    n[k] = c.n[k][l];
    J_old[k] = c.acc[k][l];
  }
  for (int k = 0; k < 3; ++k) u[k] = (A.v[k] + row(c.Wa, k, A.omega)) - (B.v[k] + row(c.Wb, k, B.omega));
  const double un = dot(n, u);
  const double gap = c.gap_speed[l];
  const double residual = (gap < 0.0 ? gap : 0.0) - un;
  const double T = c.start_un[l] < 0.0 ? -e * c.start_un[l] : 0.0;
  const double target = gap < T ? gap : T;
  for (int k = 0; k < 3; ++k) rhs[k] = target * n[k] - u[k];
  const double k00 = c.Kinv[0][l], k01 = c.Kinv[1][l], k02 = c.Kinv[2][l], k11 = c.Kinv[3][l], k12 = c.Kinv[4][l],
               k22 = c.Kinv[5][l];
  const double Kr[3] = {(k00 * rhs[0] + k01 * rhs[1]) + k02 * rhs[2], (k01 * rhs[0] + k11 * rhs[1]) + k12 * rhs[2],
                        (k02 * rhs[0] + k12 * rhs[1]) + k22 * rhs[2]};
  double Js[3], jt[3];
  for (int k = 0; k < 3; ++k) Js[k] = J_old[k] + Kr[k];
  const double jn = dot(Js, n);
  for (int k = 0; k < 3; ++k) jt[k] = Js[k] - jn * n[k];
  const double mu = c.friction[l];
  const bool frictional = c.frictional[l] != 0;
  const bool sticks = jn >= 0.0 && dot(jt, jt) <= (mu * jn) * (mu * jn);
  ++counters.normal_impulses;
  for (int k = 0; k < 3; ++k) J[k] = Js[k];
  if (frictional) {
    ++counters.friction_evaluations;
    if (!sticks) {
      ++counters.sliding;
      if (c.slide_zero[l]) {
        const double jc = jn > 0.0 ? jn : 0.0;
        const double norm = std::sqrt(jt[0] * jt[0] + jt[1] * jt[1] + jt[2] * jt[2]);
        const double scale = jc > 0.0 && norm > 0.0 ? std::min(1.0, mu * jc / norm) : 0.0;
        for (int k = 0; k < 3; ++k) J[k] = jc * n[k] + scale * jt[k];
      } else {
        const double Kn[3] = {c.Kn[0][l], c.Kn[1][l], c.Kn[2][l]};
        const double denom = c.denom[l];
        double jsl = 0.0;
        if (denom > 0.0) jsl = std::max(0.0, ((target - un) + dot(Kn, J_old)) / denom);
        for (int k = 0; k < 3; ++k) J[k] = jsl * c.dir[k][l];
      }
    }
  } else {
    const double jn_old = dot(J_old, n);
    const double jn_new = std::max(0.0, jn_old + (target - un) / c.nKn[l]);
    for (int k = 0; k < 3; ++k) J[k] = jn_new * n[k];
  }
  double j[3];
  for (int k = 0; k < 3; ++k) {
    j[k] = J[k] - J_old[k];
    c.acc[k][l] = J[k];
  }
  if (j[0] == 0.0 && j[1] == 0.0 && j[2] == 0.0) return residual;
  double dwa[3], dwb[3];
  for (int k = 0; k < 3; ++k) {
    dwa[k] = row(c.Ma, k, j);
    dwb[k] = row(c.Mb, k, j);
  }
  if (c.push_a[l])
    for (int k = 0; k < 3; ++k) {
      A.v[k] = A.v[k] + c.ma[l] * j[k];
      A.omega[k] = A.omega[k] + dwa[k];
    }
  if (c.push_b[l])
    for (int k = 0; k < 3; ++k) {
      B.v[k] = B.v[k] - c.mb[l] * j[k];
      B.omega[k] = B.omega[k] - dwb[k];
    }
  return residual;
}

bool same_velocities(const BatchVelocities& x, const BatchVelocities& y, int bodies) {
  for (int i = -1; i < bodies; ++i)
    if (std::memcmp(x.at(i).v, y.at(i).v, sizeof(double) * 6) != 0) return false;
  return true;
}

}  // namespace

TEST_CASE("contact batches: four lanes give each contact's update alone in the search's order, to the bit, on AVX2 and without",
          "[batches]") {
  constexpr double dt = 1.0 / 240.0;
  constexpr int kPasses = 10;
  for (const bool friction : {true, false}) {
    for (unsigned seed = 1; seed <= 20; ++seed) {
      CAPTURE(seed, friction);
      Started st = start_tangle(seed);
      const Tangle& t = st.t;
      const int bodies = st.bodies;
      const SolverBodyArray& start = st.start;
      const BatchVelocities& start_velocities = st.velocities;

      ContactBatches batches;
      batches.build(t.contacts, start, dt, friction, true);
      // Every contact is in one batch once.
      std::vector<int> order;
      batches.order(order);
      std::vector<int> sorted = order;
      std::sort(sorted.begin(), sorted.end());
      std::vector<int> all(t.contacts.size());
      for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
      REQUIRE(sorted == all);

      // The oracle: each contact alone, in the search's order (the batches keep it for every body).
      std::vector<std::pair<int, int>> where(t.contacts.size());  // contact -> (batch, lane)
      for (std::size_t b = 0; b < batches.all().size(); ++b)
        for (int l = 0; l < kBatchLanes; ++l)
          if (batches.all()[b].contact[l] >= 0)
            where[static_cast<std::size_t>(batches.all()[b].contact[l])] = {static_cast<int>(b), l};
      BatchVelocities ref = start_velocities;
      std::vector<ContactBatch> ref_batches(batches.all().begin(), batches.all().end());
      ImpulseCounters ref_counters;
      std::vector<double> ref_residual;
      for (int pass = 0; pass < kPasses; ++pass) {
        const double e = -1.0 + static_cast<double>(pass + 1) / kPasses;
        double residual = 0.0;
        for (const auto& [b, l] : where)
          residual = std::max(residual, reference_update(ref_batches[static_cast<std::size_t>(b)], l, ref, e, ref_counters));
        ref_residual.push_back(residual);
      }
      CHECK(ref_counters.normal_impulses == static_cast<std::uint64_t>(kPasses) * t.contacts.size());
      if (friction) {  // some updates stick, some slide
        CHECK(ref_counters.sliding > 0);
        CHECK(ref_counters.sliding < ref_counters.friction_evaluations);
      }
      // The passes moved something: the test compares impulses, not two untouched copies.
      CHECK_FALSE(same_velocities(ref, start_velocities, bodies));

      for (const bool avx2 : {false, true}) {
        if (avx2 && !contact_batches_use_avx2()) continue;
        CAPTURE(avx2);
        BatchVelocities lanes = start_velocities;
        ContactBatches run = batches;
        ImpulseCounters counters;
        bool residuals_same = true;
        for (int pass = 0; pass < kPasses; ++pass) {
          const double e = -1.0 + static_cast<double>(pass + 1) / kPasses;
          const double residual = run.pass(lanes, e, counters, avx2);
          residuals_same = residuals_same && std::memcmp(&residual, &ref_residual[static_cast<std::size_t>(pass)],
                                                         sizeof residual) == 0;
        }
        CHECK(residuals_same);
        CHECK(same_velocities(lanes, ref, bodies));
        CHECK(same_counters(counters, ref_counters));
        bool accumulated_same = true;
        for (std::size_t b = 0; b < run.all().size(); ++b)
          accumulated_same = accumulated_same && std::memcmp(run.all()[b].acc, ref_batches[b].acc, sizeof ref_batches[b].acc) == 0;
        CHECK(accumulated_same);
      }
    }
  }
}

TEST_CASE("contact batches: the same impulses as the sequential loop in the same order, to rounding", "[batches]") {
  // The batches update velocities directly (dv = j / m) where the sequential loop updates the
  // momenta and forms velocities from them (v = P / m): the same impulses, rounded differently.
  constexpr double dt = 1.0 / 240.0;
  constexpr int kPasses = 10;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    CAPTURE(seed);
    Started st = start_tangle(seed);
    const Tangle& t = st.t;
    const int bodies = st.bodies;
    const SolverBodyArray& start = st.start;
    BatchVelocities& velocities = st.velocities;
    ContactBatches batches;
    batches.build(t.contacts, start, dt, true, true);
    std::vector<int> order(t.contacts.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);  // the search's

    SolverBodyArray seq = start;
    std::vector<SolverContact> seq_contacts = t.contacts;
    ImpulseCounters seq_counters, counters;
    for (int pass = 0; pass < kPasses; ++pass) {
      const double e = -1.0 + static_cast<double>(pass + 1) / kPasses;
      for (const int k : order) {
        SolverContact& c = seq_contacts[static_cast<std::size_t>(k)];
        const Vec3 u = seq.relative_velocity(c);
        const double target = allow_gap(c, c.start_un < 0.0 ? -e * c.start_un : 0.0, dt);
        const Vec3 j = resting_impulse(c, u, target, true, seq_counters);
        if (!is_exact_zero(j)) seq.apply(c, j);
      }
      batches.pass(velocities, e, counters, contact_batches_use_avx2());
    }
    std::vector<SolverContact> lane_contacts = t.contacts;
    batches.finish(lane_contacts);
    double speed = 0.0, worst = 0.0;
    for (int i = 0; i < bodies; ++i) {
      const SolverBody& s = seq.state(i);
      const BatchVelocity& v = velocities.at(i);
      for (int k = 0; k < 3; ++k) {
        speed = std::max({speed, std::abs(s.v[k]), std::abs(s.omega[k])});
        worst = std::max({worst, std::abs(s.v[k] - v.v[k]), std::abs(s.omega[k] - v.omega[k])});
      }
    }
    // Rounding (1e-16 relative) grown by ten passes over some tens of coupled contacts.
    CHECK(worst <= 1e-10 * speed);
    double impulse = 0.0, worst_impulse = 0.0;
    for (std::size_t i = 0; i < t.contacts.size(); ++i) {
      impulse = std::max(impulse, seq_contacts[i].accumulated.norm());
      worst_impulse = std::max(worst_impulse, (seq_contacts[i].accumulated - lane_contacts[i].accumulated).norm());
    }
    CHECK(worst_impulse <= 1e-10 * impulse);
    CHECK(counters.normal_impulses == seq_counters.normal_impulses);
    CHECK(counters.friction_evaluations == seq_counters.friction_evaluations);
  }
}

TEST_CASE("contact batches: no batch holds a moving body twice, and each body meets its contacts in order",
          "[batches]") {
  Tangle t = make_tangle(7, 12, 200);
  SolverBodyArray sb;
  sb.gather(t.bodies);
  for (SolverContact& c : t.contacts) begin_resting_phase(c, sb.relative_velocity(c));
  ContactBatches batches;
  batches.build(t.contacts, sb, 1.0 / 240.0, true);
  std::vector<int> batch_of(t.contacts.size(), -1);
  int filled = 0;
  for (std::size_t k = 0; k < batches.all().size(); ++k) {
    const ContactBatch& batch = batches.all()[k];
    std::vector<int> moving;
    for (int l = 0; l < kBatchLanes; ++l) {
      if (batch.contact[l] < 0) continue;
      ++filled;
      batch_of[static_cast<std::size_t>(batch.contact[l])] = static_cast<int>(k);
      if (batch.push_a[l]) moving.push_back(batch.a[l]);
      if (batch.push_b[l]) moving.push_back(batch.b[l]);
    }
    std::sort(moving.begin(), moving.end());
    CHECK(std::adjacent_find(moving.begin(), moving.end()) == moving.end());
  }
  CHECK(filled == 200);
  // A moving body's contacts are in batches that follow one another as the contacts do.
  for (std::size_t body = 0; body + 1 < t.bodies.size(); ++body) {
    int last = -1;
    bool in_order = true;
    for (std::size_t i = 0; i < t.contacts.size(); ++i) {
      const SolverContact& c = t.contacts[i];
      if (c.a != static_cast<int>(body) && c.b != static_cast<int>(body)) continue;
      in_order = in_order && batch_of[i] > last;
      last = batch_of[i];
    }
    CHECK(in_order);
  }
  // 11 moving boxes, two to most contacts: at most 5 contacts can share a batch, and chains of
  // contacts through one body leave lanes empty; on this tangle two thirds of the lanes fill, enough
  // to pay.
  CHECK(3 * filled >= 2 * kBatchLanes * batches.batches());
  CHECK(batches.pays());
}

TEST_CASE("contact batches: a stack's chain of pairs fills a lane a batch and runs one contact at a time", "[batches]") {
  // Box i rests on box i - 1 on four points, box 0 on the ground: a pair's four points share both
  // boxes, and each pair a box with the next, so nearly every contact needs a batch of its own.
  Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/stack_10.json");
  World world(scene);
  world.step();
  std::vector<BodyContact> found;
  world.contacts(found);
  REQUIRE(found.size() == 40);
  std::vector<RigidBody> bodies = world.bodies();
  SolverBodyArray sb;
  sb.gather(bodies);
  std::vector<SolverContact> contacts;
  for (const BodyContact& bc : found) {
    SolverContact c;
    c.a = bc.body_a;
    c.b = bc.body_b;
    c.n = bc.contact.normal;
    contacts.push_back(c);
  }
  ContactBatches batches;
  batches.build(contacts, sb, scene.time.dt, true);
  CHECK(batches.batches() >= 30);  // at most 1.33 contacts a batch
  CHECK_FALSE(batches.pays());
}

TEST_CASE("contact batches: scenes follow the sequential loop's trajectory, to rounding", "[batches]") {
  // The same impulses in the same order for every body, rounded differently (velocities updated
  // directly, not through the momenta): a resting stack and the bone scene agree for their whole
  // run; pile_100's fall is chaotic once its boxes pile up, so it is compared over its first 150
  // steps (0.6 s, the first impacts), where the difference measured 1.1e-9 m.
  struct Case {
    const char* name;
    int steps;
    double tolerance;  // m, the largest difference of a body's centre allowed
  };
  for (const Case& k : {Case{"stack_10", 1200, 1e-15}, Case{"bone_hits_pile", 1200, 1e-8}, Case{"pile_100", 150, 1e-8}}) {
    CAPTURE(k.name);
    Scene one = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + k.name + ".json");
    Scene batched = one;
    batched.solver.contact_batches = true;
    World a(one), b(batched);
    double worst = 0.0;
    for (int i = 0; i < k.steps; ++i) {
      a.step();
      b.step();
      for (std::size_t j = 0; j < a.bodies().size(); ++j)
        worst = std::max(worst, (a.bodies()[j].x - b.bodies()[j].x).norm());
    }
    CHECK(worst <= k.tolerance);
    CHECK(b.method_diagnostics()["contact_passes"] == a.method_diagnostics()["contact_passes"]);
  }
}
