#include "boxpile/reference/process/protocol.hpp"

#include <algorithm>
#include <cmath>

#include "boxpile/sim/io/json_input.hpp"

namespace boxpile::protocol {
namespace {

using nlohmann::json;

// A quaternion or a normal this far from unit length is no rotation or direction: an engine in
// single precision stays within about 1e-6 of 1, so this only refuses what is broken.
constexpr double kUnitTolerance = 1e-3;
// Contact points an answer may hold per body (plus one set for a scene of no body): far above
// what any engine reports (ours: at most 8 per touching pair), low enough that a runaway engine
// cannot make boxpile hold gigabytes.
constexpr std::size_t kMaxContactsPerBody = 256;

[[noreturn]] void fail(const std::string& what) { throw ReplyError(what); }

std::string type_of(const json& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  return "an object";
}

json parse_object(std::string_view line) {
  json j = json::parse(line.begin(), line.end(), nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) {
    for (const char* word : {"NaN", "Infinity"}) {
      if (line.find(word) != std::string_view::npos) {
        fail(std::string("is not JSON: it has a number that is not finite (") + word + ")");
      }
    }
    fail("is not JSON");
  }
  if (!j.is_object()) fail("is " + type_of(j) + ", not a JSON object");
  const auto ok = j.find("ok");
  if (ok == j.end()) fail("has no \"ok\"");
  if (!ok->is_boolean()) fail("\"ok\" is " + type_of(*ok) + ", not a boolean");
  if (!ok->get<bool>()) {
    const auto error = j.find("error");
    const std::string text = error != j.end() && error->is_string() ? json_input::shortened(error->get<std::string>())
                                                                     : "(no \"error\" given)";
    fail("answered ok: false: " + text);
  }
  return j;
}

const json& field(const json& object, const char* key, const std::string& path) {
  const auto it = object.find(key);
  if (it == object.end()) fail("has no \"" + path + key + "\"");
  return *it;
}

double number(const json& v, const std::string& path) {
  if (v.is_null()) fail("\"" + path + "\" is null where a number belongs (not finite)");
  if (!v.is_number()) fail("\"" + path + "\" is " + type_of(v) + ", not a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail("\"" + path + "\" is not finite");
  return x;
}

bool boolean(const json& v, const std::string& path) {
  if (!v.is_boolean()) fail("\"" + path + "\" is " + type_of(v) + ", not a boolean");
  return v.get<bool>();
}

std::string text(const json& v, const std::string& path) {
  if (!v.is_string()) fail("\"" + path + "\" is " + type_of(v) + ", not a string");
  return v.get<std::string>();
}

const json& array(const json& v, const std::string& path) {
  if (!v.is_array()) fail("\"" + path + "\" is " + type_of(v) + ", not an array");
  return v;
}

template <int N>
Eigen::Matrix<double, N, 1> numbers(const json& v, const std::string& path) {
  const json& a = array(v, path);
  if (a.size() != N) fail("\"" + path + "\" has " + std::to_string(a.size()) + " numbers, not " + std::to_string(N));
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) out[i] = number(a[static_cast<std::size_t>(i)], path + "[" + std::to_string(i) + "]");
  return out;
}

Vec3 unit_vector(const json& v, const std::string& path) {
  const Vec3 n = numbers<3>(v, path);
  if (std::abs(n.norm() - 1.0) > kUnitTolerance) fail("\"" + path + "\" is not a unit vector");
  return n;
}

Quat quaternion(const json& v, const std::string& path) {
  const Eigen::Vector4d w = numbers<4>(v, path);
  if (std::abs(w.norm() - 1.0) > kUnitTolerance) fail("\"" + path + "\" is not a unit quaternion [w, x, y, z]");
  return Quat(w[0], w[1], w[2], w[3]);
}

json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }
json quat(const Quat& q) { return json::array({q.w(), q.x(), q.y(), q.z()}); }

DeclaredSetting declared_setting(const json& s, const std::string& path) {
  if (!s.is_object()) fail("\"" + path + "\" is " + type_of(s) + ", not an object");
  DeclaredSetting d;
  d.key = text(field(s, "key", path + "."), path + ".key");
  d.kind = text(field(s, "kind", path + "."), path + ".kind");
  if (d.kind != "integer" && d.kind != "number" && d.kind != "boolean" && d.kind != "choice") {
    fail("\"" + path + ".kind\" is " + json_input::in_quotes(d.kind) + ", not one of integer, number, boolean, choice");
  }
  if (const auto u = s.find("unit"); u != s.end()) d.unit = text(*u, path + ".unit");
  if (const auto w = s.find("what"); w != s.end()) d.what = text(*w, path + ".what");
  d.default_value = field(s, "default", path + ".");
  if (d.kind == "integer" || d.kind == "number") {
    d.min = number(field(s, "min", path + "."), path + ".min");
    d.max = number(field(s, "max", path + "."), path + ".max");
    if (d.min > d.max) fail("\"" + path + "\" has min above max");
  }
  if (d.kind == "choice") {
    const json& c = array(field(s, "choices", path + "."), path + ".choices");
    for (std::size_t i = 0; i < c.size(); ++i) d.choices.push_back(text(c[i], path + ".choices[" + std::to_string(i) + "]"));
    if (d.choices.empty()) fail("\"" + path + ".choices\" is empty");
  }
  return d;
}

}  // namespace

std::string hello_request() { return json{{"op", "hello"}, {"protocol", kVersion}}.dump(); }

std::string load_request(const Scene& scene, const json& settings) {
  return json{{"op", "load"}, {"settings", settings.is_null() ? json::object() : settings}, {"scene", scene_message(scene)}}
      .dump();
}

std::string step_request(int n, bool state, bool contacts) {
  return json{{"op", "step"}, {"n", n}, {"state", state}, {"contacts", contacts}}.dump();
}

std::string quit_request() { return json{{"op", "quit"}}.dump(); }

json scene_message(const Scene& scene) {
  const auto material = [&scene](const Material& m) {
    return json{{"friction", scene.effects.friction ? m.friction : 0.0},
                {"restitution", scene.effects.restitution ? m.restitution : 0.0}};
  };
  const std::vector<RigidBody> rigid = make_bodies(scene);
  json bodies = json::array();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& d = scene.bodies[i];
    const RigidBody& r = rigid[i];
    json boxes = json::array();
    for (const BoxShape& b : d.boxes) {
      boxes.push_back({{"half_extents", vec(b.half_extents)}, {"position", vec(b.offset)}, {"orientation", quat(b.orientation)}});
    }
    json inertia = json::array();
    for (int row = 0; row < 3; ++row) inertia.push_back(vec(r.inertia_body.row(row).transpose()));
    json body = {{"name", d.name},
                 {"fixed", d.fixed},
                 {"mass", r.mass},
                 {"center_of_mass", vec(-r.frame_offset)},
                 {"inertia", inertia},
                 {"position", vec(d.frame.position)},
                 {"orientation", quat(d.frame.orientation)},
                 {"velocity", vec(d.velocity)},
                 {"angular_velocity", vec(d.angular_velocity)},
                 {"boxes", boxes}};
    body.update(material(r.material));
    if (d.wire) body["wire"] = {{"from", vec(d.wire->from)}, {"to", vec(d.wire->to)}, {"anchor", vec(d.wire->anchor)}};
    bodies.push_back(std::move(body));
  }
  const Effects& e = scene.effects;
  return json{
      {"name", scene.name},
      {"dt", scene.time.dt},
      {"gravity", vec(e.gravity ? scene.gravity : Vec3::Zero())},
      {"ground", scene.ground ? json{{"normal", vec(scene.ground->normal)}, {"offset", scene.ground->offset}} : json()},
      {"effects", {{"friction", e.friction}, {"restitution", e.restitution}, {"damping", e.damping}, {"gyroscopic", e.gyroscopic}}},
      {"damping", {{"linear", scene.damping.linear}, {"angular", scene.damping.angular}}},
      {"bodies", bodies},
      {"ground_material", material(scene.material)},
  };
}

Hello parse_hello(std::string_view line) {
  const json j = parse_object(line);
  const json& version = field(j, "protocol", "");
  if (!version.is_number_integer() || version.get<long long>() != kVersion) {
    fail("speaks protocol " + version.dump() + "; this boxpile speaks version " + std::to_string(kVersion) + " alone");
  }
  Hello h;
  h.name = text(field(j, "name", ""), "name");
  h.version = text(field(j, "version", ""), "version");
  h.precision = text(field(j, "precision", ""), "precision");
  if (h.precision != "float32" && h.precision != "float64") {
    fail("\"precision\" is " + json_input::in_quotes(h.precision) + ", not float32 or float64");
  }
  h.contacts = boolean(field(j, "contacts", ""), "contacts");
  h.timing = boolean(field(j, "timing", ""), "timing");
  if (const auto s = j.find("settings"); s != j.end()) {
    const json& list = array(*s, "settings");
    for (std::size_t i = 0; i < list.size(); ++i) h.settings.push_back(declared_setting(list[i], "settings[" + std::to_string(i) + "]"));
  }
  return h;
}

void parse_ok(std::string_view line) { static_cast<void>(parse_object(line)); }

StepReply parse_step(std::string_view line, const StepAsk& ask) {
  StepReply out;
  parse_step(line, ask, out);
  return out;
}

void parse_step(std::string_view line, const StepAsk& ask, StepReply& out) {
  const json j = parse_object(line);
  out.time = number(field(j, "time", ""), "time");
  if (out.time < 0.0) fail("\"time\" is negative");
  out.engine_seconds.reset();
  if (const auto s = j.find("engine_seconds"); s != j.end()) {
    out.engine_seconds = number(*s, "engine_seconds");
    if (*out.engine_seconds < 0.0) fail("\"engine_seconds\" is negative");
  }
  if (ask.state) {
    const json& bodies = array(field(j, "bodies", ""), "bodies");
    if (bodies.size() != ask.bodies) {
      fail("\"bodies\" has " + std::to_string(bodies.size()) + " entries; the scene has " + std::to_string(ask.bodies) +
           " bodies");
    }
    out.bodies.resize(ask.bodies);
    for (std::size_t i = 0; i < ask.bodies; ++i) {
      const json& b = bodies[i];
      const std::string path = "bodies[" + std::to_string(i) + "]";
      if (!b.is_object()) fail("\"" + path + "\" is " + type_of(b) + ", not an object");
      BodyState& s = out.bodies[i];
      s.position = numbers<3>(field(b, "position", path + "."), path + ".position");
      s.orientation = quaternion(field(b, "orientation", path + "."), path + ".orientation");
      s.velocity = numbers<3>(field(b, "velocity", path + "."), path + ".velocity");
      s.angular_velocity = numbers<3>(field(b, "angular_velocity", path + "."), path + ".angular_velocity");
    }
  }
  out.contacts.clear();
  if (!ask.contacts) return;
  const json& contacts = array(field(j, "contacts", ""), "contacts");
  const std::size_t most = kMaxContactsPerBody * std::max<std::size_t>(ask.bodies, 1);
  if (contacts.size() > most) {
    fail("\"contacts\" has " + std::to_string(contacts.size()) + " points, more than " + std::to_string(most) +
         " for " + std::to_string(ask.bodies) + " bodies");
  }
  const long n = static_cast<long>(ask.bodies);
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const json& c = contacts[i];
    const std::string path = "contacts[" + std::to_string(i) + "]";
    if (!c.is_object()) fail("\"" + path + "\" is " + type_of(c) + ", not an object");
    BodyContact bc;
    const auto index = [&](const char* key, long low) {
      const json& v = field(c, key, path + ".");
      if (!v.is_number_integer()) fail("\"" + path + "." + key + "\" is " + type_of(v) + ", not an integer");
      const long long k = v.get<long long>();
      if (k < low || k >= n) {
        fail("\"" + path + "." + key + "\" is " + std::to_string(k) + ", not a body index in [" + std::to_string(low) +
             ", " + std::to_string(n - 1) + "]");
      }
      return static_cast<int>(k);
    };
    bc.body_a = index("a", 0);
    bc.body_b = index("b", kGround);
    if (bc.body_a == bc.body_b) fail("\"" + path + "\" has the same body as a and b");
    bc.contact.position = numbers<3>(field(c, "position", path + "."), path + ".position");
    bc.contact.normal = unit_vector(field(c, "normal", path + "."), path + ".normal");
    bc.contact.depth = number(field(c, "depth", path + "."), path + ".depth");
    out.contacts.push_back(bc);
  }
}

}  // namespace boxpile::protocol
