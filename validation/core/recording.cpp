#include "boxpile/validation/core/recording.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/validation/core/json_output.hpp"

namespace boxpile {
namespace {

using json_input::JsonNode;
using nlohmann::json;

// The name contacts give the ground in place of a body's.
constexpr const char* kGroundName = "ground";

json contacts_json(const std::vector<BodyContact>& contacts, const SceneShapes& shapes) {
  const auto name = [&](int index) {
    return index == kGround ? std::string(kGroundName) : shapes.bodies[static_cast<std::size_t>(index)].name;
  };
  json out = json::array();
  for (const BodyContact& bc : contacts) {
    json c = to_json(bc.contact);
    c["body_a"] = name(bc.body_a);
    c["shape_a"] = bc.shape_a;
    c["body_b"] = name(bc.body_b);
    c["shape_b"] = bc.shape_b;
    out.push_back(std::move(c));
  }
  return out;
}

json frame_json(const Recording& r, std::size_t f) {
  const FrameSeries& s = r.frames;
  json frame = {{"t", s.t[f]}, {"bodies", bodies_json(s.states[f])}};
  if (f < s.contacts.size()) {
    frame["contact_count"] = s.contacts[f].size();
    frame["contacts"] = contacts_json(s.contacts[f], r.shapes);
  }
  if (f < s.energy.size()) {
    frame["energy"] = {{"kinetic", s.kinetic[f]}, {"potential", s.energy[f] - s.kinetic[f]}, {"total", s.energy[f]}};
    if (f < s.rotational.size()) {
      frame["energy"]["translational"] = s.kinetic[f] - s.rotational[f];
      frame["energy"]["rotational"] = s.rotational[f];
    }
    frame["max_penetration"] = s.penetration[f];
    frame["levitation"] = s.levitation[f];
  }
  if (f < s.stack_height.size()) frame["stack_height"] = s.stack_height[f];
  return frame;
}

// --- reading ---

BoxShape read_box(const JsonNode& node) {
  node.expect_object({"half_extents", "offset", "orientation"});
  BoxShape box;
  box.half_extents = json_input::read_half_extents(node.at("half_extents"));
  box.offset = json_input::read_vec3(node.at("offset"));
  box.orientation = json_input::read_orientation(node.at("orientation"));
  return box;
}

BodyShapes read_body_shapes(const JsonNode& node) {
  node.expect_object({"name", "fixed", "boxes", "wire"});
  BodyShapes b;
  b.name = node.at("name").string();
  b.fixed = node.at("fixed").boolean();
  const JsonNode boxes = node.at("boxes");
  const std::size_t n = boxes.array_size();
  if (n == 0) boxes.fail("a body needs at least one box");
  for (std::size_t i = 0; i < n; ++i) b.boxes.push_back(read_box(boxes.element(i)));
  if (const auto wire = node.find("wire")) {
    wire->expect_object({"from", "to", "anchor"});
    b.wire = Wire{json_input::read_vec3(wire->at("from")), json_input::read_vec3(wire->at("to")),
                  json_input::read_vec3(wire->at("anchor"))};
  }
  return b;
}

SceneShapes read_shapes_node(const JsonNode& node) {
  node.expect_object({"ground", "bodies"});
  SceneShapes shapes;
  const JsonNode ground = node.at("ground");
  if (!ground.json().is_null()) shapes.ground = json_input::read_half_space(ground);
  const JsonNode bodies = node.at("bodies");
  for (std::size_t i = 0, n = bodies.array_size(); i < n; ++i) shapes.bodies.push_back(read_body_shapes(bodies.element(i)));
  return shapes;
}

class FrameReader {
 public:
  explicit FrameReader(const SceneShapes& shapes) : shapes_(shapes) {
    for (std::size_t i = 0; i < shapes.bodies.size(); ++i) index_[shapes.bodies[i].name] = static_cast<int>(i);
  }

  void read(const JsonNode& node, FrameSeries& s) const {
    s.t.push_back(node.at("t").number());
    s.states.push_back(read_states(node.at("bodies")));
    s.contacts.push_back(read_contacts(node.at("contacts")));
    const JsonNode energy = node.at("energy");
    s.energy.push_back(energy.at("total").number());
    s.kinetic.push_back(energy.at("kinetic").number());
    s.penetration.push_back(node.at("max_penetration").number());
    s.levitation.push_back(node.at("levitation").number());
  }

 private:
  std::vector<BodyState> read_states(const JsonNode& bodies) const {
    bodies.expect_array_size(shapes_.bodies.size());
    std::vector<BodyState> states(shapes_.bodies.size());
    for (std::size_t i = 0; i < states.size(); ++i) {
      const JsonNode b = bodies.element(i);
      BodyState& s = states[i];
      s.name = b.at("name").string();
      if (s.name != shapes_.bodies[i].name) b.at("name").fail("expected \"" + shapes_.bodies[i].name + "\" (the shapes' order)");
      s.position = json_input::read_vec3(b.at("position"));
      s.orientation = json_input::read_orientation(b.at("orientation"));
      s.velocity = json_input::read_vec3(b.at("velocity"));
      s.angular_velocity = json_input::read_vec3(b.at("angular_velocity"));
    }
    return states;
  }

  int body_index(const JsonNode& node, bool ground_allowed) const {
    const std::string name = node.string();
    if (ground_allowed && name == kGroundName) return kGround;
    const auto it = index_.find(name);
    if (it == index_.end()) node.fail("no body named \"" + name + "\" in shapes");
    return it->second;
  }

  std::vector<BodyContact> read_contacts(const JsonNode& contacts) const {
    std::vector<BodyContact> out;
    for (std::size_t i = 0, n = contacts.array_size(); i < n; ++i) {
      const JsonNode c = contacts.element(i);
      BodyContact bc;
      bc.contact.position = json_input::read_vec3(c.at("position"));
      bc.contact.normal = json_input::read_vec3(c.at("normal"));
      bc.contact.depth = c.at("depth").number();
      const double feature = c.at("feature").number();
      if (feature < 0.0 || feature > 4294967295.0) c.at("feature").fail("must be a 32-bit feature id");
      bc.contact.feature.value = static_cast<std::uint32_t>(feature);
      bc.body_a = body_index(c.at("body_a"), false);
      bc.shape_a = c.at("shape_a").integer();
      bc.body_b = body_index(c.at("body_b"), true);
      bc.shape_b = c.at("shape_b").integer();
      out.push_back(bc);
    }
    return out;
  }

  const SceneShapes& shapes_;
  std::unordered_map<std::string, int> index_;
};

}  // namespace

double value_at_time(const std::vector<double>& t, const std::vector<double>& y, double time) {
  const std::size_t n = std::min(t.size(), y.size());
  if (n == 0) return std::nan("");
  const auto it = std::lower_bound(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(n), time);
  if (it == t.begin()) return y.front();
  if (it == t.begin() + static_cast<std::ptrdiff_t>(n)) return y[n - 1];
  const auto k = static_cast<std::size_t>(it - t.begin());
  const double s = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return y[k - 1] + s * (y[k] - y[k - 1]);
}

SceneShapes shapes_of(const Scene& scene) {
  SceneShapes shapes;
  shapes.ground = scene.ground;
  for (const BodyDesc& b : scene.bodies) shapes.bodies.push_back({b.name, b.fixed, b.boxes, b.wire});
  return shapes;
}

json shapes_json(const SceneShapes& shapes) {
  json bodies = json::array();
  for (const BodyShapes& b : shapes.bodies) {
    json boxes = json::array();
    for (const BoxShape& box : b.boxes) {
      boxes.push_back({{"half_extents", to_json(box.half_extents)},
                       {"offset", to_json(box.offset)},
                       {"orientation", to_json(box.orientation)}});
    }
    json body = {{"name", b.name}, {"fixed", b.fixed}, {"boxes", std::move(boxes)}};
    if (b.wire) {
      body["wire"] = {{"from", to_json(b.wire->from)}, {"to", to_json(b.wire->to)}, {"anchor", to_json(b.wire->anchor)}};
    }
    bodies.push_back(std::move(body));
  }
  json ground = nullptr;
  if (shapes.ground) ground = {{"normal", to_json(shapes.ground->normal)}, {"offset", shapes.ground->offset}};
  return {{"ground", ground}, {"bodies", std::move(bodies)}};
}

SceneShapes read_document_shapes(const json& doc, const std::string& source) {
  return read_shapes_node(JsonNode(doc, source).at("shapes"));
}

Recorder::Recorder(const Scene& scene, std::string engine, RecordDetail detail) : meter_(scene), detail_(detail) {
  recording_.scene = scene.name;
  recording_.engine = std::move(engine);
  recording_.dt = scene.time.dt;
  recording_.shapes = shapes_of(scene);
}

void Recorder::frame(const StepView& view) {
  FrameSeries& s = recording_.frames;
  s.t.push_back(view.t);
  s.states.push_back(view.states);
  if (detail_ == RecordDetail::StatesOnly) return;
  view.engine.contacts(contacts_);
  last_ = meter_.measure(view.states);
  s.contacts.push_back(contacts_);
  s.energy.push_back(last_.energy.total());
  s.kinetic.push_back(last_.energy.kinetic());
  s.rotational.push_back(last_.energy.rotational);
  s.penetration.push_back(last_.penetration.depth);
  s.levitation.push_back(last_.levitation);
}

void Recorder::first_step(const StepView& view) {
  FrameSeries& s = recording_.frames;
  if (view.step != 1 || detail_ == RecordDetail::StatesOnly || s.contacts.empty() || !s.contacts[0].empty()) return;
  view.engine.contacts(s.contacts[0]);
}

json recording_json(const Recording& r, const std::vector<json>& extra) {
  json frames = json::array();
  for (std::size_t f = 0; f < r.frames.t.size(); ++f) {
    json frame = frame_json(r, f);
    if (f < extra.size()) frame.update(extra[f]);
    frames.push_back(std::move(frame));
  }
  json doc = {{"scene", r.scene}, {"engine", r.engine}, {"colour", engine_colour(r.engine)}, {"dt", r.dt}, {"shapes", shapes_json(r.shapes)},
              {"frames", std::move(frames)}};
  if (r.stopped) {
    doc["stopped"] = {{"step", r.stopped->step}, {"t", r.stopped->t}, {"body", r.stopped->body},
                      {"quantity", r.stopped->quantity}};
  }
  return doc;
}

Recording recording_from_json(const json& doc, const std::string& source) {
  const JsonNode root(doc, source);
  Recording r;
  r.scene = root.at("scene").string();
  r.engine = root.at("engine").string();
  r.dt = json_input::read_positive(root.at("dt"));
  r.shapes = read_shapes_node(root.at("shapes"));
  const JsonNode frames = root.at("frames");
  const std::size_t n = frames.array_size();
  if (n == 0) frames.fail("a recording needs at least one frame");
  const FrameReader reader(r.shapes);
  for (std::size_t f = 0; f < n; ++f) reader.read(frames.element(f), r.frames);
  if (const auto stopped = root.find("stopped")) {
    r.stopped = NonFiniteStop{stopped->at("step").integer(), stopped->at("t").number(),
                              stopped->at("body").string(), stopped->at("quantity").string(),
                              /*description=*/""};
  }
  return r;
}

Recording read_recording(const std::string& path) {
  const json doc = json_input::parse(json_input::read_text_file(path), path);
  return recording_from_json(doc, path);
}

}  // namespace boxpile
