// The recording of a run: the bodies' shapes once (so that a run can be drawn without its scene
// file), and per recorded frame every body's state, the contact set the engine used in the step
// that led to it, and the measurements of our rulers. `boxpile run --out` writes one; `boxpile
// compare` keeps one per engine (runs/ENGINE.json in its report); replay pages are drawn from them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/core/run_loop.hpp"
#include "boxpile/validation/rulers/state_meter.hpp"

namespace boxpile {

// One body's geometry as the scene placed it: boxes in the body frame, and its wire.
struct BodyShapes {
  std::string name;
  bool fixed = false;
  std::vector<BoxShape> boxes;
  std::optional<Wire> wire;
};

struct SceneShapes {
  std::optional<HalfSpace> ground;
  std::vector<BodyShapes> bodies;  // scene order
};

SceneShapes shapes_of(const Scene& scene);
// {"ground": {"normal", "offset"} or null, "bodies": [{"name", "fixed", "boxes", "wire"}]}.
nlohmann::json shapes_json(const SceneShapes& shapes);
// The shapes under the key "shapes" of a document (a recording, a replay page's data).
SceneShapes read_document_shapes(const nlohmann::json& doc, const std::string& source);

// Recorded frames of one run, column by column. `states` and `t` are always filled; the other
// columns are filled by a full recording (Recorder) and left empty by a states-only one.
struct FrameSeries {
  std::vector<double> t;  // s
  std::vector<std::vector<BodyState>> states;
  std::vector<std::vector<BodyContact>> contacts;  // the contact set of the step that led here
  std::vector<double> energy;        // J, total
  std::vector<double> kinetic;       // J
  std::vector<double> rotational;    // J, the rotational part of kinetic
  std::vector<double> penetration;   // m, deepest
  std::vector<double> levitation;    // m
  std::vector<double> stack_height;  // m, the tallest stack (compare fills it; 0 when none)
};

// y at `time` of a series sampled at increasing times t: linear between samples, the end values
// outside them, NaN for an empty series. Frames of engines run at different steps meet through it.
double value_at_time(const std::vector<double>& t, const std::vector<double>& y, double time);

struct Recording {
  std::string scene;
  std::string engine;
  double dt = 0.0;  // s
  SceneShapes shapes;
  FrameSeries frames;
  std::optional<NonFiniteStop> stopped;  // where a run that blew up stopped
};

// How much a Recorder keeps per frame.
enum class RecordDetail {
  Full,        // states, contacts and measurements
  StatesOnly,  // time and states (for runs compared by pose alone)
};

// Fills a recording at each frame of a run loop: states, the engine's contacts, and energy,
// penetration and levitation measured by StateMeter.
class Recorder {
 public:
  Recorder(const Scene& scene, std::string engine, RecordDetail detail = RecordDetail::Full);
  // Records the frame `view` shows.
  void frame(const StepView& view);
  // After the first step (view.step == 1): its contact set becomes the start frame's, which has
  // none of its own (nothing has been stepped yet), so that a replay opens on the contacts that
  // hold the scene up. A no-op at any other step.
  void first_step(const StepView& view);
  // The last frame's measurements (after frame()).
  const FrameMetrics& last_metrics() const { return last_; }
  Recording& recording() { return recording_; }

 private:
  StateMeter meter_;
  RecordDetail detail_;
  Recording recording_;
  FrameMetrics last_;
  std::vector<BodyContact> contacts_;
};

// The recording as `run --out` writes it (docs/viewer.md lists the keys). `extra`, when given,
// holds one object per frame whose keys are added to that frame (our solver's statistics).
nlohmann::json recording_json(const Recording& recording, const std::vector<nlohmann::json>& extra = {});

// Reads a recording written by recording_json; InputError naming the file and the JSON path of
// anything missing or malformed.
Recording read_recording(const std::string& path);
Recording recording_from_json(const nlohmann::json& doc, const std::string& source);

}  // namespace boxpile
