#include "boxpile/sim/solver/penalty_method.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>

#include "boxpile/sim/io/own_settings.hpp"

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
  ++counters_.substeps;
}

void PenaltyMethod::apply_contact_forces(StepContext& ctx) {
  const bool friction = ctx.scene.effects.friction;
  const bool restitution = ctx.scene.effects.restitution;
  PenaltyCounters& counters = counters_;
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

nlohmann::json PenaltyMethod::diagnostics(std::size_t) const {
  // Its substeps and the work of its springs and anchors so far.
  const PenaltyCounters& p = counters_;
  return {{"method", "penalty"},
          {"substeps", p.substeps},
          {"spring_evaluations", p.spring_evaluations},
          {"anchors_created", p.anchors_created},
          {"sliding_points", p.sliding_points}};
}

namespace {
nlohmann::json optional_json(const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(); }
// The shortest decimal that reads back as x (as the loader's messages write numbers).
std::string shortest_decimal(double x) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}
}  // namespace

ContactMethodRow penalty_method_row() {
  using S = Scene;
  using nlohmann::json;
  using Kind = SettingInfo::Kind;
  ContactMethodRow row;
  row.name = "penalty";
  row.what = "the lab text's penalty method: damped springs at the contact points (docs/penalty.md)";
  row.settings = {
      // The penalty method (docs/penalty.md); each one left out is derived from the scene when the
      // world is built.
      {{.key = "stiffness", .kind = Kind::Number, .unit = "N/m", .what = "normal spring per contact point",
        .min = kSoftestSpring, .max = kStiffestSpring, .scene_key = "solver.stiffness"},
       [](S& s, const json& v) { s.solver.penalty.stiffness = v.get<double>(); },
       [](const S& s) { return optional_json(s.solver.penalty.stiffness); }},
      {{.key = "damping", .kind = Kind::Number, .unit = "N s/m",
        .what = "normal and tangential damper per contact point", .min = 0, .max = kStiffestSpring,
        .scene_key = "solver.damping"},
       [](S& s, const json& v) { s.solver.penalty.damping = v.get<double>(); },
       [](const S& s) { return optional_json(s.solver.penalty.damping); }},
      {{.key = "friction_stiffness", .kind = Kind::Number, .unit = "N/m", .what = "friction spring per contact point",
        .min = kSoftestSpring, .max = kStiffestSpring, .scene_key = "solver.friction_stiffness"},
       [](S& s, const json& v) { s.solver.penalty.friction_stiffness = v.get<double>(); },
       [](const S& s) { return optional_json(s.solver.penalty.friction_stiffness); }},
      {{.key = "substeps", .kind = Kind::Integer, .what = "penalty steps per scene step", .min = 1,
        .max = kMaxPenaltySubsteps, .scene_key = "solver.substeps"},
       [](S& s, const json& v) { s.solver.penalty.substeps = v.get<int>(); },
       [](const S& s) { return optional_json(s.solver.penalty.substeps); }},
  };
  row.make = [](const Scene& scene, const std::vector<RigidBody>& bodies) -> std::unique_ptr<ContactMethod> {
    const PenaltyParameters p = derive_penalty_parameters(scene);
    if (const std::string problem = penalty_parameters_problem(scene, p); !problem.empty())
      throw std::invalid_argument(scene.source + ": solver: " + problem);
    return std::make_unique<PenaltyMethod>(p, bodies.size());
  };
  row.work_per_step = [](const Scene& s) -> long { return derive_penalty_parameters(s).substeps; };
  row.time_step_problem = [](const Scene& s) { return penalty_parameters_problem(s, derive_penalty_parameters(s)); };
  // A damping set for every pair would leave the materials' restitution unread; a scene whose dt
  // breaks the stability bound, with substeps left to derive, is refused naming the bound; and
  // collision.reuse_contacts is the impulse method's (the penalty method tests every pair).
  row.check_scene = [](const json& root, const Scene& s) -> std::optional<SceneProblem> {
    if (root.contains("collision") && root["collision"].is_object() && root["collision"].contains("reuse_contacts")) {
      return SceneProblem{
          "/collision/reuse_contacts",
          "belongs to the impulse method, but solver.method is \"penalty\": the penalty method tests every pair "
          "at every step (its springs read each contact's depth); remove it or set solver.method to \"impulse\""};
    }
    if (s.solver.penalty.damping && s.effects.restitution) {
      double e = s.material.restitution;
      for (const BodyDesc& b : s.bodies)
        if (b.material) e = std::max(e, b.material->restitution);
      if (e > 0.0) {
        return SceneProblem{"/solver/damping",
                            "sets every contact's damping, so the materials' restitution (up to " +
                                shortest_decimal(e) +
                                ") would be ignored: the penalty method derives each pair's damping from its "
                                "restitution when \"damping\" is left out; remove one of them"};
      }
    }
    const PenaltyParameters p = derive_penalty_parameters(s);
    if (const std::string problem = penalty_parameters_problem(s, p); !problem.empty())
      return SceneProblem{"/time/dt", problem};
    return std::nullopt;
  };
  return row;
}

}  // namespace boxpile
