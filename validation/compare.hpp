// `boxpile compare`: one scene run in several engines, each measured with the same rulers, then
// compared engine against engine and against itself from a perturbed start (to tell a real
// difference from chaos), with the contact sets of chosen frames checked by all three detectors.
// docs/compare.md says what each result means and how report.json holds it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <map>

#include <nlohmann/json.hpp>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/metrics.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/compare_findings.hpp"
#include "boxpile/validation/contact_diff.hpp"
#include "boxpile/validation/outcomes.hpp"
#include "boxpile/validation/recording.hpp"
#include "boxpile/validation/stability_checks.hpp"
#include "boxpile/validation/stacks.hpp"

namespace boxpile {

// Where a run is, for a progress display: run `index` of `total` (engines and their baselines).
struct CompareProgress {
  std::string_view engine;
  bool baseline = false;  // the perturbed second run
  int index = 0;          // 0-based
  int total = 0;
  double fraction = 0.0;  // of this run's steps
};

struct CompareSettings {
  // The engines run, in order (the registry's compare list by default).
  std::vector<std::string> engines = default_engines(&DefaultLists::compare);
  // Settings {key: value} per engine, each checked against the engine's table (parse_set_options);
  // an engine left out runs at its defaults.
  std::map<std::string, nlohmann::json> engine_settings;
  // Every free body's start is moved by this much (across gravity; along the wire for a body on
  // one) for the baseline run of each engine, m.
  double perturbation = 1e-9;
  // Frames recorded per simulated second (at most one per step, always the first and the last).
  double frame_rate = 60.0;  // 1/s
  // A body's difference between two runs "passes" these when it first exceeds them.
  double position_threshold = 1e-2;     // m
  double orientation_threshold = 5e-2;  // rad (2.9 degrees)
  // Bodies this close count as touching for stacks and contact checks.
  double touch_tolerance = kTouchTolerance;  // m
  // Frames spread evenly over the run (the last at the end) at which contact sets are checked,
  // besides the frame of the deepest penetration.
  int contact_check_frames = 4;
  // Outcome statistics over perturbed starts (validation/outcomes.hpp): `outcomes.starts` runs per
  // engine after the compared runs; none when 0.
  OutcomeSettings outcomes;
  // Called at each recorded frame of each run.
  std::function<void(const CompareProgress&)> progress;
  // The settings given for `engine` ({} when none).
  nlohmann::json settings_of(const std::string& engine) const;
};

// An impact: a pair of bodies (or a body and the ground, body_b = kGround) approaching faster than
// resting contact explains, found the same way for every engine from the contact set it used in a
// step and the velocities before the step. Ours carry the impulse our solver applied
// (World::events()).
struct ImpactEvent {
  double t = 0.0;  // s, the start of the step
  int body_a = 0;
  int body_b = kGround;
  double approach_speed = 0.0;    // m/s
  std::optional<double> impulse;  // N s
};

// What an impact struck: the ground, or another body. The energy plot marks the two alike in
// every engine (a triangle, a circle) and report.json's events name it.
enum class ImpactKind { Ground, Bodies };
inline ImpactKind impact_kind(const ImpactEvent& e) { return e.body_b == kGround ? ImpactKind::Ground : ImpactKind::Bodies; }
inline const char* impact_kind_name(ImpactKind k) { return k == ImpactKind::Ground ? "ground" : "bodies"; }

// How well a body on a wire stayed on it through a run (every step measured).
struct WireReport {
  std::string body;
  double max_off = 0.0;       // m, largest distance of the anchor from the wire's line
  double max_past_end = 0.0;  // m, largest distance beyond an end
  double final_along = 0.0;   // m along the wire at the end
  double length = 0.0;        // m
};

struct EngineRun {
  std::string engine;
  // Every setting's value the engine ran with, defaults included (resolved_settings).
  nlohmann::json settings = nlohmann::json::object();
  long steps = 0;
  double wall_seconds = 0.0;  // stepping only
  double us_per_step = 0.0;
  // The recorded frames (CompareSettings::frame_rate), the bodies' shapes and the contact sets;
  // `recording.stopped` says where a run that blew up stopped.
  Recording recording;
  std::vector<BodyState> final_states;
  double final_t = 0.0;
  // Measured at every step.
  double energy_initial = 0.0, energy_final = 0.0, energy_max = 0.0;  // J
  double energy_max_t = 0.0;                                          // s
  Penetration deepest;  // over the whole run
  double deepest_t = 0.0;
  // Per recorded frame, the deepest penetration of every step since the frame before (the frame
  // at the start: its own): the penetration plot draws these, so that no peak between frames is
  // lost; their largest is `deepest.depth`.
  std::vector<double> interval_penetration;  // m
  double levitation_max = 0.0;  // m, over the recorded frames after the start
  double levitation_final = 0.0;
  std::vector<ImpactEvent> events;
  std::vector<StackReport> stacks;  // at the end
  std::vector<WireReport> wires;
  bool finite = true;  // every state finite through the run
  // Why the run stopped early: the first non-finite state (step, body, quantity), from this run
  // or the perturbed baseline. The report marks the engine failed; the command exits 1.
  std::optional<std::string> failure;
  std::uint64_t engine_messages = 0;  // ODE's messages during the run
  // The scene's checks (validation/stability_checks.hpp), measured at every step.
  RunMeasures measures;
  std::vector<SceneCheckResult> checks;
};

// One body's difference between two runs of the same scene over the recorded frames.
struct BodyDifference {
  std::string name;
  std::vector<double> position;     // m, per frame
  std::vector<double> orientation;  // rad, per frame
  double max_position = 0.0, max_orientation = 0.0;
  std::optional<double> position_passes, orientation_passes;  // s, first over the threshold
};

// Two runs compared frame by frame: "a" against "b" (b is "<engine> perturbed" for a baseline).
struct RunDifference {
  std::string a, b;
  std::vector<double> t;
  std::vector<BodyDifference> bodies;
  std::vector<double> max_position;  // m, per frame, the largest over the bodies
  double largest_position = 0.0, largest_orientation = 0.0;
  std::string largest_position_body, largest_orientation_body;
  std::optional<double> position_passes, orientation_passes;  // s, the first body to pass
};

// An engine against itself started 1e-9 m away: how fast it diverges from itself.
struct Baseline {
  std::string engine;
  RunDifference divergence;
  // The mean exponential growth rate of the difference up to its largest value,
  // ln(largest / perturbation) / t_largest, 1/s (<= 0: the difference does not grow).
  double growth_rate = 0.0;
};

// Two engines against each other, with the verdict of the baselines.
struct PairComparison {
  RunDifference difference;
  // The earlier of the two engines' own times to pass the position threshold (empty when
  // neither diverges from itself that far).
  std::optional<double> chaos_time;
  // "unstable": one engine of the two shows instability (first_instability: a NaN, a rise of
  // energy, resting bodies that keep moving) and the other does not, whatever the differences;
  // else "agree": never past the threshold; "chaos": past it no earlier than half the chaos
  // time; "differ": past it before chaos explains it.
  std::string verdict;
  std::string unstable_engine;  // the engine that is unstable (verdict "unstable")
  std::string instability;      // its failed check, e.g. "energy_rise 0.11 > 0.0001"
  // With `--starts N` (CompareResult::outcomes): how often the two agree start by start, and
  // whether their outcomes differ beyond what perturbed starts cause. "chaos" holds only when
  // they do not: a pair whose outcomes differ is "differ" with `beyond_chaos` saying which
  // measures.
  std::optional<int> starts_compared, starts_agreeing;
  std::string beyond_chaos;
};

// One detector's contact set of a pair: its point count and how it differs from ours.
struct DetectorCheck {
  std::string detector;
  int points = 0;
  ContactDiff diff;  // against ours (ours against itself for "own")
};

// One touching pair of boxes (or a box and the ground) at a checked frame, through every
// detector of the table that applies to box-box and box-plane alike (validation/detectors.hpp):
// ours first, then ODE's and Bullet's.
struct ContactPairCheck {
  int body_a = 0, shape_a = 0;
  int body_b = kGround, shape_b = 0;
  std::vector<DetectorCheck> detectors;
  // The check of one detector (it must be among them).
  const DetectorCheck& of(std::string_view detector) const;
};

// The largest disagreement of one kind at a checked frame: "normal_angle" between the mean
// normals (rad), "depth_difference" of the deepest points (m, absolute), "point_distance": how far
// the smaller point set lies outside the contact region of the larger (m, 0 when one set lies
// within the other's region; ContactDiff::hull_distance). Values up to 1e-9 (rounding) are not
// listed.
struct ContactDisagreement {
  std::string metric;
  std::string reference;  // a detector other than ours: "ode" or "bullet"
  double value = 0.0;
  ContactPairCheck pair;
};

struct ContactFrameCheck {
  std::string engine;  // whose poses
  std::string why;     // how the frame was chosen
  std::size_t frame = 0;
  double t = 0.0;
  int pairs = 0;            // touching pairs checked
  int count_mismatches = 0;  // pairs where the detectors give different point counts
  std::vector<ContactDisagreement> worst;  // largest first within each metric
};

struct CompareResult {
  Scene scene;  // as run (dt and duration overridden)
  CompareSettings settings;
  long steps = 0;
  std::vector<Stack> start_stacks;
  std::vector<EngineRun> runs;
  std::vector<Baseline> baselines;  // one per engine, in the same order
  std::vector<PairComparison> pairs;
  std::vector<ContactFrameCheck> contacts;
  std::optional<OutcomeStatistics> outcomes;  // when settings.outcomes.starts > 0
  // What the runs show engine by engine (validation/compare_findings.hpp).
  std::vector<CompareFinding> findings;
};

// Runs the scene in each engine (then again from the perturbed start), one after the other (ODE's
// random generator is global), and compares. Throws UnknownEngine for an engine not available.
CompareResult run_compare(const Scene& scene, const CompareSettings& settings);

// The pieces, for tests and other tools.
EngineRun run_engine(const Scene& scene, std::string_view engine, const CompareSettings& settings,
                     const std::function<void(double)>& progress = {});
// The scene with every free body moved by `distance` (see CompareSettings::perturbation).
Scene perturbed_scene(const Scene& scene, double distance);
RunDifference diff_runs(const std::string& a, const FrameSeries& fa, const std::string& b,
                        const FrameSeries& fb, double position_threshold, double orientation_threshold);
ContactFrameCheck check_contacts(const Scene& scene, const std::vector<BodyState>& states,
                                 double touch_tolerance);

}  // namespace boxpile
