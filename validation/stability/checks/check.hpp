// One check of a scene's "checks" object (docs/scene-format.md, "Checks"): the row that declares
// it, keyed by its key in the object, and the observer that measures it over a run.
//
// Every check is one file in this folder. A file NAME.cpp defines `const CheckRow& NAME_check()`;
// CMake lists the folder and generates the table from the file names (validation/CMakeLists.txt),
// so a new check is its file, a fixture that holds it and a line in docs/scene-format.md. Each
// check reads its own node of the scene file (errors are InputErrors at the node's path, so they
// read "scene.json: checks.rest.max_move: must be > 0"), watches the body states after every
// step, and gives one result or more at the end. RunMonitor (stability_checks.hpp) keeps the
// figures every check shares (RunMeasures) and hands them to each.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// One scene check's outcome: the measured value against its limit.
struct SceneCheckResult {
  std::string name;   // "energy_rise", "rest_speed", "rest_move", "no_turning", "rebound", "slide mu_0.30", ...
  double value = 0.0;
  double limit = 0.0;
  bool at_least = false;  // passes when value >= limit (else value <= limit)
  bool passed = false;
  std::string unit;  // "J", "m", "rad/s", "" for fractions
  std::string key;     // the scene's check key it comes from ("rest" for rest_speed and rest_move)
  std::string reason;  // why the limit is what it is (the scene's checks.reasons), empty if not given
};

// Error figures of one run, measured alike for every engine.
struct RunMeasures {
  bool finite = true;          // every state finite at every step observed
  long steps = 0;              // steps observed after the start
  double energy_start = 0.0;   // J, kinetic + gravitational (potential zero at the origin)
  double energy_rise = 0.0;    // largest (E - E0) / |E0| over the steps (0 if E never rose)
  double energy_rise_t = 0.0;  // s, when
  double energy_change = 0.0;  // largest |E - E0| / |E0|
  double kinetic_end = 0.0;           // J, all bodies at the end
  double kinetic_end_max_body = 0.0;  // J, the largest of one body at the end
  double speed_end_max = 0.0;         // m/s, the fastest point of any body at the end (|v| + |omega| r)
  double largest_move = 0.0;  // m, the farthest any body's position got from its start
  // The first step at which a body had moved farther than the scene's rest limit (its "collapse"),
  // unset when none did or the scene has no rest check (recorded by the rest check).
  std::optional<long> moved_at_step;
  double height_error = 0.0;  // m, largest |height change| of a body at the end (along gravity)
  double drift = 0.0;         // m, largest sideways displacement of a body at the end
  double deepest_penetration = 0.0;  // m, over the run
  // rad/s, the fastest any body turned: over the whole run, or within no_turning's window when
  // the scene holds that check (recorded by it).
  double max_spin = 0.0;
  std::optional<double> rebound;  // m, rise above rest height after the first impact (recorded by the rebound check)
  double smallest_edge = 0.0;     // m, of any box in the scene
};

// What every check sees of a run, kept by RunMonitor.
struct RunView {
  const Scene& scene;
  Vec3 up;                         // against gravity
  const std::vector<Vec3>& start;  // each body's frame position at step 0
  const RunMeasures& measures;     // the shared figures, the latest states included
};

class Check {
 public:
  virtual ~Check() = default;
  // The states after `step` steps at time t (step 0: the start of a run, where a check with
  // state of its own starts it afresh). `run.measures` already includes these states.
  virtual void observe(const RunView& run, long step, double t, const std::vector<BodyState>& states) {
    (void)run, (void)step, (void)t, (void)states;
  }
  // Appends this check's results, in order, against the run so far (the caller fills in their
  // key and reason).
  virtual void evaluate(const RunView& run, std::vector<SceneCheckResult>& out) const = 0;
  // Figures of its own that the run's measures carry (see RunMeasures).
  virtual void record(RunMeasures& measures) const { (void)measures; }
};

// A check's declaration: the table of checks (scene_checks.hpp) holds one per file of this folder.
struct CheckRow {
  std::string_view key;      // in the scene's "checks" object and its "reasons"
  std::string_view meaning;  // what it holds, one sentence (docs/scene-format.md lists the same)
  // Its place in a report's list of results: lower first (ties: by key).
  int order = 0;
  // Held at its default limit when the scene does not give it (energy_rise, penetration).
  bool held_by_default = false;
  // It says something about this scene's own motion, beyond energy and penetration: every scene
  // of the hard catalogue holds at least one such check.
  bool of_its_own = false;
  // The check as the scene asks for it: `node` is its member of "checks", absent only for a
  // check held by default. Throws InputError at the offending node.
  std::unique_ptr<Check> (*read)(const std::optional<json_input::JsonNode>& node, const Scene& scene) = nullptr;
};

// --- helpers that several checks share (scene_checks.cpp) ---

// The index of the body a check names (node: its name), or InputError "no body named ...".
int read_check_body(const json_input::JsonNode& node, const Scene& scene);

// A plane a body's centre is held to one side of: normal . x >= offset.
struct PlaneSide {
  int body = 0;
  Vec3 normal = Vec3::UnitX();  // unit
  double offset = 0.0;          // m
};
// {"body": NAME, "normal": [x, y, z], "offset": m}; a zero normal is refused.
PlaneSide read_plane_side(const json_input::JsonNode& node, const Scene& scene);
// An array of those.
std::vector<PlaneSide> read_plane_sides(const json_input::JsonNode& node, const Scene& scene);
// The body's signed distance to the plane's side (m; >= 0 on the side it is held to).
inline double side_margin(const PlaneSide& p, const BodyState& s) { return p.normal.dot(s.position) - p.offset; }

// A result that passes when value <= limit, or value >= limit.
SceneCheckResult at_most(std::string name, double value, double limit, std::string unit);
SceneCheckResult at_least(std::string name, double value, double limit, std::string unit);

// A check of one of the figures every run measures: `name` passes while measures.*figure <= limit.
std::unique_ptr<Check> figure_at_most(std::string name, double RunMeasures::*figure, double limit, std::string unit);

}  // namespace boxpile
