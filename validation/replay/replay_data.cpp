#include "boxpile/validation/replay/replay_data.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/json_input.hpp"

namespace boxpile {
namespace {

using json_input::JsonNode;
using nlohmann::json;

// The format's name and version, checked when a page's data is read back.
constexpr const char* kFormat = "boxpile-replay-1";
// Floats per body state: position (3), orientation w x y z (4), velocity (3), angular velocity (3).
constexpr std::size_t kStateFloats = 13;
// Floats per contact point: position (3), normal (3), depth.
constexpr std::size_t kContactFloats = 7;

// Little-endian packing whatever the host's byte order.
class Packer {
 public:
  void f32(double x) { u32(std::bit_cast<std::uint32_t>(static_cast<float>(x))); }
  void i16(int x) {
    const auto v = static_cast<std::uint16_t>(static_cast<std::int16_t>(x));
    bytes_.push_back(static_cast<unsigned char>(v & 0xff));
    bytes_.push_back(static_cast<unsigned char>(v >> 8));
  }
  void u32(std::uint32_t v) {
    for (int k = 0; k < 4; ++k) bytes_.push_back(static_cast<unsigned char>(v >> (8 * k) & 0xff));
  }
  void vec3(const Vec3& v) {
    for (int k = 0; k < 3; ++k) f32(v[k]);
  }
  std::string text() const { return base64(bytes_); }

 private:
  std::vector<unsigned char> bytes_;
};

std::string seconds_text(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f s", t);
  return buf;
}

std::size_t ceil_div(std::size_t a, std::size_t b) { return b == 0 ? 1 : std::max<std::size_t>(1, (a + b - 1) / b); }

// The frames kept: every `stride`-th, and always the last.
std::vector<std::size_t> kept_frames(std::size_t frames, std::size_t stride) {
  std::vector<std::size_t> kept;
  for (std::size_t f = 0; f < frames; f += stride) kept.push_back(f);
  if (frames > 0 && kept.back() != frames - 1) kept.push_back(frames - 1);
  return kept;
}

json engine_data(const Recording& r, const std::vector<std::size_t>& frames, std::size_t contact_stride) {
  const FrameSeries& s = r.frames;
  Packer states, contacts, pairs, features;
  json t = json::array(), energy = json::array(), counts = json::array();
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::size_t f = frames[k];
    t.push_back(s.t[f]);
    energy.push_back(f < s.energy.size() ? json(s.energy[f]) : json(nullptr));
    for (const BodyState& b : s.states[f]) {
      states.vec3(b.position);
      for (const double q : {b.orientation.w(), b.orientation.x(), b.orientation.y(), b.orientation.z()}) states.f32(q);
      states.vec3(b.velocity);
      states.vec3(b.angular_velocity);
    }
    const bool keep_contacts = f < s.contacts.size() && k % contact_stride == 0;
    counts.push_back(keep_contacts ? s.contacts[f].size() : 0);
    if (!keep_contacts) continue;
    for (const BodyContact& bc : s.contacts[f]) {
      contacts.vec3(bc.contact.position);
      contacts.vec3(bc.contact.normal);
      contacts.f32(bc.contact.depth);
      pairs.i16(bc.body_a);
      pairs.i16(bc.body_b);
      features.u32(bc.contact.feature.value);
    }
  }
  json stopped = nullptr;
  if (r.stopped) {
    stopped = {{"step", r.stopped->step}, {"t", r.stopped->t}, {"body", r.stopped->body}, {"quantity", r.stopped->quantity}};
  }
  return {{"name", r.engine},         {"colour", engine_colour(r.engine)}, {"t", std::move(t)},           {"energy", std::move(energy)},
          {"states", states.text()},  {"contact_counts", counts},    {"contacts", contacts.text()},
          {"contact_bodies", pairs.text()}, {"contact_features", features.text()}, {"stopped", stopped}};
}

// Checks one packed array: valid base64 of exactly `count` items of `item_bytes`.
void check_packed(const JsonNode& node, std::size_t count, std::size_t item_bytes) {
  const std::optional<std::vector<unsigned char>> bytes = unbase64(node.string());
  if (!bytes) node.fail("is not base64");
  if (bytes->size() != count * item_bytes) {
    node.fail("holds " + std::to_string(bytes->size()) + " bytes, expected " + std::to_string(count * item_bytes));
  }
}

}  // namespace

std::string base64(const std::vector<unsigned char>& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = static_cast<std::uint32_t>(bytes[i]) << 16;
    if (n > 1) v |= static_cast<std::uint32_t>(bytes[i + 1]) << 8;
    if (n > 2) v |= bytes[i + 2];
    for (std::size_t k = 0; k < 4; ++k) out.push_back(k <= n ? kAlphabet[v >> (18 - 6 * k) & 63] : '=');
  }
  return out;
}

std::optional<std::vector<unsigned char>> unbase64(const std::string& text) {
  if (text.size() % 4 != 0) return std::nullopt;
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::vector<unsigned char> out;
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    const int pad = last ? (text[i + 3] == '=') + (text[i + 2] == '=') : 0;
    if (pad == 1 && text[i + 2] == '=') return std::nullopt;  // "x=y=" is not padding
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) {
      const int d = k >= 4 - pad ? 0 : value(text[i + static_cast<std::size_t>(k)]);
      if (d < 0) return std::nullopt;
      v = v << 6 | static_cast<std::uint32_t>(d);
    }
    for (int k = 0; k < 3 - pad; ++k) out.push_back(static_cast<unsigned char>(v >> (16 - 8 * k) & 0xff));
  }
  return out;
}

std::vector<ReplayMark> marks_from_report(const json& report) {
  std::vector<ReplayMark> marks;
  if (!report.contains("pairs")) return marks;
  for (const json& p : report.at("pairs")) {
    const auto passes = [&](const char* key) { return p.contains(key) && p.at(key).is_number(); };
    const bool position = passes("position_passes"), orientation = passes("orientation_passes");
    if (!position && !orientation) continue;
    const double tp = position ? p.at("position_passes").get<double>() : INFINITY;
    const double to = orientation ? p.at("orientation_passes").get<double>() : INFINITY;
    const std::string pair = p.at("engines").at(0).get<std::string>() + " / " + p.at("engines").at(1).get<std::string>();
    std::string what = tp <= to ? "position differs by more than " + json(p.value("position_threshold", 0.0)).dump() + " m"
                                : "orientation differs by more than " + json(p.value("orientation_threshold", 0.0)).dump() + " rad";
    marks.push_back({std::min(tp, to), pair + ": " + what + " at " + seconds_text(std::min(tp, to)) + " (" +
                                           p.value("verdict", std::string("?")) + ")"});
  }
  std::sort(marks.begin(), marks.end(), [](const ReplayMark& a, const ReplayMark& b) { return a.t < b.t; });
  return marks;
}

json replay_data(const std::string& title, const std::vector<const Recording*>& runs,
                 const std::vector<ReplayMark>& marks, const ReplayBudget& budget) {
  std::size_t frames = 0, bodies = 0, body_states = 0, contact_points = 0;
  for (const Recording* r : runs) {
    frames = std::max(frames, r->frames.t.size());
    bodies = r->shapes.bodies.size();
    body_states += r->frames.t.size() * bodies;
    for (const auto& c : r->frames.contacts) contact_points += c.size();
  }
  const std::size_t frame_stride = ceil_div(body_states, budget.body_states);
  const std::size_t contact_stride = ceil_div(contact_points / frame_stride, budget.contact_points);

  json notes = json::array();
  if (frame_stride > 1) {
    notes.push_back("one recorded frame in " + std::to_string(frame_stride) + " is kept (" + std::to_string(body_states) +
                    " body states over the page's budget of " + std::to_string(budget.body_states) + ")");
  }
  if (contact_stride > 1) {
    notes.push_back("contacts are drawn on one frame in " + std::to_string(contact_stride) + " only (" +
                    std::to_string(contact_points) + " contact points over the page's budget of " +
                    std::to_string(budget.contact_points) + ")");
  }
  json engines = json::array();
  for (const Recording* r : runs) {
    engines.push_back(engine_data(*r, kept_frames(r->frames.t.size(), frame_stride), contact_stride));
  }
  json marks_json = json::array();
  for (const ReplayMark& m : marks) marks_json.push_back({{"t", m.t}, {"label", m.label}});
  return {{"format", kFormat},
          {"title", title},
          {"dt", runs.empty() ? 0.0 : runs.front()->dt},  // s, the simulation step
          {"shapes", runs.empty() ? json(nullptr) : shapes_json(runs.front()->shapes)},
          {"frame_stride", frame_stride},
          {"contact_stride", contact_stride},
          {"engines", std::move(engines)},
          {"marks", std::move(marks_json)},
          {"notes", std::move(notes)}};
}

void check_replay_data(const json& data, const std::string& source) {
  const JsonNode root(data, source);
  root.expect_object({"format", "title", "dt", "shapes", "frame_stride", "contact_stride", "engines", "marks", "notes"});
  if (root.at("format").string() != kFormat) root.at("format").fail(std::string("expected \"") + kFormat + "\"");
  root.at("title").string();
  const SceneShapes shapes = read_document_shapes(data, source);
  const JsonNode engines = root.at("engines");
  const std::size_t n = engines.array_size();
  if (n == 0) engines.fail("a replay needs at least one engine");
  for (std::size_t e = 0; e < n; ++e) {
    const JsonNode engine = engines.element(e);
    engine.expect_object({"name", "colour", "t", "energy", "states", "contact_counts", "contacts", "contact_bodies",
                          "contact_features", "stopped"});
    engine.at("name").string();
    if (engine.has("colour")) {
      const std::string colour = engine.at("colour").string();
      const bool hex = colour.size() == 7 && colour[0] == '#' &&
                       std::all_of(colour.begin() + 1, colour.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
      if (!hex) engine.at("colour").fail("expected a colour \"#rrggbb\"");
    }
    const std::size_t frames = engine.at("t").array_size();
    engine.at("energy").expect_array_size(frames);
    const JsonNode counts = engine.at("contact_counts");
    counts.expect_array_size(frames);
    std::size_t points = 0;
    for (std::size_t f = 0; f < frames; ++f) points += static_cast<std::size_t>(std::max(0, counts.element(f).integer()));
    check_packed(engine.at("states"), frames * shapes.bodies.size(), kStateFloats * 4);
    check_packed(engine.at("contacts"), points, kContactFloats * 4);
    check_packed(engine.at("contact_bodies"), points, 2 * 2);
    check_packed(engine.at("contact_features"), points, 4);
  }
  const JsonNode marks = root.at("marks");
  for (std::size_t i = 0, m = marks.array_size(); i < m; ++i) {
    marks.element(i).at("t").number();
    marks.element(i).at("label").string();
  }
}

}  // namespace boxpile
