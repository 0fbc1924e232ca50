#include "sim/world.hpp"

#include <algorithm>
#include <cmath>

namespace boxpile {

namespace {
// An approach faster than this counts as a collision event: well above the |g| dt that gravity
// adds to a resting contact in one step, and above rounding.
constexpr double kEventSpeedMin = 0.01;  // m/s
constexpr double kEventSpeedGravitySteps = 2.0;
}  // namespace

Material combine_materials(const Material& a, const Material& b) {
  return {std::sqrt(a.friction * b.friction), std::max(a.restitution, b.restitution)};
}

World::World(const Scene& scene)
    : scene_(scene), bodies_(make_bodies(scene)), wires_(make_wire_joints(scene, bodies_)) {
  ground_.name = "ground";
  ground_.fixed = true;
  ground_.material = scene.material;
  ground_.update_derived();
  start_v_.resize(bodies_.size());
  start_omega_.resize(bodies_.size());
  margins_.resize(bodies_.size());
  for (const RigidBody& b : bodies_) {
    double r = 0.0;  // the farthest any box corner lies from the centre of mass
    for (const BoxShape& box : b.shapes) r = std::max(r, box.offset.norm() + box.half_extents.norm());
    bounding_radius_.push_back(r);
  }
  contacts_.reserve(8 * bodies_.size());
  solver_contacts_.reserve(8 * bodies_.size());
}

void World::step() {
  const Effects& fx = scene_.effects;
  const SolverSettings& s = scene_.solver;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    start_v_[i] = bodies_[i].v;
    start_omega_[i] = bodies_[i].omega;
  }

  // 1. The contact set, found once and reused through the whole step.
  find_contacts();
  prepare_solver_contacts();
  SolverBodies sb{bodies_, ground_};
  stats_ = StepStats{};

  // 2. Collision loop: resolve approaching contacts with the scene's restitution.
  const double event_speed = std::max(kEventSpeedMin, kEventSpeedGravitySteps * scene_.gravity.norm() * scene_.time.dt);
  collision_loop(sb, solver_contacts_, s.collision_passes, fx.restitution, fx.friction, time_,
                 scene_.time.dt, event_speed, counters_.impulses, stats_, events_);
  ++counters_.collision_loop_runs;

  // 3. External forces on the momenta: gravity, air damping; the wires take their share.
  integrate_momenta();
  enforce_wires();

  // 4. Contact loop: every contact of the set, restitution ramped up to 0.
  contact_loop(sb, solver_contacts_, s.contact_passes, fx.friction, scene_.time.dt, counters_.impulses, stats_);
  ++counters_.contact_loop_runs;
  enforce_wires();

  // 5. Shock propagation: from the ground up, each level frozen once solved.
  if (s.shock_propagation) {
    shock_.run(sb, solver_contacts_, s.shock_passes, fx.friction, scene_.time.dt, counters_.impulses, stats_);
    ++counters_.shock_propagation_runs;
  }
  enforce_wires();

  // Penetration recovery: pseudo-velocities that push overlaps apart (positions only).
  if (s.penetration_recovery > 0.0) {
    recovery_.run(sb, solver_contacts_, s.penetration_recovery, s.penetration_slop, scene_.time.dt,
                  s.recovery_passes);
    ++counters_.recovery_runs;
  }

  // 6. Positions and orientations; wired anchors back onto their wires.
  integrate_positions();
  project_wires();
  time_ += scene_.time.dt;
  ++counters_.steps;
}

void World::find_contacts() {
  contacts_.clear();
  // Each body's speculative margin: the scene's contact margin plus how far any of its points
  // can move in one step, (|v| + |omega| r) dt, so that a fast body meets what it would reach
  // within the step as a speculative contact instead of tunnelling into it.
  const double dt = scene_.time.dt;
  const double base = std::max(scene_.collision.margin, scene_.solver.contact_margin);
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const RigidBody& b = bodies_[i];
    margins_[i] = base + (b.v.norm() + b.omega.norm() * bounding_radius_[i]) * dt;
  }
  CollisionSettings cs = scene_.collision;
  for (const auto& [i, j] : broadphase_.find_pairs(bodies_, margins_)) {
    ++counters_.broadphase_pairs;
    counters_.narrowphase_calls += bodies_[i].shapes.size() * bodies_[j].shapes.size();
    cs.margin = margins_[i] + margins_[j] - base;
    collide_bodies(bodies_, i, j, cs, contacts_);
  }
  if (!scene_.ground) return;
  for (int i = 0; i < static_cast<int>(bodies_.size()); ++i) {
    if (bodies_[i].fixed) continue;
    counters_.narrowphase_calls += bodies_[i].shapes.size();
    cs.margin = margins_[i];
    collide_body_ground(bodies_, i, *scene_.ground, cs, contacts_);
  }
}

void World::prepare_solver_contacts() {
  solver_contacts_.clear();
  for (const BodyContact& bc : contacts_) {
    const RigidBody& a = bodies_[bc.body_a];
    const RigidBody& b = bc.body_b == kGround ? ground_ : bodies_[bc.body_b];
    SolverContact c;
    c.a = bc.body_a;
    c.b = bc.body_b;
    c.n = bc.contact.normal;
    c.ra = bc.contact.position - a.x;
    c.rb = bc.contact.position - b.x;
    c.depth = bc.contact.depth;
    const Material m = combine_materials(a.material, b.material);
    c.friction = m.friction;
    c.restitution = m.restitution;
    if (!a.fixed) c.Ka = collision_matrix_share(a, c.ra);
    if (!b.fixed) c.Kb = collision_matrix_share(b, c.rb);
    set_collision_matrix(c, !a.fixed, !b.fixed);
    solver_contacts_.push_back(c);
  }
}

void World::integrate_momenta() {
  const Effects& fx = scene_.effects;
  const double dt = scene_.time.dt;
  // Damping dP/dt = -c P integrated exactly over the step: P *= exp(-c dt), stable for any c dt.
  const double keep_linear = std::exp(-scene_.damping.linear * dt);
  const double keep_angular = std::exp(-scene_.damping.angular * dt);
  for (RigidBody& b : bodies_) {
    if (b.fixed) continue;
    if (fx.gravity) {
      b.P += b.mass * scene_.gravity * dt;
      ++counters_.gravity_applications;
    }
    if (fx.damping) {
      b.P *= keep_linear;
      b.L *= keep_angular;
      ++counters_.damping_applications;
    }
    b.v = b.inv_mass * b.P;
    b.omega = b.inv_inertia_world * b.L;
  }
}

void World::integrate_positions() {
  const double dt = scene_.time.dt;
  const bool explicit_euler = scene_.solver.integrator == PositionIntegrator::ExplicitEuler;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    RigidBody& b = bodies_[i];
    if (b.fixed) continue;
    // Explicit Euler moves with the velocities the step started with; semi-implicit Euler with
    // the ones the step just resolved.
    Vec3 v = explicit_euler ? start_v_[i] : b.v;
    Vec3 w = explicit_euler ? start_omega_[i] : b.omega;
    if (scene_.solver.penetration_recovery > 0.0) {  // pushed apart, positions only
      v += recovery_.pseudo_v()[i];
      w += recovery_.pseudo_omega()[i];
    }
    b.x += dt * v;
    // dq/dt = 1/2 (0, omega) q (Baraff's notes, "quaternion derivative"), then renormalised.
    const Quat spin(0.0, w.x(), w.y(), w.z());
    b.q.coeffs() += 0.5 * dt * (spin * b.q).coeffs();
    const Vec3 omega_now = b.omega;
    b.update_derived();
    if (scene_.effects.gyroscopic) {
      // L is what is conserved: omega = I(t)^-1 L changes as the body turns.
      ++counters_.gyroscopic_updates;
    } else {
      // The mission neglects the gyroscopic term (spherical inertia): omega is kept, and L is
      // re-expressed with the turned inertia, L = I(t + dt) omega.
      b.L = b.R * b.inertia_body * b.R.transpose() * omega_now;
      b.omega = omega_now;
    }
  }
}

void World::enforce_wires() {
  for (const WireJoint& w : wires_) enforce_wire_velocity(bodies_[w.body], w);
}

void World::project_wires() {
  for (const WireJoint& w : wires_) {
    project_onto_wire(bodies_[w.body], w);
    bodies_[w.body].update_derived();
  }
}

void World::body_states(std::vector<BodyState>& out) const {
  out.resize(bodies_.size());
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const RigidBody& b = bodies_[i];
    const Pose frame = b.frame_pose();
    out[i] = {b.name, frame.position, frame.orientation, b.v, b.omega};
  }
}

}  // namespace boxpile
