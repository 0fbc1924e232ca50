#include "boxpile/reference/registry.hpp"

#include <algorithm>
#include <array>
#include <cstdint>

#include "boxpile/reference/bullet/bullet_contacts.hpp"
#include "boxpile/reference/bullet/bullet_engine.hpp"
#include "boxpile/reference/dart/dart_contacts.hpp"
#include "boxpile/reference/dart/dart_engine.hpp"
#include "boxpile/reference/mujoco/mujoco_contacts.hpp"
#include "boxpile/reference/mujoco/mujoco_engine.hpp"
#include "boxpile/reference/ode/ode_contacts.hpp"
#include "boxpile/reference/ode/ode_engine.hpp"
#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/io/own_settings.hpp"
#include "boxpile/sim/solver/penalty_parameters.hpp"
#include "boxpile/sim/world.hpp"

namespace boxpile {

using nlohmann::json;

Manifold DetectorInfo::detect(const ContactQuery& q, const DetectOptions& options) const {
  const OrientedBox a = q.a.box();
  if (q.plane) return box_plane(a, *q.plane, options);
  return box_box(a, q.b->box(), options);
}

namespace {

// A reference engine E built from its settings struct S through S's table.
template <class E, class S>
EngineRow typed_row(std::string name, std::string title, const SettingsTable<S>& (*table)(), DefaultLists in,
                    std::vector<DetectorInfo> detectors = {}) {
  EngineRow row;
  row.name = std::move(name);
  row.title = std::move(title);
  row.make = [table](const Scene& scene, const json& settings) -> std::unique_ptr<Engine> {
    return std::make_unique<E>(scene, table().make(settings));
  };
  row.settings = [table] { return table().infos(); };
  row.resolved = [table](const Scene&, const json& settings) { return table().values(table().make(settings)); };
  row.detectors = std::move(detectors);
  row.in = in;
  return row;
}

// Our simulator: `method` forces the contact method whatever the scene's solver.method says (the
// settings of the other method are then not offered), none runs each scene's own. Its settings
// are the scene's solver and collision keys (sim/io/own_settings.hpp): given ones overwrite the
// scene's.
bool offered(const SettingInfo& s, const std::optional<std::string>& method) {
  if (!method) return true;
  return s.group.empty() || s.group == *method;
}

Scene own_scene(const Scene& scene, const json& settings, const std::optional<std::string>& method) {
  Scene s = scene;
  if (method) s.solver.method = *method;
  own_settings_table().apply(s, settings);
  return s;
}

EngineRow own_row(std::string name, std::string title, std::optional<std::string> method, DefaultLists in,
                  std::vector<DetectorInfo> detectors = {}) {
  EngineRow row;
  row.name = name;
  row.title = std::move(title);
  row.make = [method, name](const Scene& scene, const json& settings) -> std::unique_ptr<Engine> {
    if (!method) return std::make_unique<World>(own_scene(scene, settings, method));
    return std::make_unique<World>(own_scene(scene, settings, method), name);
  };
  row.scene_with = [](const Scene& scene, const json& settings) { return own_scene(scene, settings, std::nullopt); };
  row.work_per_step = [method](const Scene& scene, const json& settings) -> long {
    const Scene s = own_scene(scene, settings, method);
    const ContactMethodRow& m = contact_method(s.solver.method);
    return m.work_per_step ? m.work_per_step(s) : 1;
  };
  row.time_step_problem = [method](const Scene& scene, const json& settings) -> std::string {
    const Scene s = own_scene(scene, settings, method);
    const ContactMethodRow& m = contact_method(s.solver.method);
    return m.time_step_problem ? m.time_step_problem(s) : std::string();
  };
  if (!method) {
    row.runs_as = [](const Scene& scene) -> std::string { return "own-" + scene.solver.method; };
  }
  row.settings = [method] {
    std::vector<SettingInfo> out;
    for (const Setting<Scene>& s : own_settings_table().rows())
      if (offered(s.info, method)) out.push_back(s.info);
    return out;
  };
  // The values the run reads: the scene's (with the given ones applied), and for "own" only the
  // settings of the method the scene runs.
  row.resolved = [method](const Scene& scene, const json& settings) {
    const Scene s = own_scene(scene, settings, method);
    json out = json::object();
    for (const Setting<Scene>& r : own_settings_table().rows())
      if (offered(r.info, method ? method : std::optional(s.solver.method))) out[r.info.key] = r.read(s);
    return out;
  };
  row.detectors = std::move(detectors);
  row.in = in;
  return row;
}

Manifold own_box_box(const OrientedBox& a, const OrientedBox& b, const DetectOptions& options) {
  Manifold m;
  collide_box_box(a, b, options.own, m);
  return m;
}

Manifold own_box_plane(const OrientedBox& a, const HalfSpace& plane, const DetectOptions& options) {
  Manifold m;
  collide_box_plane(a, plane, options.plane_margin, m);
  return m;
}

EngineRow coloured(std::string colour, EngineRow row) {
  row.colour = std::move(colour);
  return row;
}

// The colours of engines whose rows bring none: far from the built-in rows' colours and from
// each other, readable on white plots and on the replay page's dark background.
constexpr std::array<const char*, 8> kSpareColours = {"#7F3C8D", "#3969AC", "#11A579", "#E73F74",
                                                      "#008695", "#CF1C90", "#4B4B8F", "#A5AA99"};

// The built-in rows, in the order help texts list them. Adding an engine is one row here (and
// its folder: see registry.hpp).
std::vector<EngineRow> built_in_rows() {
  std::vector<EngineRow> rows;
  // Okabe and Ito's colour-blind safe palette, one colour per row.
  rows.push_back(coloured("#0072B2", own_row("own", "boxpile's simulator, the scene's solver.method (built in)", std::nullopt,
                         {.compare = true, .stability = true},
                         {{"own", "boxpile's separating-axis test with face clipping", false, &own_box_box,
                           &own_box_plane}})));
  // One engine per contact method of the registry (sim/solver/contact_method.hpp), "own-NAME".
  for (const ContactMethodRow& m : contact_methods()) {
    EngineRow r = own_row("own-" + m.name, "boxpile's simulator, " + m.name + " method forced (built in)", m.name,
                          {.main_job = true});
    // The palette's colours of the first two; a method registered later gets a spare colour.
    r.colour = m.name == "impulse" ? "#56B4E9" : m.name == "penalty" ? "#CC79A7" : "";
    rows.push_back(std::move(r));
  }
  rows.push_back(coloured("#D55E00", typed_row<OdeEngine>(
      "ode", "ODE 0.16, double precision (Debian libode-dev, pkg-config ode)", &ode_settings_table,
      {.compare = true, .stability = true, .main_job = true},
      {{"ode", "ODE's dCollide (dBoxBox, box-plane)", false,
        [](const OrientedBox& a, const OrientedBox& b, const DetectOptions&) { return ode_box_box(a, b); },
        [](const OrientedBox& a, const HalfSpace& p, const DetectOptions&) { return ode_box_plane(a, p); }}})));
  rows.push_back(coloured("#009E73", typed_row<BulletEngine>(
      "bullet", "Bullet 3.24, double precision (Debian libbullet-dev, pkg-config bullet-float64)",
      &bullet_settings_table, {.compare = true, .stability = true, .main_job = true},
      {{"bullet", "Bullet's btBoxBoxDetector through a persistent manifold", false,
        [](const OrientedBox& a, const OrientedBox& b, const DetectOptions&) { return bullet_box_box(a, b); },
        [](const OrientedBox& a, const HalfSpace& p, const DetectOptions&) { return bullet_box_plane(a, p); }},
       {"bullet-multipoint", "Bullet with setPlaneConvexMultipointIterations(3, 3)", true,
        [](const OrientedBox& a, const OrientedBox& b, const DetectOptions&) { return bullet_box_box(a, b); },
        [](const OrientedBox& a, const HalfSpace& p, const DetectOptions&) {
          return bullet_box_plane(a, p, kBulletMultipoint);
        }}})));
  rows.push_back(coloured("#E69F00", typed_row<MujocoEngine>(
      "mujoco", "MuJoCo 2.2.2, double precision, C API (Debian libmujoco-dev)", &mujoco_settings_table,
      {},
      {{"mujoco", "MuJoCo 2.2.2's collision table (mjc_BoxBox, mjc_PlaneBox)", false,
        [](const OrientedBox& a, const OrientedBox& b, const DetectOptions&) { return mujoco_box_box(a, b); },
        [](const OrientedBox& a, const HalfSpace& p, const DetectOptions&) { return mujoco_box_plane(a, p); }}})));
  // DART is in no default list, as MuJoCo: its Dantzig LCP costs about 10 times ODE's QuickStep
  // a step (docs/reference-engines.md); `--engines ...,dart` adds it.
  rows.push_back(coloured("#8C564B", typed_row<DartEngine>(
      "dart", "DART 6.12.1, double precision, Dantzig LCP (Debian libdart-dev, libdart-collision-ode-dev)",
      &dart_settings_table, {},
      {{"dart", "DART's DARTCollisionDetector (box-box; the ground as a large box)", false,
        [](const OrientedBox& a, const OrientedBox& b, const DetectOptions&) {
          return dart_box_box(DartDetector::Dart, a, b);
        },
        [](const OrientedBox& a, const HalfSpace& p, const DetectOptions&) {
          return dart_box_plane(DartDetector::Dart, a, p);
        }},
       {"fcl", "FCL 0.7's box primitives through DART's FCLCollisionDetector (the ground as a large box)", false,
        [](const OrientedBox& a, const OrientedBox& b, const DetectOptions&) {
          return dart_box_box(DartDetector::FclPrimitive, a, b);
        },
        [](const OrientedBox& a, const HalfSpace& p, const DetectOptions&) {
          return dart_box_plane(DartDetector::FclPrimitive, a, p);
        }}})));
  return rows;
}

struct Registry {
  std::deque<EngineRow> rows;
  std::deque<DetectorInfo> detectors;

  Registry() {
    for (EngineRow& row : built_in_rows()) add(std::move(row));
  }
  void add(EngineRow row) {
    if (row.name.empty()) throw std::invalid_argument("an engine row needs a name");
    for (const EngineRow& r : rows)
      if (r.name == row.name) throw std::invalid_argument("engine \"" + row.name + "\" is registered twice");
    if (row.available() && !row.make) throw std::invalid_argument("engine \"" + row.name + "\" has no factory");
    for (const DetectorInfo& d : row.detectors) {
      for (const DetectorInfo& e : detectors)
        if (e.name == d.name) throw std::invalid_argument("detector \"" + d.name + "\" is registered twice");
      detectors.push_back(d);
    }
    rows.push_back(std::move(row));
  }
};

Registry& registry() {
  static Registry r;
  return r;
}

// The settings every row shares, applied here rather than by each row: the time step.
const std::string& time_step_key() { return time_step_setting().key; }

json given_or_empty(const json& settings) { return settings.is_null() ? json::object() : settings; }

// `scene` at the time step the settings give (its own when they give none).
Scene at_time_step(const Scene& scene, const json& settings) {
  Scene s = scene;
  if (const auto dt = settings.find(time_step_key()); dt != settings.end()) s.time.dt = dt->get<double>();
  return s;
}

// The settings a row's own functions read: all but the shared ones.
json row_settings(const json& settings) {
  json own = given_or_empty(settings);
  own.erase(time_step_key());
  return own;
}

}  // namespace

void add_engine(EngineRow row) { registry().add(std::move(row)); }

const EngineRow* find_engine_row(std::string_view name) {
  for (const EngineRow& r : registry().rows)
    if (r.name == name) return &r;
  return nullptr;
}

std::vector<std::string> engine_names() {
  std::vector<std::string> names;
  for (const EngineRow& r : registry().rows) names.push_back(r.name);
  return names;
}

std::vector<std::string> available_engine_names() {
  std::vector<std::string> names;
  for (const EngineRow& r : registry().rows)
    if (r.available()) names.push_back(r.name);
  return names;
}

std::string available_engines_text() {
  std::string s;
  for (const std::string& n : available_engine_names()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

std::vector<std::string> default_engines(bool DefaultLists::*list) {
  std::vector<std::string> names;
  for (const EngineRow& r : registry().rows)
    if (r.available() && r.in.*list) names.push_back(r.name);
  return names;
}

const EngineRow& engine_row(std::string_view name) {
  const EngineRow* row = find_engine_row(name);
  if (!row) throw UnknownEngine("unknown engine " + json_input::in_quotes(name) + "; available: " + available_engines_text());
  if (!row->available()) {
    throw UnknownEngine("engine " + json_input::in_quotes(name) + ": " + row->unavailable +
                        "; available: " + available_engines_text());
  }
  return *row;
}

void check_engine_name(std::string_view name) { engine_row(name); }

std::unique_ptr<Engine> make_engine(std::string_view name, const Scene& scene, const json& settings) {
  const json given = given_or_empty(settings);
  return engine_row(name).make(at_time_step(scene, given), row_settings(given));
}

Scene scene_with_settings(std::string_view name, const Scene& scene, const json& settings) {
  const EngineRow& row = engine_row(name);
  const json given = given_or_empty(settings);
  const Scene s = at_time_step(scene, given);
  return row.scene_with ? row.scene_with(s, row_settings(given)) : s;
}

long engine_work_per_step(std::string_view name, const Scene& scene, const json& settings) {
  const EngineRow& row = engine_row(name);
  const json given = given_or_empty(settings);
  return row.work_per_step ? row.work_per_step(at_time_step(scene, given), row_settings(given)) : 1;
}

std::string engine_time_step_problem(std::string_view name, const Scene& scene, const json& settings) {
  const EngineRow& row = engine_row(name);
  const json given = given_or_empty(settings);
  return row.time_step_problem ? row.time_step_problem(at_time_step(scene, given), row_settings(given)) : "";
}

std::string engine_runs_as(std::string_view name, const Scene& scene) {
  const EngineRow& row = engine_row(name);
  return row.runs_as ? row.runs_as(scene) : std::string(name);
}

std::vector<SettingInfo> engine_settings(std::string_view name) {
  const EngineRow& row = engine_row(name);
  std::vector<SettingInfo> out{time_step_setting()};
  if (!row.settings) return out;
  for (SettingInfo& s : row.settings()) {
    // A row of the engine's own by the shared key (an engine program declaring "dt") would be a
    // second meaning of one name: the registry's applies.
    if (s.key != time_step_key()) out.push_back(std::move(s));
  }
  return out;
}

json resolved_settings(std::string_view name, const Scene& scene, const json& settings) {
  const EngineRow& row = engine_row(name);
  const json given = given_or_empty(settings);
  const Scene s = at_time_step(scene, given);
  const json own = row_settings(given);
  json out = json::object();
  if (row.resolved) {
    out = row.resolved(s, own);
  } else {
    for (const SettingInfo& info : engine_settings(name))
      out[info.key] = own.contains(info.key) ? own[info.key] : info.default_value;
  }
  out[time_step_key()] = s.time.dt;
  return out;
}

std::string engine_colour(std::string_view name) {
  if (const EngineRow* row = find_engine_row(name); row && !row->colour.empty()) return row->colour;
  // FNV-1a of the name: the same colour in every process and on every machine.
  std::uint32_t hash = 2166136261u;
  for (char c : name) hash = (hash ^ static_cast<unsigned char>(c)) * 16777619u;
  return kSpareColours[hash % kSpareColours.size()];
}

const std::deque<DetectorInfo>& detectors() { return registry().detectors; }

}  // namespace boxpile
