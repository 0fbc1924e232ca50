#include "boxpile/sim/solver/impulse_method.hpp"

#include <algorithm>

#include "boxpile/sim/solver/collision_loop.hpp"
#include "boxpile/sim/solver/contact_loop.hpp"
#include "boxpile/sim/solver/integrate.hpp"

namespace boxpile {

namespace {

// What every contact of a pair of bodies shares: the penetration left alone (relative to the pair's
// boxes) and the combined material.
struct PairTerms {
  static constexpr int kNone = kGround - 1;  // no body has this index: no pair yet
  int a = kNone, b = kNone;
  double slop = 0.0, friction = 0.0, restitution = 0.0;
};

PairTerms pair_terms(const SolverSettings& s, int body_a, int body_b, const RigidBody& a, const RigidBody& b) {
  const Material m = combine_materials(a.material, b.material);
  return {body_a, body_b, penetration_slop_for(s, std::min(smallest_edge(a), smallest_edge(b))), m.friction,
          m.restitution};
}

}  // namespace

ImpulseMethod::ImpulseMethod(std::size_t body_count) {
  start_v_.resize(body_count);
  start_omega_.resize(body_count);
  const StepStorage storage{body_count};
  solver_contacts_.reserve(storage.contacts());
  prepared_k_.reserve(storage.contacts());
  resting_bodies_.reserve(body_count);
  shock_.reserve(storage);
  recovery_.reserve(storage);
}

void ImpulseMethod::step(StepContext& ctx) {
  const SolverSettings& s = ctx.scene.solver;
  std::vector<RigidBody>& bodies = ctx.bodies;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    start_v_[i] = bodies[i].v;
    start_omega_[i] = bodies[i].omega;
  }

  // 1. The contact set (found by the world), as the solver sees it through the whole step.
  prepare_solver_contacts(ctx);
  if (same_set_) ++ctx.counters.same_contact_sets;
  StepProfile& profile = ctx.counters.profile;
  profile.lap(Stage::prepare);
  ImpulseStep step{ctx, SolverBodies{bodies, ctx.ground}, resting_bodies_, solver_contacts_};
  ctx.stats = StepStats{};

  // 2. Collision loop: resolve approaching contacts with the scene's restitution.
  collision_loop(step);
  ++ctx.counters.collision_loop_runs;
  profile.lap(Stage::collision_loop);

  // 3. External forces on the momenta: gravity, air damping; the wires take their share.
  integrate_momenta(ctx);
  enforce_wires(bodies, ctx.wires);
  profile.lap(Stage::forces);

  // 4. Contact loop: every contact of the set, restitution ramped up to 0.
  contact_loop(step);
  ++ctx.counters.contact_loop_runs;
  enforce_wires(bodies, ctx.wires);
  profile.lap(Stage::contact_loop);

  // 5. Shock propagation: from the ground up, each level frozen once solved.
  if (s.shock_propagation) {
    shock_.run(step, same_set_);
    ++ctx.counters.shock_propagation_runs;
  }
  enforce_wires(bodies, ctx.wires);
  profile.lap(Stage::shock_propagation);

  // Penetration recovery: pseudo-velocities that push overlaps apart (positions only).
  if (s.penetration_recovery > 0.0) {
    recovery_.run(step, s.shock_propagation ? &shock_ : nullptr);
    ++ctx.counters.recovery_runs;
  }
  profile.lap(Stage::recovery);

  // 6. Positions and orientations; wired anchors back onto their wires.
  integrate_positions(ctx);
  project_wires(bodies, ctx.wires);
  profile.lap(Stage::integration);
}

void ImpulseMethod::prepare_solver_contacts(const StepContext& ctx) {
  // Last step's solver contacts stay in place: a contact the world kept from the last step at the
  // same index keeps its offsets and collision matrices (its bodies have not moved beyond
  // rounding since they were formed) and only takes back its K over both bodies.
  const std::size_t count = ctx.contacts.size();
  const std::size_t kept = std::min(solver_contacts_.size(), count);
  same_set_ = count > 0 && count == solver_contacts_.size();
  solver_contacts_.resize(count);
  prepared_k_.resize(count);
  // A pair's contacts come one after another: its slop and material are found once per pair.
  PairTerms pair;
  for (std::size_t k = 0; k < count; ++k) {
    SolverContact& c = solver_contacts_[k];
    const bool same = k < kept && ctx.same_as_last_step[k];
    same_set_ = same_set_ && same;
    if (same) {
      const CollisionMatrix& m = prepared_k_[k];
      c.K = m.K;
      c.Kinv = m.Kinv;
      c.Kinv_n = m.Kinv_n;
      c.Kinv_n_size = m.Kinv_n_size;
      continue;
    }
    const BodyContact& bc = ctx.contacts[k];
    const RigidBody& a = ctx.bodies[bc.body_a];
    const RigidBody& b = bc.body_b == kGround ? ctx.ground : ctx.bodies[bc.body_b];
    if (bc.body_a != pair.a || bc.body_b != pair.b) pair = pair_terms(ctx.scene.solver, bc.body_a, bc.body_b, a, b);
    // Filled where it stays: a SolverContact is some 600 bytes, and copying each one into the
    // set cost a quarter of this function (perf, Jenga tower).
    c = SolverContact{};
    c.a = bc.body_a;
    c.b = bc.body_b;
    c.n = bc.contact.normal;
    c.ra = bc.contact.position - a.x;
    c.rb = bc.contact.position - b.x;
    c.Wa = cross_matrix(c.ra).transpose();
    c.Wb = cross_matrix(c.rb).transpose();
    c.depth = bc.contact.depth;
    c.slop = pair.slop;
    c.friction = pair.friction;
    c.restitution = pair.restitution;
    // The shares formed in locals, so K is summed from registers rather than from the stores.
    const Mat3 Ka = a.fixed ? Mat3::Zero() : collision_matrix_share(a, c.ra);
    const Mat3 Kb = b.fixed ? Mat3::Zero() : collision_matrix_share(b, c.rb);
    c.Ka = Ka;
    c.Kb = Kb;
    set_collision_matrix(c, Ka + Kb);
    prepared_k_[k] = {c.K, c.Kinv, c.Kinv_n, c.Kinv_n_size};
  }
}

void ImpulseMethod::integrate_positions(StepContext& ctx) {
  const SolverSettings& s = ctx.scene.solver;
  const bool explicit_euler = s.integrator == PositionIntegrator::ExplicitEuler;
  for (std::size_t i = 0; i < ctx.bodies.size(); ++i) {
    RigidBody& b = ctx.bodies[i];
    if (b.fixed) continue;
    // Explicit Euler moves with the velocities the step started with; semi-implicit Euler with
    // the ones the step just resolved.
    Vec3 v = explicit_euler ? start_v_[i] : b.v;
    Vec3 w = explicit_euler ? start_omega_[i] : b.omega;
    if (s.penetration_recovery > 0.0) {  // pushed apart, positions only
      v += recovery_.pseudo_v()[i];
      w += recovery_.pseudo_omega()[i];
    }
    advance_pose(b, v, w, ctx.dt, ctx.scene.effects.gyroscopic, ctx.counters);
  }
}

}  // namespace boxpile
