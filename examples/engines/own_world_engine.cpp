// An engine over docs/engine-protocol.md in C++: boxpile's own simulator (boxpile::sim's World)
// served to boxpile as a separate program. It shows what an engine program does (answer hello,
// build its world from load's resolved scene, step and report), and lets the tests check the
// protocol end to end: the same World in-process and over the protocol gives the same states to
// the last bit, and the benchmark bench_protocol measures what the protocol itself costs.
//
//   boxpile compare SCENE --engines own,served --engine-cmd served=build/bin/own_world_engine
#include <chrono>
#include <iostream>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "boxpile/sim/world.hpp"

namespace {

using nlohmann::json;
using boxpile::Quat;
using boxpile::Vec3;

Vec3 vec(const json& v) { return {v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()}; }
Quat quat(const json& v) { return Quat(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>(), v.at(3).get<double>()); }
json to_json(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }
json to_json(const Quat& q) { return json::array({q.w(), q.x(), q.y(), q.z()}); }

// The resolved scene of load as our Scene: the solver at its defaults (this engine declares no
// settings), each body's material as given (already combined with the effects).
boxpile::Scene scene_from(const json& s) {
  boxpile::Scene scene;
  scene.name = s.at("name").get<std::string>();
  scene.time.dt = s.at("dt").get<double>();
  scene.gravity = vec(s.at("gravity"));
  if (!s.at("ground").is_null()) scene.ground = boxpile::HalfSpace{vec(s["ground"].at("normal")), s["ground"].at("offset").get<double>()};
  const json& e = s.at("effects");
  scene.effects.friction = e.at("friction").get<bool>();
  scene.effects.restitution = e.at("restitution").get<bool>();
  scene.effects.damping = e.at("damping").get<bool>();
  scene.effects.gyroscopic = e.at("gyroscopic").get<bool>();
  scene.damping = {s.at("damping").at("linear").get<double>(), s.at("damping").at("angular").get<double>()};
  scene.material.friction = s.at("ground_material").at("friction").get<double>();
  scene.material.restitution = s.at("ground_material").at("restitution").get<double>();
  for (const json& b : s.at("bodies")) {
    boxpile::BodyDesc d;
    d.name = b.at("name").get<std::string>();
    d.fixed = b.at("fixed").get<bool>();
    d.mass = b.at("mass").get<double>();
    d.frame = {vec(b.at("position")), quat(b.at("orientation"))};
    d.velocity = vec(b.at("velocity"));
    d.angular_velocity = vec(b.at("angular_velocity"));
    d.material = boxpile::Material{b.at("friction").get<double>(), b.at("restitution").get<double>(), std::nullopt};
    for (const json& box : b.at("boxes")) {
      d.boxes.push_back({vec(box.at("half_extents")), vec(box.at("position")), quat(box.at("orientation"))});
    }
    if (b.contains("wire")) d.wire = boxpile::Wire{vec(b["wire"].at("from")), vec(b["wire"].at("to")), vec(b["wire"].at("anchor"))};
    scene.bodies.push_back(std::move(d));
  }
  return scene;
}

json answer_step(boxpile::World& world, const json& request, std::vector<boxpile::BodyState>& states,
                 std::vector<boxpile::BodyContact>& contacts) {
  const int n = request.value("n", 1);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < n; ++k) world.step();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  json answer = {{"ok", true}, {"time", world.time()}, {"engine_seconds", seconds}};
  if (request.value("state", true)) {
    world.body_states(states);
    json bodies = json::array();
    for (const boxpile::BodyState& s : states) {
      bodies.push_back({{"position", to_json(s.position)},
                        {"orientation", to_json(s.orientation)},
                        {"velocity", to_json(s.velocity)},
                        {"angular_velocity", to_json(s.angular_velocity)}});
    }
    answer["bodies"] = std::move(bodies);
  }
  if (request.value("contacts", false)) {
    world.contacts(contacts);
    json list = json::array();
    for (const boxpile::BodyContact& c : contacts) {
      list.push_back({{"a", c.body_a},
                      {"b", c.body_b},
                      {"position", to_json(c.contact.position)},
                      {"normal", to_json(c.contact.normal)},
                      {"depth", c.contact.depth}});
    }
    answer["contacts"] = std::move(list);
  }
  return answer;
}

}  // namespace

int main() {
  std::optional<boxpile::World> world;
  std::vector<boxpile::BodyState> states;
  std::vector<boxpile::BodyContact> contacts;
  std::string line;
  while (std::getline(std::cin, line)) {
    json answer;
    try {
      const json request = json::parse(line);
      const std::string op = request.at("op").get<std::string>();
      if (op == "hello") {
        answer = {{"ok", true},       {"protocol", 1},      {"name", "own-world"},
                  {"version", "boxpile::sim World, served over the engine protocol"},
                  {"precision", "float64"}, {"contacts", true}, {"timing", true}};
      } else if (op == "load") {
        world.emplace(scene_from(request.at("scene")));
        answer = {{"ok", true}};
      } else if (op == "step") {
        if (!world) throw std::runtime_error("step before load");
        answer = answer_step(*world, request, states, contacts);
      } else if (op == "quit") {
        std::cout << json{{"ok", true}}.dump() << std::endl;
        return 0;
      } else {
        throw std::runtime_error("unknown op \"" + op + "\"");
      }
    } catch (const std::exception& e) {
      answer = {{"ok", false}, {"error", e.what()}};
    }
    std::cout << answer.dump() << std::endl;  // endl: flushed at once, boxpile waits for it
  }
  return 0;
}
