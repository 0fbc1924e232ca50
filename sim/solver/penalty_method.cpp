#include "boxpile/sim/solver/penalty_method.hpp"

#include "boxpile/sim/solver/integrate.hpp"
#include "boxpile/sim/solver/penalty_force.hpp"

namespace boxpile {

namespace {
// Anchors reserved per body: a box on a box touches at up to 8 points, on the ground at 4, so a
// body in a pile rarely carries more than this many (the vectors grow once if it does).
constexpr std::size_t kAnchorsPerBody = 16;

// The mass one contact point carries: a quarter (kPointsPerSupport) of the pair's reduced mass.
double point_mass(const RigidBody& a, const RigidBody& b) {
  const double inv = a.inv_mass + b.inv_mass;
  return 1.0 / (inv * kPointsPerSupport);
}
// The damper a point gets in a step of length h. Explicit (read at the step's start), a damper c
// on a point of mass m changes its velocity by a factor 1 - c h / m per step: past c h / m = 1 it
// reverses the point every step and the velocity rings at full size while the position stays (a
// stack of 5 with c = 450 N s/m and 10 substeps showed 1.35 cm/s at every frame). There it is
// integrated implicitly instead, its force read at the step's end velocity: the factor is
// 1 / (1 + c h / m), so the damper is c / (1 + c h / m), which never reverses a point.
double stable_damper(double c, double m, double h) {
  const double x = c * h / m;
  return x > 1.0 ? c / (1.0 + x) : c;
}

}  // namespace

PenaltyMethod::PenaltyMethod(const PenaltyParameters& parameters, std::size_t body_count)
    : parameters_(parameters) {
  anchors_.reserve(kAnchorsPerBody * body_count);
}

void PenaltyMethod::step(StepContext& ctx) {
  // 1-2. The contact set (found by the world for this step): at each touching point a normal
  //      spring-damper and a friction spring to its anchor, summed into the bodies' momenta.
  apply_contact_forces(ctx);
  StepProfile& profile = ctx.counters.profile;
  profile.lap(Stage::penalty_forces);
  // 3. External forces on the momenta: gravity, air damping; the wires take their share.
  integrate_momenta(ctx);
  enforce_wires(ctx.bodies, ctx.wires);
  profile.lap(Stage::forces);
  // 4. Positions with the new velocities (symplectic Euler); wired anchors back onto their wires.
  integrate_positions(ctx);
  project_wires(ctx.bodies, ctx.wires);
  profile.lap(Stage::integration);
  ++ctx.counters.penalty_substeps;
}

void PenaltyMethod::apply_contact_forces(StepContext& ctx) {
  const bool friction = ctx.scene.effects.friction;
  const bool restitution = ctx.scene.effects.restitution;
  PenaltyCounters& counters = ctx.counters.penalty;
  anchors_.begin_step();
  for (const BodyContact& bc : ctx.contacts) {
    RigidBody& a = ctx.bodies[bc.body_a];
    const bool b_is_ground = bc.body_b == kGround;
    RigidBody* b_body = b_is_ground ? nullptr : &ctx.bodies[bc.body_b];
    const RigidBody& b = b_is_ground ? ctx.ground : *b_body;
    const Vec3& p = bc.contact.position;
    const Vec3 ra = p - a.x;
    const Vec3 rb = p - b.x;

    const Material m = combine_materials(a.material, b.material);
    PenaltyPoint pt;
    pt.n = bc.contact.normal;
    pt.depth = bc.contact.depth;
    pt.u = a.v + a.omega.cross(ra) - b.v - b.omega.cross(rb);
    pt.stiffness = parameters_.stiffness;
    const double mass = point_mass(a, b);
    pt.damping = stable_damper(parameters_.damping.value_or(point_damping(
                                   parameters_.stiffness, mass, damping_ratio_for_restitution(restitution ? m.restitution : 0.0))),
                               mass, ctx.dt);
    pt.friction_stiffness = friction ? parameters_.friction_stiffness : 0.0;
    pt.static_mu = m.static_mu();
    pt.dynamic_mu = m.friction;

    // The anchor lives on B (in its axes about its centre of mass; in the world for the ground).
    auto to_b = [&](const Vec3& world) { return b_is_ground ? world : Vec3(b.R.transpose() * (world - b.x)); };
    bool created = false;
    const Vec3 on_a = a.R.transpose() * ra;
    FrictionAnchor& anchor = anchors_.find_or_create(AnchorKey::of(bc), on_a, to_b(p), created);
    counters.anchors_created += created ? 1 : 0;
    // A point within the contact margin but not touching keeps its anchor and gets no force: a
    // resting face's corners that rise by rounding do not lose their anchors.
    if (bc.contact.depth <= 0.0) continue;
    pt.p = a.x + a.R * anchor.tie_a;
    Vec3 anchor_world = b_is_ground ? anchor.on_b : Vec3(b.x + b.R * anchor.on_b);
    const PenaltyForce f = penalty_force(pt, anchor_world, anchor.sliding);
    anchor.on_b = to_b(anchor_world);
    ++counters.spring_evaluations;
    counters.sliding_points += f.slipped ? 1 : 0;

    // Forces over the step as impulses on the momenta; velocities follow in integrate_momenta.
    const Vec3 impulse = ctx.dt * f.force;
    if (!a.fixed) {
      a.P += impulse;
      a.L += ra.cross(impulse);
    }
    if (b_body && !b_body->fixed) {
      b_body->P -= impulse;
      b_body->L -= rb.cross(impulse);
    }
  }
  anchors_.end_step();
}

void PenaltyMethod::integrate_positions(StepContext& ctx) {
  for (RigidBody& b : ctx.bodies) {
    if (b.fixed) continue;
    advance_pose(b, b.v, b.omega, ctx.dt, ctx.scene.effects.gyroscopic, ctx.counters);
  }
}

}  // namespace boxpile
