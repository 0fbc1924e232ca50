#include "boxpile/sim/solver/impulse_method.hpp"

#include <algorithm>
#include <cassert>

#include "boxpile/sim/solver/collision_loop.hpp"
#include "boxpile/sim/solver/contact_loop.hpp"
#include "boxpile/sim/solver/integrate.hpp"
#include "boxpile/sim/io/own_settings.hpp"
#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/thread_pool.hpp"

namespace boxpile {

namespace {

// What one contact costs a step's island stages on one thread, roughly (pile_100 and the heaps in
// motion, AMD EPYC): how the pool judges whether the islands are worth sharing (ThreadPool::shares).
constexpr double kContactStepSeconds = 0.5e-6;

// The fewest contacts in a group of islands whose contact loop runs in batches
// (solver.contact_batches): an island of one box on the ground fills one lane of each of its
// four batches, a group of islands some 85% of the lanes (pile_100).
constexpr int kGroupContacts = 64;

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

ImpulseMethod::ImpulseMethod(const Scene& scene, std::size_t body_count)
    : speculative_(scene.solver.speculative_contacts), reuse_(scene.collision.reuse_contacts) {
  start_v_.resize(body_count);
  start_omega_.resize(body_count);
  const StepStorage storage{body_count};
  solver_contacts_.reserve(storage.contacts());
  matrices_.reserve(storage.contacts());
  islands_.reserve(body_count, storage.contacts());
  last_order_.reserve(storage.contacts());
  resting_bodies_.reserve(body_count);
  shock_.reserve(storage);
  recovery_.reserve(storage);
  // One per thread of the world's pool, which has resolve_threads(solver.threads).
  workers_.resize(static_cast<std::size_t>(resolve_threads(scene.solver.threads)));
  batch_velocities_.reserve(body_count);
  group_end_.reserve(storage.contacts());
  for (Worker& w : workers_) {
    w.shock.active.reserve(body_count);
    w.recovery.reserve(storage);
    // A batch per four contacts: batches that fill fewer lanes grow the storage once.
    w.batches.reserve(storage.contacts(), storage.contacts() / kBatchLanes, body_count);
  }
}

template <class Stage>
void ImpulseMethod::for_each_island(StepContext& ctx, Stage&& stage) {
  assert(static_cast<std::size_t>(ctx.pool.size()) <= workers_.size());
  auto run_item = [&](int item, int w) {
    const int island = islands_.by_size()[static_cast<std::size_t>(item)];
    Worker& worker = workers_[static_cast<std::size_t>(w)];
    ImpulseStep step{ctx, SolverBodies{ctx.bodies, ctx.ground}, resting_bodies_, solver_contacts_, matrices_, worker.counters,
                     worker.stats};
    stage(step, islands_.begin(island), islands_.end(island), worker);
  };
  // The caller's thread takes the largest island; the others can share only the rest.
  const int count = islands_.count();
  const int largest = count > 0 ? islands_.end(islands_.by_size()[0]) - islands_.begin(islands_.by_size()[0]) : 0;
  const int shareable = static_cast<int>(solver_contacts_.size()) - largest;
  ctx.pool.run(count, run_item, shareable * kContactStepSeconds);
}

template <class Stage>
void ImpulseMethod::for_each_island_group(StepContext& ctx, Stage&& stage) {
  assert(static_cast<std::size_t>(ctx.pool.size()) <= workers_.size());
  // Consecutive islands joined until a group holds kGroupContacts: fixed by the islands alone, so
  // the same whatever the number of threads.
  group_end_.clear();
  const int count = islands_.count();
  int from = count > 0 ? islands_.begin(0) : 0, largest = 0;
  for (int i = 0; i < count; ++i) {
    const int end = islands_.end(i);
    if (end - from >= kGroupContacts || i == count - 1) {
      group_end_.push_back(end);
      largest = std::max(largest, end - from);
      from = end;
    }
  }
  auto run_item = [&](int item, int w) {
    const std::size_t g = static_cast<std::size_t>(item);
    const int begin = g == 0 ? islands_.begin(0) : group_end_[g - 1];
    Worker& worker = workers_[static_cast<std::size_t>(w)];
    ImpulseStep step{ctx, SolverBodies{ctx.bodies, ctx.ground}, resting_bodies_, solver_contacts_, matrices_, worker.counters,
                     worker.stats};
    stage(step, begin, group_end_[g], worker);
  };
  const int shareable = static_cast<int>(solver_contacts_.size()) - largest;
  ctx.pool.run(static_cast<int>(group_end_.size()), run_item, shareable * kContactStepSeconds);
}

void ImpulseMethod::merge_workers() {
  ImpulseStepStats& st = stats_;
  for (Worker& w : workers_) {
    counters_.impulses.normal_impulses += w.counters.normal_impulses;
    counters_.impulses.friction_evaluations += w.counters.friction_evaluations;
    counters_.impulses.sliding += w.counters.sliding;
    const ImpulseStepStats& ws = w.stats;
    st.collision_passes_used = std::max(st.collision_passes_used, ws.collision_passes_used);
    st.contact_passes_used = std::max(st.contact_passes_used, ws.contact_passes_used);
    for (int k = 0; k < kMaxSolverPasses; ++k) {
      st.collision_residual[k] = std::max(st.collision_residual[k], ws.collision_residual[k]);
      st.contact_residual[k] = std::max(st.contact_residual[k], ws.contact_residual[k]);
      st.shock_change[k] = std::max(st.shock_change[k], ws.shock_change[k]);
    }
    st.shock_pass_count = std::max(st.shock_pass_count, ws.shock_pass_count);
    st.shock_passes_used += ws.shock_passes_used;
    st.shock_parts += ws.shock_parts;
    st.shock_stalled_levels += ws.shock_stalled_levels;
    st.residual_after_shock = std::max(st.residual_after_shock, ws.residual_after_shock);
    w.counters = ImpulseCounters{};
    w.stats = ImpulseStepStats{};
  }
}

void ImpulseMethod::step(StepContext& ctx) {
  const SolverSettings& s = ctx.scene.solver;
  std::vector<RigidBody>& bodies = ctx.bodies;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    start_v_[i] = bodies[i].v;
    start_omega_[i] = bodies[i].omega;
  }

  // 1. The contact set (found by the world), as the solver sees it through the whole step, island
  // by island: each stage below runs over the islands, on the pool's threads.
  prepare_solver_contacts(ctx);
  if (same_set_) ++counters_.same_contact_sets;
  StepProfile& profile = ctx.counters.profile;
  profile.lap(Stage::prepare);
  stats_ = ImpulseStepStats{};
  ImpulseStep step{ctx, SolverBodies{bodies, ctx.ground}, resting_bodies_, solver_contacts_, matrices_, counters_.impulses, stats_};
  const auto contacts_of = [&](ImpulseStep& is, int begin, int end) {
    return std::span<SolverContact>(is.contacts.data() + begin, static_cast<std::size_t>(end - begin));
  };

  // 2. Collision loop: resolve approaching contacts with the scene's restitution.
  for_each_island(ctx, [&](ImpulseStep& is, int begin, int end, Worker&) { collision_loop(is, contacts_of(is, begin, end)); });
  // Events come only from impulses, and impulses only from a pass: a step in which no island ran
  // one (every point at rest or apart) has none to record.
  if (std::any_of(workers_.begin(), workers_.end(), [](const Worker& w) { return w.stats.collision_passes_used > 0; }))
    record_collision_events(step);
  ++counters_.collision_loop_runs;
  profile.lap(Stage::collision_loop);

  // 3. External forces on the momenta: gravity, air damping; the wires take their share.
  integrate_momenta(ctx);
  enforce_wires(bodies, ctx.wires);
  profile.lap(Stage::forces);

  // 4. Contact loop: every contact of the set, restitution ramped up to 0.
  resting_bodies_.gather(bodies);
  if (s.contact_batches && s.accumulated_impulses) {
    // In batches (contact_batches.hpp), island group by island group, on the batches' own copy of
    // the velocities. (Push-only impulses run one at a time: batches would not change their order.)
    batch_velocities_.gather(resting_bodies_, static_cast<int>(bodies.size()));
    for_each_island_group(ctx, [&](ImpulseStep& is, int begin, int end, Worker& w) {
      contact_loop(is, contacts_of(is, begin, end), &w.batches, &batch_velocities_);
    });
    batch_velocities_.scatter(resting_bodies_, bodies);
  } else {
    for_each_island(ctx, [&](ImpulseStep& is, int begin, int end, Worker&) { contact_loop(is, contacts_of(is, begin, end)); });
  }
  resting_bodies_.scatter(bodies);
  ++counters_.contact_loop_runs;
  enforce_wires(bodies, ctx.wires);
  profile.lap(Stage::contact_loop);

  // 5. Shock propagation: from the ground up, each level frozen once solved.
  if (s.shock_propagation) {
    shock_.prepare(step, same_set_);
    resting_bodies_.gather(bodies);
    // Each island's residual taken on its worker, from the compact bodies, while its contacts are
    // fresh; the step's is the largest (merge_workers).
    for_each_island(ctx, [&](ImpulseStep& is, int begin, int end, Worker& w) {
      shock_.solve_island(is, begin, end, w.shock);
      w.stats.residual_after_shock =
          std::max(w.stats.residual_after_shock, approach_residual(is.resting, contacts_of(is, begin, end), ctx.dt));
    });
    resting_bodies_.scatter(bodies);
    ++counters_.shock_propagation_runs;
  }
  enforce_wires(bodies, ctx.wires);
  profile.lap(Stage::shock_propagation);

  // Penetration recovery: pseudo-velocities that push overlaps apart (positions only).
  if (s.penetration_recovery > 0.0) {
    const ShockPropagation* levels = s.shock_propagation ? &shock_ : nullptr;
    // Recovery's targets read the velocities from the compact bodies, which hold the resting
    // phase's result: the wires may have changed some since.
    if (!ctx.wires.empty()) resting_bodies_.gather(bodies);
    if (recovery_.prepare(step))
      for_each_island(ctx, [&](ImpulseStep& is, int begin, int end, Worker& w) {
        recovery_.solve_island(is, levels, begin, end, w.recovery);
      });
    ++counters_.recovery_runs;
  }
  merge_workers();
  profile.lap(Stage::recovery);

  // 6. Positions and orientations; wired anchors back onto their wires.
  integrate_positions(ctx);
  project_wires(bodies, ctx.wires);
  profile.lap(Stage::integration);
}

void ImpulseMethod::prepare_solver_contacts(const StepContext& ctx) {
  // Last step's solver contacts stay in place: a contact the world kept from the last step at the
  // same index keeps its offsets and collision matrices (its bodies have not moved beyond
  // rounding since they were formed) and only takes back its K over both bodies where shock
  // propagation changed it.
  // The contacts are taken island by island (islands.hpp); a contact kept from the last step is
  // at its last place when the islands before it are the same too.
  islands_.find(ctx.contacts, ctx.bodies);
  const std::vector<int>& order = islands_.order();
  const std::size_t count = ctx.contacts.size();
  const std::size_t kept = std::min(last_order_.size(), count);
  same_set_ = count > 0 && count == solver_contacts_.size();
  solver_contacts_.resize(count);
  matrices_.resize(count);
  // A pair's contacts come one after another: its slop and material are found once per pair.
  PairTerms pair;
  for (std::size_t p = 0; p < count; ++p) {
    SolverContact& c = solver_contacts_[p];
    const std::size_t k = static_cast<std::size_t>(order[p]);
    const bool same = p < kept && last_order_[p] == order[p] && ctx.same_as_last_step[k];
    same_set_ = same_set_ && same;
    if (same) {
      // Its K is as prepared unless shock propagation set its frozen share: then it is formed
      // again from the shares, as below (the same sum, so the same K and inverse to the bit).
      if (c.frozen_k) set_collision_matrix(c, matrices_[p], true, true);
      continue;
    }
    const BodyContact& bc = ctx.contacts[k];
    const RigidBody& a = ctx.bodies[bc.body_a];
    const RigidBody& b = bc.body_b == kGround ? ctx.ground : ctx.bodies[bc.body_b];
    if (bc.body_a != pair.a || bc.body_b != pair.b) pair = pair_terms(ctx.scene.solver, bc.body_a, bc.body_b, a, b);
    // Filled where it stays: copying each SolverContact into the set cost a quarter of this
    // function (perf, Jenga tower, when it was some 600 bytes).
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
    set_collision_matrix(c, Ka + Kb);
    matrices_[p] = {Ka, Kb};
  }
  last_order_.assign(order.begin(), order.end());
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


ContactMethodRow impulse_method_row() {
  using S = Scene;
  using nlohmann::json;
  using Kind = SettingInfo::Kind;
  ContactMethodRow row;
  row.name = "impulse";
  row.what = "the Guendelman-Bridson-Fedkiw impulse method (docs/solver.md)";
  row.variants = {
      {"boxpile", "ours, every addition on", [](Scene& s) { set_impulse_additions(s.solver, s.collision, true); }},
      {"lab",
       "the lab text's, every addition off: pair_impulses, accumulated_impulses, speculative_contacts, "
       "sticking_solves, contact_batches, shock_propagation, reuse_contacts off, penetration_recovery 0, integrator explicit_euler",
       [](Scene& s) { set_impulse_additions(s.solver, s.collision, false); }},
  };
  row.settings = {
      scene_flag<&Scene::solver, &SolverSettings::pair_impulses>({.key = "pair_impulses", .kind = Kind::Boolean,
        .what = "collision loop: the approaching points of a pair get their normal impulses from one system "
                "(a flat landing stays flat); off: push-only Newton-Coulomb impulses point by point (the lab text)",
        .scene_key = "solver.pair_impulses"}),
      scene_flag<&Scene::solver, &SolverSettings::accumulated_impulses>({.key = "accumulated_impulses", .kind = Kind::Boolean,
        .what = "contact loop and shock propagation: each contact's impulse accumulated over the phase and "
                "projected on the friction cone (may take back what it gave); off: push-only impulses with "
                "the ramped restitution on the present u_n (the lab text)",
        .scene_key = "solver.accumulated_impulses"}),
      scene_flag<&Scene::solver, &SolverSettings::speculative_contacts>({.key = "speculative_contacts", .kind = Kind::Boolean,
        .what = "points up to contact_margin (or collision_margin) plus a step's motion apart are contacts that "
                "may close their gap in the step; off: touching or overlapping points only, both margins "
                "unused (the lab text)",
        .scene_key = "solver.speculative_contacts"}),
      scene_flag<&Scene::solver, &SolverSettings::sticking_solves>({.key = "sticking_solves", .kind = Kind::Boolean,
        .what = "shock propagation: a group of a level whose touching points can all stick is solved "
                "directly (least squares); off: every group by passes",
        .scene_key = "solver.sticking_solves"}),
      scene_flag<&Scene::solver, &SolverSettings::contact_batches>({.key = "contact_batches", .kind = Kind::Boolean,
        .what = "contact loop: the contacts regrouped into batches of four that share no moving body, a batch's "
                "accumulated impulses computed at once on the velocities (AVX2 where the processor has it, the "
                "same results without), where they fill enough lanes to pay; off: one contact at a time "
                "in the contact search's order, as push-only impulses always are",
        .scene_key = "solver.contact_batches"}),
      {{.key = "collision_passes", .kind = Kind::Integer, .what = "passes of the collision loop", .min = 1,
        .max = kMaxSolverPasses, .scene_key = "solver.collision_passes"},
       [](S& s, const json& v) { s.solver.collision_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.collision_passes); }},
      {{.key = "contact_passes", .kind = Kind::Integer, .what = "passes of the contact loop (restitution ramped to 0)",
        .min = 1, .max = kMaxSolverPasses, .scene_key = "solver.contact_passes"},
       [](S& s, const json& v) { s.solver.contact_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.contact_passes); }},
      scene_flag<&Scene::solver, &SolverSettings::shock_propagation>({.key = "shock_propagation", .kind = Kind::Boolean, .what = "shock propagation after the contact loop",
        .scene_key = "solver.shock_propagation"}),
      {{.key = "shock_passes", .kind = Kind::Integer, .what = "most passes over one level in shock propagation",
        .min = 1, .max = kMaxSolverPasses, .scene_key = "solver.shock_passes"},
       [](S& s, const json& v) { s.solver.shock_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.shock_passes); }},
      {{.key = "recovery_passes", .kind = Kind::Integer,
        .what = "most passes of penetration recovery per group of a phase (split impulses)", .min = 1,
        .max = kMaxSolverPasses, .scene_key = "solver.recovery_passes"},
       [](S& s, const json& v) { s.solver.recovery_passes = v.get<int>(); },
       [](const S& s) { return json(s.solver.recovery_passes); }},
      {{.key = "penetration_recovery", .kind = Kind::Number, .unit = "1/step",
        .what = "fraction of a penetration pushed out per step (0: off)", .min = 0, .max = 1,
        .scene_key = "solver.penetration_recovery"},
       [](S& s, const json& v) { s.solver.penetration_recovery = v.get<double>(); },
       [](const S& s) { return json(s.solver.penetration_recovery); }},
      {{.key = "penetration_slop", .kind = Kind::Number, .unit = "m", .what = "overlaps this shallow are left alone",
        .min = 0, .max = limits::kMaxMargin, .scene_key = "solver.penetration_slop"},
       [](S& s, const json& v) { s.solver.penetration_slop = v.get<double>(); },
       [](const S& s) { return json(s.solver.penetration_slop); }},
      {{.key = "integrator", .kind = Kind::Choice, .what = "position update",
        .choices = {"explicit_euler", "semi_implicit_euler"}, .scene_key = "solver.integrator"},
       [](S& s, const json& v) {
         s.solver.integrator = v.get<std::string>() == "explicit_euler" ? PositionIntegrator::ExplicitEuler
                                                                        : PositionIntegrator::SemiImplicitEuler;
       },
       [](const S& s) {
         return json(s.solver.integrator == PositionIntegrator::ExplicitEuler ? "explicit_euler" : "semi_implicit_euler");
       }},
      // The impulse method's alone: the penalty method tests every pair at every step.
      scene_flag<&Scene::collision, &CollisionSettings::reuse_contacts>({.key = "reuse_contacts", .kind = Kind::Boolean,
        .what = "copy a pair's contacts from the last step while neither body moves beyond rounding (1e-12)",
        .scene_key = "collision.reuse_contacts"}),
  };
  row.make = [](const Scene& scene, const std::vector<RigidBody>& bodies) -> std::unique_ptr<ContactMethod> {
    return std::make_unique<ImpulseMethod>(scene, bodies.size());
  };
  // Static friction is read by the penalty method's friction springs alone.
  row.check_scene = [](const json& root, const Scene&) -> std::optional<SceneProblem> {
    const std::string problem =
        "belongs to the penalty method (the impulse method has one coefficient, \"friction\"), but solver.method is "
        "\"impulse\": remove it or set solver.method to \"penalty\"";
    if (root.contains("material") && root["material"].is_object() && root["material"].contains("static_friction"))
      return SceneProblem{"/material/static_friction", problem};
    if (!root.contains("bodies") || !root["bodies"].is_array()) return std::nullopt;
    for (std::size_t i = 0; i < root["bodies"].size(); ++i) {
      const json& b = root["bodies"][i];
      if (b.is_object() && b.contains("material") && b["material"].is_object() &&
          b["material"].contains("static_friction"))
        return SceneProblem{"/bodies/" + std::to_string(i) + "/material/static_friction", problem};
    }
    return std::nullopt;
  };
  return row;
}

nlohmann::json ImpulseMethod::diagnostics(std::size_t events) const {
  const ImpulseStepStats& st = stats_;
  // Passes used and the residual (largest approaching normal velocity, m/s) after each pass, and
  // shock propagation's largest velocity change in each pass (m/s), for the convergence plots and
  // rates.
  nlohmann::json collision = nlohmann::json::array(), contact = nlohmann::json::array();
  for (int k = 0; k < st.collision_passes_used; ++k) collision.push_back(st.collision_residual[k]);
  for (int k = 0; k < st.contact_passes_used; ++k) contact.push_back(st.contact_residual[k]);
  nlohmann::json shock = nlohmann::json::array();
  for (int k = 0; k < st.shock_pass_count; ++k) shock.push_back(st.shock_change[k]);
  return {{"method", "impulse"},
          {"collision_passes", st.collision_passes_used},
          {"collision_residuals", collision},
          {"contact_residuals", contact},
          {"shock_changes", shock},
          {"shock_levels", st.shock_levels},
          {"residual_after_shock", st.residual_after_shock},
          {"collision_events", events}};
}

}  // namespace boxpile
