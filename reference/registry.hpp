// Every engine that can run a scene, one row each: the one place the command line, the reports,
// the sweeps, the docs and the tests learn which engines exist. Every list of engines (help texts,
// "unknown engine ...; available: ..." errors, the defaults of compare, stability and the main
// job, `boxpile settings`, sweep keys, the detector table, the tests' loops) is derived from the
// rows; nothing else names an engine.
//
// Adding an engine
// ----------------
// 1. A folder reference/NAME/ with
//      NAME_engine.hpp/.cpp    class NameEngine : public Engine, built from (const Scene&,
//                              const NameSettings&);
//      NAME_settings.hpp/.cpp  struct NameSettings (plain fields with their defaults as member
//                              initialisers) and `const SettingsTable<NameSettings>&
//                              name_settings_table()`, one Setting<NameSettings> per field: key,
//                              kind, unit, range or choices, meaning (sim/io/setting.hpp), an
//                              apply and a read function. The default is read from NameSettings{}.
//      NAME_contacts.hpp/.cpp  (optional) the engine's contact detector for one query.
//      packages                what it needs installed, a line each (`debian libname-dev ...`),
//                              which scripts/install-deps reads and the row's title names;
//    and its sources in reference/CMakeLists.txt (its find_package/pkg_check_modules beside
//    ODE's and Bullet's).
// 2. One row in kBuiltInRows (reference/registry.cpp), with its colour in every plot:
//      coloured("#rrggbb", typed_row<NameEngine>("name", "Name 1.2 (Debian libname-dev)",
//                            &name_settings_table,
//                            {.compare = true, .stability = true, .main_job = false},
//                            {/* DetectorInfo rows, or none */}))
//    or, for an engine that cannot be built here, a row with `unavailable` saying why.
// That is all: `boxpile run --engine name`, `--set name.KEY=VALUE`, sweep grids, `boxpile
// settings`, compare's and stability's reports (which record every setting's value) and the
// tests that loop over engines pick it up. Its known verdicts on the hard catalogue go in
// fixtures/verdicts/hard.json (tests/test_hard.cpp reads them).
//
// Engines known only at run time (a child process given by `--engine-cmd NAME=COMMAND`, whose
// settings are announced in its `hello`) are added with add_engine() before the command checks
// its engine names; their `settings` function may ask the engine, and is called only when a
// list of settings is needed.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/reference/detector.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/io/setting.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// An engine name that is unknown, or known but not available; what() says which and lists the
// engines that can be used.
class UnknownEngine : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The engine lists a row belongs to by default (each command's list is the rows flagged for it,
// in registry order).
struct DefaultLists {
  bool compare = false;    // `boxpile compare` without --engines
  bool stability = false;  // `boxpile stability` without --engines
  bool main_job = false;   // `boxpile` with no command (compare on the bone scene)
};

struct EngineRow {
  std::string name;
  // One line: the engine, its version, and how it is installed.
  std::string title;
  // Builds the engine for a scene with settings {key: value}, each already checked against
  // `settings()` (check_engine_settings); keys left out take their defaults. The settings every
  // engine shares (the time step, sim/io/setting.hpp's time_step_setting()) are not the row's:
  // the registry writes them into the scene before it calls any of the row's functions.
  std::function<std::unique_ptr<Engine>(const Scene& scene, const nlohmann::json& settings)> make;
  // The engine's settings table (empty when it has none, or has no function).
  std::function<std::vector<SettingInfo>()> settings;
  // Every setting's value the engine runs with for `scene` and the given settings; when empty,
  // each declaration's default overlaid with the given settings.
  std::function<nlohmann::json(const Scene& scene, const nlohmann::json& settings)> resolved;
  // For an engine whose settings are the scene's (ours: its solver and collision keys): the scene
  // with the given settings written in, so that the rulers read what the engine runs. Empty for
  // engines whose settings live outside the scene.
  std::function<Scene(const Scene& scene, const nlohmann::json& settings)> scene_with;
  // What one step of `scene` costs against the step cap, in steps: the penalty method's
  // substeps each find and resolve the contacts, a whole step's work. Empty: 1.
  std::function<long(const Scene& scene, const nlohmann::json& settings)> work_per_step;
  // Why the engine cannot run `scene` at its time step with the given settings, known before it
  // is built (the penalty method's stability bound); empty function or text: it can.
  std::function<std::string(const Scene& scene, const nlohmann::json& settings)> time_step_problem;
  // The row whose engine this one is on `scene` ("own" is own-impulse or own-penalty by the
  // scene's solver.method): two names of one engine are not run side by side. Empty: itself.
  std::function<std::string(const Scene& scene)> runs_as;
  // The contact detectors the engine brings (none, one, or variants of one).
  std::vector<DetectorInfo> detectors;
  DefaultLists in;
  // The engine's colour in every plot, lab figure and replay page ("#rrggbb"); empty: the colour
  // engine_colour() picks from the name alone.
  std::string colour;
  // Why the engine cannot be built here; empty when it can.
  std::string unavailable;

  bool available() const { return unavailable.empty(); }
};

// Adds a row at run time (after the built-in ones); std::invalid_argument when the name is taken
// or empty, or the row has no factory while claiming to be available.
void add_engine(EngineRow row);

// The row named `name`, available or not; null when there is none.
const EngineRow* find_engine_row(std::string_view name);

// Every engine name, available or not, in registry order.
std::vector<std::string> engine_names();
// The names make_engine() can build.
std::vector<std::string> available_engine_names();
// "own, own-impulse, ..., bullet": the available names as a help text or an error lists them.
std::string available_engines_text();
// The default engine list of a command: the available rows with `list` set, in registry order.
std::vector<std::string> default_engines(bool DefaultLists::*list);

// The one colour of the engine `name` in every plot, lab figure and replay page ("#rrggbb"): its
// row's, else (a row without one, a run file of an engine not registered now) one picked from the
// name alone, so that a name is drawn in one colour wherever it is drawn.
std::string engine_colour(std::string_view name);

// Throws UnknownEngine unless make_engine() can build `name`.
void check_engine_name(std::string_view name);
// The available row named `name` (UnknownEngine otherwise).
const EngineRow& engine_row(std::string_view name);

// The engine `name` built from `scene` and settings {key: value} (checked:
// check_engine_settings); UnknownEngine for a name that is not available.
std::unique_ptr<Engine> make_engine(std::string_view name, const Scene& scene,
                                    const nlohmann::json& settings = nlohmann::json::object());

// `scene` with `name`'s settings written in: the time step, and the row's own when they are the
// scene's (EngineRow::scene_with). What every command steps and measures.
Scene scene_with_settings(std::string_view name, const Scene& scene, const nlohmann::json& settings);

// EngineRow::work_per_step, time_step_problem and runs_as of `name` (1, "" and `name` when the
// row has none).
long engine_work_per_step(std::string_view name, const Scene& scene, const nlohmann::json& settings);
std::string engine_time_step_problem(std::string_view name, const Scene& scene, const nlohmann::json& settings);
std::string engine_runs_as(std::string_view name, const Scene& scene);

// The settings `name` declares: the time step first (every engine's), then the row's.
std::vector<SettingInfo> engine_settings(std::string_view name);
// Every setting's value `name` runs with for `scene` and `settings` (defaults included).
nlohmann::json resolved_settings(std::string_view name, const Scene& scene,
                                 const nlohmann::json& settings = nlohmann::json::object());

// Every registered detector, rows in registry order and each row's detectors in its order.
const std::deque<DetectorInfo>& detectors();

}  // namespace boxpile
