#include "boxpile/sim/io/scene_loader.hpp"

#include "boxpile/sim/solver/step_context.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/sim/collision/broadphase.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/io/own_settings.hpp"
#include "boxpile/sim/solver/contact_method.hpp"
#include "boxpile/sim/solver/penalty_parameters.hpp"
#include "boxpile/sim/time_steps.hpp"

namespace boxpile {
namespace {

using json_input::in_quotes;
using json_input::JsonNode;

// Two bodies (or a body and the ground) overlap at the start when they interpenetrate by more
// than this. Stacks written in decimal touch only up to rounding (0.1 + 0.2 != 0.3): about 1e-12 m
// for coordinates up to 1e4 m, far below this, while any overlap a solver would push apart is
// far above it.
constexpr double kInitialOverlapTolerance = 1e-9;  // m

// The anchor of a wire must start this close to the wire: the same tolerance as the initial
// overlap, so that positions written in decimal (0.1 + 0.2) still count as on the wire.
constexpr double kWireStartTolerance = 1e-9;  // m

// The effects vocabulary, in the order of the flags they set.
constexpr std::array<std::string_view, 5> kEffectNames = {"gravity", "friction", "restitution",
                                                          "damping", "gyroscopic"};
constexpr std::array<bool Effects::*, 5> kEffectFlags = {
    &Effects::gravity, &Effects::friction, &Effects::restitution, &Effects::damping,
    &Effects::gyroscopic};


// The keys of the scene's `solver` and `collision` objects are the rows of our settings table
// (sim/io/own_settings.hpp) whose scene_key lies in that object: one declaration (range, kind,
// default, the method that reads it) for the loader, `--set`, sweep grids and the docs.
struct SectionRow {
  std::string_view key;  // in the object
  const Setting<Scene>* row;
};

std::vector<SectionRow> section_rows(std::string_view section) {
  std::vector<SectionRow> rows;
  for (const Setting<Scene>& r : own_settings_table().rows()) {
    const std::string_view key = r.info.scene_key;
    if (key.size() > section.size() && key.substr(0, section.size()) == section && key[section.size()] == '.') {
      rows.push_back({key.substr(section.size() + 1), &r});
    }
  }
  return rows;
}

// The object holds only the keys of `section`'s rows and `extra`.
void expect_section_keys(const JsonNode& node, std::string_view section, std::initializer_list<std::string_view> extra) {
  std::vector<std::string_view> allowed(extra);
  for (const SectionRow& r : section_rows(section)) allowed.push_back(r.key);
  node.expect_object(allowed);
}

// Each row's value given, checked against its declaration and written into the scene.
void read_section_values(const JsonNode& node, std::string_view section, Scene& scene) {
  for (const SectionRow& r : section_rows(section)) {
    if (const auto v = node.find(r.key)) r.row->apply(scene, check_setting_value(r.row->info, *v));
  }
}

std::string format_point(const Vec3& p) {
  std::string s = "[";
  for (int i = 0; i < 3; ++i) {
    if (i > 0) s += ", ";
    s += json_input::format_number(p[i]);
  }
  return s + "]";
}

double read_mass(const JsonNode& node) {
  return json_input::read_in_range(node, limits::kMinMass, limits::kMaxMass, "kg");
}

double read_unit_interval(const JsonNode& node) {
  const double e = node.number();
  if (e < 0.0 || e > 1.0) node.fail("must be in [0, 1], got " + json_input::format_number(e));
  return e;
}

// A material; keys left out keep the values of `fallback` (the scene's, for a body).
// A material that sets "friction" but not "static_friction" has mu_s = mu (it does not inherit the
// fallback's static coefficient).
Material read_material(const JsonNode& node, const Material& fallback) {
  node.expect_object({"friction", "restitution", "static_friction"});
  Material m = fallback;
  if (const auto mu = node.find("friction")) {
    m.friction = json_input::read_in_range(*mu, 0.0, limits::kMaxFriction, "");
    m.static_friction.reset();
  }
  if (const auto e = node.find("restitution")) m.restitution = read_unit_interval(*e);
  if (const auto mu_s = node.find("static_friction")) {
    m.static_friction = json_input::read_in_range(*mu_s, 0.0, limits::kMaxFriction, "");
    if (*m.static_friction < m.friction) {
      mu_s->fail("the static coefficient must be at least the dynamic one (\"friction\", " +
                 json_input::format_number(m.friction) + "), got " + json_input::format_number(*m.static_friction));
    }
  }
  return m;
}

// Only the listed effects are on; each may be listed once.
Effects read_effects(const JsonNode& node) {
  Effects effects{false, false, false, false, false};
  std::array<bool, kEffectNames.size()> listed{};
  for (std::size_t i = 0; i < node.array_size(); ++i) {
    const JsonNode item = node.element(i);
    const std::size_t k = item.choice(kEffectNames, "effect");
    if (listed[k]) item.fail("effect " + in_quotes(kEffectNames[k]) + " is listed twice");
    listed[k] = true;
    effects.*kEffectFlags[k] = true;
  }
  return effects;
}

Damping read_damping(const JsonNode& node) {
  node.expect_object({"linear", "angular"});
  Damping d;
  if (const auto c = node.find("linear")) d.linear = json_input::read_in_range(*c, 0.0, limits::kMaxDampingRate, "1/s");
  if (const auto c = node.find("angular")) d.angular = json_input::read_in_range(*c, 0.0, limits::kMaxDampingRate, "1/s");
  return d;
}

// The scene's `solver` object: its method, then every key of our settings table under
// `solver.`; a key of one method given while the scene runs the other is an error naming the
// method it belongs to (a setting that is accepted must do something).
void read_solver(const JsonNode& node, Scene& scene) {
  expect_section_keys(node, "solver", {"method"});
  if (const auto m = node.find("method")) {
    const std::vector<std::string_view> names = contact_method_names();
    scene.solver.method = std::string(names[m->choice(names, "solver method")]);
  }
  const std::string& method = scene.solver.method;
  for (const SectionRow& r : section_rows("solver")) {
    const std::string& group = r.row->info.group;
    if (group.empty() || group == method) continue;
    if (const auto k = node.find(r.key)) {
      k->fail("belongs to the " + group + " method, but \"method\" is " + in_quotes(method) +
              ": remove it or set \"method\": " + in_quotes(group));
    }
  }
  read_section_values(node, "solver", scene);
}

void read_collision(const JsonNode& node, Scene& scene) {
  expect_section_keys(node, "collision", {});
  read_section_values(node, "collision", scene);
}

TimeSettings read_time(const JsonNode& node) {
  node.expect_object({"dt", "duration"});
  TimeSettings t;
  const JsonNode dt = node.at("dt");
  const JsonNode duration = node.at("duration");
  t.dt = dt.number();
  t.duration = duration.number();
  if (const auto problem = check_time_settings(t.dt, t.duration)) {
    (problem->field == TimeSettingsProblem::Field::Dt ? dt : duration).fail(problem->what);
  }
  return t;
}

BoxShape read_box_shape(const JsonNode& node) {
  node.expect_object({"half_extents", "offset", "orientation"});
  BoxShape box;
  box.half_extents = json_input::read_half_extents(node.at("half_extents"));
  if (const auto o = node.find("offset")) box.offset = json_input::read_vec3(*o);
  if (const auto q = node.find("orientation")) box.orientation = json_input::read_orientation(*q);
  return box;
}

// A body is one box ("half_extents") or a compound ("boxes"): exactly one of the two.
std::vector<BoxShape> read_shape(const JsonNode& body) {
  const bool single = body.has("half_extents");
  const bool compound = body.has("boxes");
  if (single && compound) {
    body.fail("has both \"half_extents\" (one box) and \"boxes\" (a compound): give one of them");
  }
  if (!single && !compound) {
    body.fail("missing required key \"half_extents\" (one box) or \"boxes\" (a compound)");
  }
  if (single) return {BoxShape{json_input::read_half_extents(body.at("half_extents"))}};

  const JsonNode boxes = body.at("boxes");
  const std::size_t n = boxes.array_size();
  if (n == 0) boxes.fail("must not be empty: a compound needs at least one box");
  if (n > static_cast<std::size_t>(kMaxBoxesPerBody)) {
    boxes.fail("at most " + std::to_string(kMaxBoxesPerBody) + " boxes per body, got " +
               std::to_string(n));
  }
  std::vector<BoxShape> shapes;
  for (std::size_t i = 0; i < n; ++i) shapes.push_back(read_box_shape(boxes.element(i)));
  return shapes;
}

// A wire: a segment from "from" to "to" (world) and the anchor (body frame) that slides on it.
// The anchor must start on the segment: an engine would otherwise snap it there in its first
// step, and each engine would do so differently.
Wire read_wire(const JsonNode& node, const Pose& frame) {
  node.expect_object({"from", "to", "anchor"});
  Wire w;
  w.from = json_input::read_vec3(node.at("from"));
  w.to = json_input::read_vec3(node.at("to"));
  w.anchor = json_input::read_vec3(node.at("anchor"));
  const Vec3 along = w.to - w.from;
  const double length = along.norm();
  if (!(length > 0.0)) {
    node.fail("zero-length wire: \"from\" and \"to\" are the same point; a wire needs two distinct ends");
  }
  const Vec3 start = frame.apply(w.anchor);
  const double s = std::clamp((start - w.from).dot(along) / (length * length), 0.0, 1.0);
  const double off = (start - (w.from + s * along)).norm();
  if (off > kWireStartTolerance) {
    node.at("anchor").fail("the anchor starts " + json_input::format_number(off) +
                           " m off the wire (at " + format_point(start) +
                           " in the world); it must lie on the segment from \"from\" to \"to\" within " +
                           json_input::format_number(kWireStartTolerance) + " m");
  }
  return w;
}

// A velocity given to a fixed body would be silently lost: say so instead.
Vec3 read_body_velocity(const JsonNode& body, std::string_view key, bool fixed, double max_norm,
                        std::string_view unit) {
  const auto node = body.find(key);
  if (!node) return Vec3::Zero();
  const Vec3 v = json_input::read_bounded_vector(*node, max_norm, unit);
  if (fixed && !v.isZero(0.0)) node->fail("a fixed body does not move: must be [0, 0, 0]");
  return v;
}

BodyDesc read_body(const JsonNode& node, const Material& scene_material) {
  node.expect_object({"name", "mass", "half_extents", "boxes", "position", "orientation",
                      "velocity", "angular_velocity", "fixed", "material", "wire"});
  BodyDesc b;
  b.name = json_input::read_name(node.at("name"));
  b.fixed = node.boolean_or("fixed", false);
  // A fixed body has infinite mass in the dynamics; its mass is optional and only reported.
  if (b.fixed) {
    const auto mass = node.find("mass");
    b.mass = mass ? read_mass(*mass) : 0.0;
  } else {
    b.mass = read_mass(node.at("mass"));
  }
  b.boxes = read_shape(node);
  b.frame.position = json_input::read_vec3(node.at("position"));
  if (const auto q = node.find("orientation")) {
    b.frame.orientation = json_input::read_orientation(*q);
  }
  b.velocity = read_body_velocity(node, "velocity", b.fixed, limits::kMaxSpeed, "m/s");
  b.angular_velocity = read_body_velocity(node, "angular_velocity", b.fixed, limits::kMaxAngularSpeed, "rad/s");
  if (const auto m = node.find("material")) b.material = read_material(*m, scene_material);
  if (const auto w = node.find("wire")) {
    if (b.fixed) w->fail("a fixed body cannot slide on a wire: remove \"wire\" or \"fixed\"");
    b.wire = read_wire(*w, b.frame);
  }
  return b;
}

std::vector<BodyDesc> read_bodies(const JsonNode& node, const Material& scene_material, const LoadLimits& caps) {
  const std::size_t n = node.array_size();
  if (n > caps.max_bodies) {
    node.fail(std::to_string(n) + " bodies, above the cap of " + std::to_string(caps.max_bodies) +
              " (--max-bodies raises it)");
  }
  std::vector<BodyDesc> bodies;
  bodies.reserve(n);
  std::unordered_map<std::string, std::size_t> first_use;
  first_use.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const JsonNode item = node.element(i);
    bodies.push_back(read_body(item, scene_material));
    const auto [it, inserted] = first_use.emplace(bodies.back().name, i);
    if (!inserted) {
      item.at("name").fail("duplicate body name " + in_quotes(bodies.back().name) +
                           " (also bodies[" + std::to_string(it->second) + "])");
    }
  }
  return bodies;
}

// ---------------------------------------------------------------------------------------------
// Truth

// A body named by the truth: its index in the scene.
int read_body_name(const JsonNode& node, const std::vector<BodyDesc>& bodies) {
  const std::string name = node.string();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name == name) return static_cast<int>(i);
  }
  node.fail("no body named " + in_quotes(name) + " in the scene");
}

// An object {BODY: value}: each key a body of the scene, each value read by `read` with the body's
// index.
template <class Read>
void for_each_body_key(const JsonNode& node, const std::vector<BodyDesc>& bodies, Read&& read) {
  if (!node.json().is_object()) node.fail("must be an object {BODY: ...} naming bodies of the scene");
  for (const auto& item : node.json().items()) {
    const JsonNode value = node.at(item.key());
    int index = -1;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].name == item.key()) index = static_cast<int>(i);
    }
    if (index < 0) value.fail("no body named " + in_quotes(item.key()) + " in the scene");
    if (bodies[static_cast<std::size_t>(index)].fixed) {
      value.fail("body " + in_quotes(item.key()) + " is fixed: a truth about it says nothing");
    }
    read(value, index);
  }
}

std::vector<TruthPoint> read_truth_points(const JsonNode& node, const std::vector<BodyDesc>& bodies) {
  std::vector<TruthPoint> points;
  for_each_body_key(node, bodies, [&](const JsonNode& v, int body) { points.push_back({body, json_input::read_vec3(v)}); });
  return points;
}

TruthTrajectory read_truth_trajectory(const JsonNode& node, const BodyDesc& body, int index) {
  node.expect_object({"start", "velocity", "acceleration", "until"});
  TruthTrajectory t;
  t.body = index;
  t.start = body.frame.position;
  t.velocity = body.velocity;
  if (const auto s = node.find("start")) t.start = json_input::read_vec3(*s);
  if (const auto v = node.find("velocity")) t.velocity = json_input::read_vec3(*v);
  t.acceleration = json_input::read_vec3(node.at("acceleration"));
  if (const auto u = node.find("until")) t.until = json_input::read_non_negative(*u);
  return t;
}

SceneTruth read_truth(const JsonNode& node, const std::vector<BodyDesc>& bodies, const TimeSettings& time) {
  node.expect_object({"final_positions", "final_velocities", "final_orientations", "trajectories", "rebound"});
  SceneTruth t;
  t.duration = time.duration;
  if (const auto p = node.find("final_positions")) t.final_positions = read_truth_points(*p, bodies);
  if (const auto v = node.find("final_velocities")) t.final_velocities = read_truth_points(*v, bodies);
  if (const auto o = node.find("final_orientations")) {
    for_each_body_key(*o, bodies, [&](const JsonNode& v, int body) {
      t.final_orientations.push_back({body, json_input::read_orientation(v)});
    });
  }
  if (const auto r = node.find("trajectories")) {
    for_each_body_key(*r, bodies, [&](const JsonNode& v, int body) {
      t.trajectories.push_back(read_truth_trajectory(v, bodies[static_cast<std::size_t>(body)], body));
    });
  }
  if (const auto r = node.find("rebound")) {
    r->expect_object({"body", "height"});
    t.rebound = TruthRebound{read_body_name(r->at("body"), bodies), r->at("height").number()};
  }
  if (t.empty()) node.fail("states no truth: give at least one of final_positions, final_velocities, "
                           "final_orientations, trajectories, rebound (or leave \"truth\" out)");
  return t;
}

// The field a JSON pointer names in the scene file, for its error message.
JsonNode at_tokens(const JsonNode& node, const std::vector<std::string>& tokens, std::size_t k) {
  if (k == tokens.size()) return node;
  return at_tokens(node.json().is_array() ? node.element(std::stoul(tokens[k])) : node.at(tokens[k]), tokens, k + 1);
}

JsonNode at_pointer(const JsonNode& root, const std::string& pointer) {
  std::vector<std::string> tokens;
  for (std::size_t start = 1; start <= pointer.size();) {
    const std::size_t end = std::min(pointer.find('/', start), pointer.size());
    tokens.push_back(pointer.substr(start, end - start));
    start = end + 1;
  }
  return at_tokens(root, tokens, 0);
}

Scene read_scene(const JsonNode& root, const LoadLimits& caps) {
  root.expect_object({"name", "note", "gravity", "ground", "material", "effects", "damping",
                      "bodies", "solver", "collision", "time", "allow_initial_overlap", "checks", "truth"});
  Scene s;
  s.name = json_input::read_name(root.at("name"));
  s.note = root.string_or("note", "");
  if (const auto g = root.find("gravity")) s.gravity = json_input::read_vec3(*g, limits::kMaxGravity);
  if (const auto g = root.find("ground")) s.ground = json_input::read_half_space(*g);
  if (const auto m = root.find("material")) s.material = read_material(*m, s.material);
  if (const auto e = root.find("effects")) s.effects = read_effects(*e);
  if (const auto d = root.find("damping")) s.damping = read_damping(*d);
  s.bodies = read_bodies(root.at("bodies"), s.material, caps);
  if (const auto c = root.find("solver")) read_solver(*c, s);
  if (const auto c = root.find("collision")) read_collision(*c, s);
  s.time = read_time(root.at("time"));
  s.allow_initial_overlap = root.boolean_or("allow_initial_overlap", false);
  if (const ContactMethodRow& method = contact_method(s.solver.method); method.check_scene) {
    if (const auto problem = method.check_scene(root.json(), s)) at_pointer(root, problem->pointer).fail(problem->message);
  }
  // The checks are validation's to read (validation/stability/scene_checks.hpp); the scene keeps
  // the object's text.
  if (const auto c = root.find("checks")) {
    if (!c->json().is_object()) c->fail(std::string("expected object, got ") + c->json().type_name());
    s.checks = c->json().dump();
  }
  if (const auto t = root.find("truth")) s.truth = read_truth(*t, s.bodies, s.time);
  return s;
}

// ---------------------------------------------------------------------------------------------
// Initial overlap

std::string body_path(std::size_t i) { return "bodies[" + std::to_string(i) + "]"; }

std::string overlap_advice() {
  return " at the start; move them apart or set \"allow_initial_overlap\": true";
}

// Pairs that can never move apart (two fixed bodies, a fixed body and the ground) are not
// checked: they exchange no impulses, so an overlap between them is harmless.
void check_ground_overlap(const Scene& scene, const std::vector<RigidBody>& bodies) {
  if (!scene.ground) return;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const RigidBody& b = bodies[i];
    if (b.fixed) continue;
    double depth = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < static_cast<int>(b.shapes.size()); ++k) {
      const OrientedBox box =
          OrientedBox::from(b.shape_pose(k), b.shapes[static_cast<std::size_t>(k)].half_extents);
      depth = std::max(depth, box_plane_depth(box, *scene.ground));
    }
    if (depth > kInitialOverlapTolerance) {
      throw InputError(scene.source, body_path(i),
                       "body " + in_quotes(b.name) + " overlaps the ground by " +
                           json_input::format_number(depth) + " m" + overlap_advice());
    }
  }
}

// Candidate pairs come from the broadphase (bounding boxes grown by the tolerance), so that the
// check is O(n log n) for a spread-out scene rather than O(n^2): 10^5 bodies load in about a second.
// The overlap reported is the first in scene order of the later body, as a reader scans the file.
void check_body_overlap(const Scene& scene, const std::vector<RigidBody>& bodies) {
  SweepAndPrune broadphase;
  const std::vector<double> margins(bodies.size(), kInitialOverlapTolerance);
  std::vector<std::pair<int, int>> pairs = broadphase.find_pairs(bodies, margins);
  std::sort(pairs.begin(), pairs.end(), [](const auto& p, const auto& q) {
    return std::pair(p.second, p.first) < std::pair(q.second, q.first);
  });
  for (const auto& [first, second] : pairs) {
    const auto i = static_cast<std::size_t>(first);
    const auto j = static_cast<std::size_t>(second);
    const RigidBody& a = bodies[i];
    const RigidBody& b = bodies[j];
    const double depth = body_pair_depth(b, a);
    if (depth > kInitialOverlapTolerance) {
      throw InputError(scene.source, body_path(j),
                       "body " + in_quotes(b.name) + " overlaps body " + in_quotes(a.name) + " (" +
                           body_path(i) + ") by " + json_input::format_number(depth) + " m" + overlap_advice());
    }
  }
}

// The pairs of the first step, before any engine is handed the scene: bodies whose bounding boxes
// overlap (grown by the initial-overlap tolerance), counted through the broadphase, which stops
// one past the cap, so that counting costs no more memory than the cap allows.
void check_pair_cap(const Scene& scene, const std::vector<RigidBody>& bodies) {
  std::vector<Aabb> boxes;
  std::vector<char> fixed;
  boxes.reserve(bodies.size());
  fixed.reserve(bodies.size());
  for (const RigidBody& b : bodies) {
    boxes.push_back(body_aabb(b, kInitialOverlapTolerance));
    fixed.push_back(b.fixed ? 1 : 0);
  }
  SweepAndPrune broadphase;
  if (broadphase.find_pairs(boxes, fixed, scene.max_pairs).size() > scene.max_pairs) {
    throw InputError(scene.source, "bodies",
                     "more than " + std::to_string(scene.max_pairs) +
                         " pairs of bodies touch or overlap at the start, above the cap on the pairs a step may "
                         "make (--max-pairs raises it; every pair costs each engine its contacts)");
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source, const LoadLimits& caps) {
  const nlohmann::json doc = json_input::parse(text, source);
  Scene scene = read_scene(JsonNode(doc, source), caps);
  scene.source = source;
  scene.max_pairs = caps.max_pairs;
  const std::vector<RigidBody> bodies = make_bodies(scene);
  if (!scene.allow_initial_overlap) {
    check_ground_overlap(scene, bodies);
    check_body_overlap(scene, bodies);
  }
  check_pair_cap(scene, bodies);
  return scene;
}

Scene load_scene(const std::string& path, const LoadLimits& caps) {
  return parse_scene(json_input::read_text_file(path, caps.max_input_bytes), path, caps);
}

}  // namespace boxpile
