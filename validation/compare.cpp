#include "boxpile/validation/compare.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>


#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/sim/collision/broadphase.hpp"
#include "boxpile/sim/finite.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/sim/solver/step_context.hpp"
#include "boxpile/validation/detectors.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/run_loop.hpp"
#include "boxpile/validation/state_meter.hpp"
#include "boxpile/validation/wire_check.hpp"

namespace boxpile {
namespace {

// The golden angle turns each body's perturbation away from the last one's, so that no two
// neighbours are pushed the same way.
constexpr double kGoldenAngle = 2.399963229728653;  // rad

// Contact disagreements at or below this are rounding (angles in rad, distances in m), not listed:
// the hull tolerance of contact_diff.hpp, far above the 1e-15 of agreeing detectors (boxes of a
// few metres) and far below any contact feature.
constexpr double kNegligibleDisagreement = kHullTolerance;

// A pair passes for chaos when it first differs no earlier than this fraction of the time the
// engines take to diverge from themselves.
constexpr double kChaosFraction = 0.5;



// Impacts in one step of a reference engine: each contact point of the step's set approaching
// faster than `speed` with the velocities before the step, and closing its gap within the step
// (a point still apart may approach at up to gap / dt), one event per pair and step.
void find_impacts(const std::vector<BodyContact>& contacts, const std::vector<RigidBody>& before,
                  double t, double dt, double speed, std::vector<ImpactEvent>& events) {
  const std::size_t first = events.size();
  for (const BodyContact& bc : contacts) {
    const Contact& c = bc.contact;
    const RigidBody& a = before[static_cast<std::size_t>(bc.body_a)];
    Vec3 relative = a.velocity_at(c.position);
    if (bc.body_b != kGround) relative -= before[static_cast<std::size_t>(bc.body_b)].velocity_at(c.position);
    const double approach = -c.normal.dot(relative);
    if (approach <= speed || (c.depth < 0.0 && approach * dt < -c.depth)) continue;
    auto same = [&](const ImpactEvent& e) { return e.body_a == bc.body_a && e.body_b == bc.body_b; };
    const auto it = std::find_if(events.begin() + static_cast<std::ptrdiff_t>(first), events.end(), same);
    if (it == events.end()) {
      events.push_back({t, bc.body_a, bc.body_b, approach, std::nullopt});
    } else {
      it->approach_speed = std::max(it->approach_speed, approach);
    }
  }
}

// Our solver records the impulse of each collision it resolved: attached to the impact found from
// outside in the same step for the same pair. (Its own approach speed is not used: it is measured
// during the sequential passes, after other points' impulses have turned the body, so a box
// landing flat at 4.45 m/s reads 4.88 m/s at its last corner.)
void attach_impulses(const std::vector<CollisionEvent>& recorded, double dt, std::vector<ImpactEvent>& events) {
  for (const CollisionEvent& e : recorded) {
    for (ImpactEvent& ev : events) {
      if (ev.body_a == e.body_a && ev.body_b == e.body_b && std::abs(ev.t - e.time) < 0.5 * dt) ev.impulse = e.impulse;
    }
  }
}

// The tallest stack of a pose, 0 when there is none.
double tallest_stack(const std::vector<RigidBody>& bodies, const Scene& scene, double tolerance) {
  double tallest = 0.0;
  for (const Stack& s : find_stacks(bodies, scene, tolerance)) tallest = std::max(tallest, s.height);
  return tallest;
}

// Watches every body on a wire through a run.
class WireWatch {
 public:
  explicit WireWatch(const Scene& scene) : scene_(scene) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const auto& wire = scene.bodies[i].wire;
      if (!wire) continue;
      index_.push_back(i);
      reports_.push_back({scene.bodies[i].name, 0.0, 0.0, 0.0, (wire->to - wire->from).norm()});
    }
  }
  void measure(const std::vector<BodyState>& states) {
    for (std::size_t k = 0; k < index_.size(); ++k) {
      const WireGap g = wire_gap(*scene_.bodies[index_[k]].wire, states[index_[k]]);
      reports_[k].max_off = std::max(reports_[k].max_off, g.off);
      reports_[k].max_past_end = std::max(reports_[k].max_past_end, g.past_end);
      reports_[k].final_along = g.along;
    }
  }
  const std::vector<WireReport>& reports() const { return reports_; }

 private:
  const Scene& scene_;
  std::vector<std::size_t> index_;
  std::vector<WireReport> reports_;
};

EngineRun run_one(const Scene& scene_file, std::string_view name, const CompareSettings& settings,
                  RecordDetail detail, const std::function<void(double)>& progress) {
  EngineRun run;
  run.engine = std::string(name);
  const nlohmann::json given = settings.settings_of(run.engine);
  const std::unique_ptr<Engine> engine = make_engine(name, scene_file, given);
  run.settings = resolved_settings(name, scene_file, given);
  // What the engine runs (its time step, and our solver's settings): the steps and the rulers.
  const Scene scene = scene_with_settings(name, scene_file, given);
  const bool full = detail == RecordDetail::Full;
  const double dt = scene.time.dt;
  const long steps = step_count(scene.time);
  const double speed = collision_event_speed(scene, scene.time.dt);

  StateMeter meter(scene);
  RunMonitor monitor(scene);
  WireWatch wires(scene);
  Recorder recorder(scene, run.engine, detail);
  std::vector<RigidBody> posed = make_bodies(scene);
  std::vector<BodyContact> contacts;
  double interval_deepest = 0.0;  // since the last recorded frame

  // Every step: energy, penetration and the wires measured, impacts found.
  auto measure_step = [&](const StepView& v) {
    recorder.first_step(v);
    monitor.observe(v.step, v.states);
    const FrameMetrics m = meter.measure_step(v.states);
    const double e = m.energy.total();
    if (v.step == 0) run.energy_initial = run.energy_max = e;
    if (e > run.energy_max) {
      run.energy_max = e;
      run.energy_max_t = v.t;
    }
    run.energy_final = e;
    if (m.penetration.depth > run.deepest.depth) {
      run.deepest = m.penetration;
      run.deepest_t = v.t;
    }
    interval_deepest = std::max(interval_deepest, m.penetration.depth);
    wires.measure(v.states);
    if (v.step == 0) return;
    v.engine.contacts(contacts);
    set_body_states(posed, v.before);
    find_impacts(contacts, posed, v.t - dt, dt, speed, run.events);
  };
  // Every frame: the recording, the tallest stack and levitation.
  auto record = [&](const StepView& v) {
    recorder.frame(v);
    if (progress && v.step > 0) progress(static_cast<double>(v.step) / static_cast<double>(steps));
    if (!full) return;
    run.interval_penetration.push_back(interval_deepest);
    interval_deepest = 0.0;
    set_body_states(posed, v.states);
    recorder.recording().frames.stack_height.push_back(tallest_stack(posed, scene, settings.touch_tolerance));
    // At the start every body is at rest, wherever the scene put it: a body placed in the air
    // is not levitating yet.
    const double levitation = recorder.last_metrics().levitation;
    if (v.step > 0) run.levitation_max = std::max(run.levitation_max, levitation);
    run.levitation_final = levitation;
  };

  RunHooks hooks;
  if (full) hooks.step = measure_step;
  hooks.frame = record;
  const RunLoopResult loop =
      run_loop(*engine, dt, steps, steps_per_frame(dt, settings.frame_rate), hooks);

  run.steps = loop.steps;
  run.wall_seconds = loop.wall_seconds;
  run.us_per_step = loop.steps > 0 ? 1e6 * loop.engine_seconds / static_cast<double>(loop.steps) : 0.0;
  run.final_states = loop.final_states;
  run.final_t = loop.final_t;
  run.finite = !loop.stopped;
  if (loop.stopped) run.failure = loop.stopped->description;
  run.recording = std::move(recorder.recording());
  run.recording.stopped = loop.stopped;
  run.engine_messages = engine->messages();
  if (!full) return run;

  if (loop.stopped) monitor.stopped_non_finite();
  run.measures = monitor.measures();
  run.checks = monitor.evaluate();
  if (const auto* recorded = engine->collision_events()) attach_impulses(*recorded, dt, run.events);
  run.wires = wires.reports();
  const std::vector<RigidBody> start = make_bodies(scene);
  set_body_states(posed, run.final_states);
  run.stacks = report_stacks(find_stacks(posed, scene, settings.touch_tolerance),
                             find_stacks(start, scene, settings.touch_tolerance), posed);
  return run;
}

double growth_rate(const RunDifference& d, double perturbation) {
  const auto largest = std::max_element(d.max_position.begin(), d.max_position.end());
  if (largest == d.max_position.end() || !(*largest > 0.0) || !(perturbation > 0.0)) return 0.0;
  const double t = d.t[static_cast<std::size_t>(largest - d.max_position.begin())];
  return t > 0.0 ? std::log(*largest / perturbation) / t : 0.0;
}

// "chaos" is a disagreement no larger than perturbed starts cause: with outcome statistics, a
// pair whose outcomes differ beyond the engines' own spread is "differ" instead, and every pair
// carries its start-by-start agreement.
void judge_chaos_by_outcomes(const OutcomeStatistics& outcomes, std::vector<PairComparison>& pairs) {
  for (PairComparison& p : pairs) {
    for (const OutcomePair& o : outcomes.pairs) {
      if (!((o.a == p.difference.a && o.b == p.difference.b) || (o.a == p.difference.b && o.b == p.difference.a)))
        continue;
      p.starts_compared = o.starts_compared;
      p.starts_agreeing = o.starts_agreeing;
      if (p.verdict != "chaos" || !o.differ) break;
      p.verdict = "differ";
      for (const MeasureTest& t : o.tests)
        if (t.differ) p.beyond_chaos += (p.beyond_chaos.empty() ? "" : ", ") + t.measure;
      p.beyond_chaos = "the outcomes over " + std::to_string(o.starts_compared) + " perturbed starts differ beyond "
                       "their own spread (" + p.beyond_chaos + ")";
      break;
    }
  }
}

std::string verdict(const RunDifference& d, const std::optional<double>& chaos_time) {
  if (!d.position_passes) return "agree";
  if (chaos_time && *d.position_passes >= kChaosFraction * *chaos_time) return "chaos";
  return "differ";
}

// The frames of the first engine's run at which contact sets are checked: evenly spread (the last
// at the end) and the one nearest after the deepest penetration.
std::vector<std::pair<std::size_t, std::string>> contact_frames(const EngineRun& run, int count) {
  std::vector<std::pair<std::size_t, std::string>> chosen;
  const std::vector<double>& t = run.recording.frames.t;
  if (t.empty()) return chosen;
  auto nearest_at_or_after = [&](double time) {
    const auto it = std::lower_bound(t.begin(), t.end(), time - 1e-12);
    return it == t.end() ? t.size() - 1 : static_cast<std::size_t>(it - t.begin());
  };
  for (int k = 1; k <= count; ++k) {
    const double time = t.back() * k / count;
    chosen.emplace_back(nearest_at_or_after(time),
                        k == count ? std::string("the end") : std::to_string(100 * k / count) + "% of the run");
  }
  if (run.deepest.depth > 0.0) chosen.emplace_back(nearest_at_or_after(run.deepest_t), "the deepest penetration");
  std::stable_sort(chosen.begin(), chosen.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  // One check per frame; the first reason given for it stays.
  const auto same_frame = [](const auto& a, const auto& b) { return a.first == b.first; };
  chosen.erase(std::unique(chosen.begin(), chosen.end(), same_frame), chosen.end());
  return chosen;
}

}  // namespace

EngineRun run_engine(const Scene& scene, std::string_view engine, const CompareSettings& settings,
                     const std::function<void(double)>& progress) {
  return run_one(scene, engine, settings, RecordDetail::Full, progress);
}

Scene perturbed_scene(const Scene& scene, double distance) {
  Scene s = scene;
  const auto [u, v] = across_directions(down_direction(scene.gravity));
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    BodyDesc& b = s.bodies[i];
    if (b.fixed) continue;
    Vec3 direction;
    if (b.wire) {
      // Along the wire, toward its middle, so that the anchor stays on it.
      const Vec3 along = (b.wire->to - b.wire->from).normalized();
      const double s_start = (b.frame.apply(b.wire->anchor) - b.wire->from).dot(along);
      direction = 2.0 * s_start < (b.wire->to - b.wire->from).norm() ? along : Vec3(-along);
    } else {
      const double angle = kGoldenAngle * static_cast<double>(i);
      direction = std::cos(angle) * u + std::sin(angle) * v;
    }
    b.frame.position += distance * direction;
  }
  return s;
}

RunDifference diff_runs(const std::string& a, const FrameSeries& fa, const std::string& b,
                        const FrameSeries& fb, double position_threshold, double orientation_threshold) {
  RunDifference d;
  d.a = a;
  d.b = b;
  // Each frame of `fa` against `fb`'s nearest in time: one frame for one when both ran at one
  // time step, the frames of runs at different time steps (`--set ENGINE.dt`) up to half a frame
  // apart otherwise. `fa`'s frames past `fb`'s last (a run stopped early) are left out.
  std::vector<std::size_t> match;
  const double half_frame = fa.t.size() > 1 ? 0.5 * (fa.t[1] - fa.t[0]) : 0.0;
  for (std::size_t f = 0, g = 0; f < fa.t.size() && !fb.t.empty(); ++f) {
    if (fa.t[f] > fb.t.back() + half_frame) break;
    while (g + 1 < fb.t.size() && std::abs(fb.t[g + 1] - fa.t[f]) <= std::abs(fb.t[g] - fa.t[f])) ++g;
    match.push_back(g);
  }
  const std::size_t frames = match.size();
  d.t.assign(fa.t.begin(), fa.t.begin() + static_cast<std::ptrdiff_t>(frames));
  const std::size_t n = frames > 0 ? fa.states[0].size() : 0;
  d.bodies.resize(n);
  d.max_position.assign(frames, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    BodyDifference& body = d.bodies[i];
    body.name = fa.states[0][i].name;
    body.position.resize(frames);
    body.orientation.resize(frames);
    for (std::size_t f = 0; f < frames; ++f) {
      const BodyState& sa = fa.states[f][i];
      const BodyState& sb = fb.states[match[f]][i];
      const double dp = (sa.position - sb.position).norm();
      const double dq = sa.orientation.angularDistance(sb.orientation);
      body.position[f] = dp;
      body.orientation[f] = dq;
      body.max_position = std::max(body.max_position, dp);
      body.max_orientation = std::max(body.max_orientation, dq);
      d.max_position[f] = std::max(d.max_position[f], dp);
      if (!body.position_passes && dp > position_threshold) body.position_passes = d.t[f];
      if (!body.orientation_passes && dq > orientation_threshold) body.orientation_passes = d.t[f];
    }
    if (body.max_position > d.largest_position || d.largest_position_body.empty()) {
      d.largest_position = body.max_position;
      d.largest_position_body = body.name;
    }
    if (body.max_orientation > d.largest_orientation || d.largest_orientation_body.empty()) {
      d.largest_orientation = body.max_orientation;
      d.largest_orientation_body = body.name;
    }
    auto earliest = [](std::optional<double>& into, const std::optional<double>& t) {
      if (t && (!into || *t < *into)) into = t;
    };
    earliest(d.position_passes, body.position_passes);
    earliest(d.orientation_passes, body.orientation_passes);
  }
  return d;
}

namespace {

// The detectors that apply to box-box and box-plane pairs alike, ours first.
std::vector<const DetectorInfo*> pair_detectors() {
  std::vector<const DetectorInfo*> shown;
  for (const DetectorInfo& d : detectors()) {
    if (d.box_plane_only) continue;
    if (d.name == kOwnDetector) {
      shown.insert(shown.begin(), &d);
    } else {
      shown.push_back(&d);
    }
  }
  return shown;
}

}  // namespace

const DetectorCheck& ContactPairCheck::of(std::string_view detector) const {
  for (const DetectorCheck& d : detectors) {
    if (d.detector == detector) return d;
  }
  throw std::out_of_range("no contact check of detector " + std::string(detector));
}

ContactFrameCheck check_contacts(const Scene& scene, const std::vector<BodyState>& states,
                                 double touch_tolerance) {
  ContactFrameCheck check;
  std::vector<RigidBody> bodies = make_bodies(scene);
  set_body_states(bodies, states);
  CollisionSettings own_settings = scene.collision;
  own_settings.margin = std::max(own_settings.margin, touch_tolerance);

  DetectOptions options;
  options.own = own_settings;
  options.plane_margin = touch_tolerance;
  const std::vector<const DetectorInfo*> shown = pair_detectors();

  std::vector<ContactPairCheck> pairs;
  // Runs every detector on the pair through `detect` and keeps the pair's check.
  auto add = [&](int ia, int sa, int ib, int sb, const auto& detect) {
    ContactPairCheck p{ia, sa, ib, sb, {}};
    const Manifold own = detect(*shown.front());
    for (const DetectorInfo* d : shown) {
      const Manifold m = d == shown.front() ? own : detect(*d);
      p.detectors.push_back({std::string(d->name), m.size(), diff_contacts(own, m)});
    }
    pairs.push_back(std::move(p));
  };
  auto box_of = [&](int body, int shape) {
    const RigidBody& b = bodies[static_cast<std::size_t>(body)];
    return OrientedBox::from(b.shape_pose(shape), b.shapes[static_cast<std::size_t>(shape)].half_extents);
  };

  const int n = static_cast<int>(bodies.size());
  for (int i = 0; i < n; ++i) {
    const RigidBody& bi = bodies[static_cast<std::size_t>(i)];
    if (!finite_magnitude(bi.x)) continue;
    const int shapes_i = static_cast<int>(bi.shapes.size());
    if (scene.ground && !bi.fixed) {
      for (int s = 0; s < shapes_i; ++s) {
        const OrientedBox box = box_of(i, s);
        if (box_plane_depth(box, *scene.ground) < -touch_tolerance) continue;
        add(i, s, kGround, 0, [&](const DetectorInfo& d) { return d.box_plane(box, *scene.ground, options); });
      }
    }
    const Aabb aabb_i = body_aabb(bi, touch_tolerance);
    for (int j = i + 1; j < n; ++j) {
      const RigidBody& bj = bodies[static_cast<std::size_t>(j)];
      if ((bi.fixed && bj.fixed) || !finite_magnitude(bj.x) || !aabb_i.overlaps(body_aabb(bj, 0.0))) continue;
      for (int s = 0; s < shapes_i; ++s) {
        const OrientedBox a = box_of(i, s);
        for (int t = 0; t < static_cast<int>(bj.shapes.size()); ++t) {
          const OrientedBox b = box_of(j, t);
          if (box_box_sat(a, b, touch_tolerance).separation > touch_tolerance) continue;
          add(i, s, j, t, [&](const DetectorInfo& d) { return d.box_box(a, b, options); });
        }
      }
    }
  }

  check.pairs = static_cast<int>(pairs.size());
  for (const ContactPairCheck& p : pairs) {
    const int own = p.detectors.front().points;
    if (std::any_of(p.detectors.begin(), p.detectors.end(), [own](const DetectorCheck& d) { return d.points != own; })) {
      ++check.count_mismatches;
    }
  }
  using Getter = std::optional<double> (*)(const ContactDiff&);
  const std::array<std::pair<const char*, Getter>, 3> metrics = {{
      {"normal_angle", [](const ContactDiff& d) { return d.normal_angle; }},
      {"depth_difference",
       [](const ContactDiff& d) {
         return d.depth_difference ? std::optional<double>(std::abs(*d.depth_difference)) : std::nullopt;
       }},
      {"point_distance", [](const ContactDiff& d) { return d.hull_distance; }},
  }};
  for (const auto& [metric, get] : metrics) {
    const std::size_t first = check.worst.size();
    for (std::size_t k = 1; k < shown.size(); ++k) {
      const std::string reference(shown[k]->name);
      const ContactPairCheck* worst = nullptr;
      double value = kNegligibleDisagreement;
      for (const ContactPairCheck& p : pairs) {
        const std::optional<double> v = get(p.detectors[k].diff);
        if (v && *v > value) {
          value = *v;
          worst = &p;
        }
      }
      if (worst) check.worst.push_back({metric, reference, value, *worst});
    }
    // Within each metric, the larger disagreement first.
    std::stable_sort(check.worst.begin() + static_cast<std::ptrdiff_t>(first), check.worst.end(),
                     [](const ContactDisagreement& a, const ContactDisagreement& b) { return a.value > b.value; });
  }
  return check;
}

nlohmann::json CompareSettings::settings_of(const std::string& engine) const {
  const auto it = engine_settings.find(engine);
  return it == engine_settings.end() ? nlohmann::json::object() : it->second;
}

CompareResult run_compare(const Scene& scene, const CompareSettings& settings) {
  CompareResult result;
  result.scene = scene;
  result.settings = settings;
  result.steps = step_count(scene.time);
  std::vector<std::string> names;
  for (const std::string& name : settings.engines) {
    check_engine_name(name);  // all of them before the first run
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  result.settings.engines = names;
  result.start_stacks = find_stacks(make_bodies(scene), scene, settings.touch_tolerance);

  const Scene perturbed = perturbed_scene(scene, settings.perturbation);
  const int total = 2 * static_cast<int>(names.size());
  for (std::size_t e = 0; e < names.size(); ++e) {
    auto progress_of = [&](bool baseline) {
      return [&, baseline](double fraction) {
        if (!settings.progress) return;
        settings.progress({names[e], baseline, static_cast<int>(2 * e) + (baseline ? 1 : 0), total, fraction});
      };
    };
    result.runs.push_back(run_one(scene, names[e], settings, RecordDetail::Full, progress_of(false)));
    const EngineRun again = run_one(perturbed, names[e], settings, RecordDetail::StatesOnly, progress_of(true));
    if (again.failure && !result.runs.back().failure) {
      result.runs.back().failure = "from the perturbed start, " + *again.failure;
    }
    Baseline b;
    b.engine = names[e];
    b.divergence = diff_runs(names[e], result.runs.back().recording.frames, names[e] + " perturbed",
                               again.recording.frames,
                             settings.position_threshold, settings.orientation_threshold);
    b.growth_rate = growth_rate(b.divergence, settings.perturbation);
    result.baselines.push_back(std::move(b));
  }

  for (std::size_t i = 0; i < names.size(); ++i) {
    for (std::size_t j = i + 1; j < names.size(); ++j) {
      PairComparison p;
      p.difference = diff_runs(names[i], result.runs[i].recording.frames, names[j], result.runs[j].recording.frames,
                               settings.position_threshold, settings.orientation_threshold);
      for (const std::size_t k : {i, j}) {
        const std::optional<double>& t = result.baselines[k].divergence.position_passes;
        if (t && (!p.chaos_time || *t < *p.chaos_time)) p.chaos_time = t;
      }
      p.verdict = verdict(p.difference, p.chaos_time);
      const SceneCheckResult* unstable_i = first_instability(result.runs[i].checks);
      const SceneCheckResult* unstable_j = first_instability(result.runs[j].checks);
      if ((unstable_i == nullptr) != (unstable_j == nullptr)) {
        const SceneCheckResult& failed = unstable_i ? *unstable_i : *unstable_j;
        p.verdict = "unstable";
        p.unstable_engine = unstable_i ? names[i] : names[j];
        p.instability = describe(failed);
      }
      result.pairs.push_back(std::move(p));
    }
  }

  if (!result.runs.empty()) {
    const EngineRun& first = result.runs.front();
    for (const auto& [frame, why] : contact_frames(first, settings.contact_check_frames)) {
      ContactFrameCheck c = check_contacts(scene, first.recording.frames.states[frame], settings.touch_tolerance);
      c.engine = first.engine;
      c.why = why;
      c.frame = frame;
      c.t = first.recording.frames.t[frame];
      result.contacts.push_back(std::move(c));
    }
  }
  if (settings.outcomes.starts > 0) {
    std::vector<OutcomeEntry> entries;
    for (const std::string& name : names) entries.push_back({name, name, settings.settings_of(name)});
    result.outcomes = run_outcomes(scene, entries, settings.outcomes);
    judge_chaos_by_outcomes(*result.outcomes, result.pairs);
  }
  result.findings = compare_findings(result);
  return result;
}

}  // namespace boxpile
