#include "boxpile/validation/stability/scene_checks.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace boxpile {

using json_input::JsonNode;

// Generated from the files of validation/stability/checks/ (validation/CMakeLists.txt).
std::vector<const CheckRow*> generated_check_rows();

namespace {

// The rows in report order, and their keys with "reasons" (what a "checks" object may hold).
struct CheckTable {
  std::vector<const CheckRow*> rows;
  std::vector<std::string_view> keys;         // of the rows
  std::vector<std::string_view> object_keys;  // the rows' and "reasons"
};

const CheckTable& table() {
  static const CheckTable t = [] {
    CheckTable out;
    out.rows = generated_check_rows();
    std::sort(out.rows.begin(), out.rows.end(), [](const CheckRow* a, const CheckRow* b) {
      return a->order != b->order ? a->order < b->order : a->key < b->key;
    });
    for (const CheckRow* r : out.rows) out.keys.push_back(r->key);
    out.object_keys = out.keys;
    out.object_keys.push_back("reasons");
    return out;
  }();
  return t;
}

// checks.reasons: a non-empty text per check the scene holds, keyed as the checks are.
std::map<std::string, std::string> read_reasons(const JsonNode& node, const SceneCheckSet& set) {
  node.expect_object(std::span<const std::string_view>(table().keys));
  std::map<std::string, std::string> reasons;
  for (const std::string_view key : table().keys) {
    const auto r = node.find(key);
    if (!r) continue;
    if (!set.holds(key)) r->fail("gives a reason for a check the scene does not hold");
    std::string text = r->string();
    if (text.empty()) r->fail("must not be empty");
    reasons.emplace(std::string(key), std::move(text));
  }
  return reasons;
}

}  // namespace

std::span<const CheckRow* const> check_rows() { return table().rows; }

const CheckRow* find_check_row(std::string_view key) {
  for (const CheckRow* r : table().rows)
    if (r->key == key) return r;
  return nullptr;
}

bool SceneCheckSet::holds(std::string_view key) const {
  return std::any_of(held.begin(), held.end(), [&](const Held& h) { return h.row->key == key; });
}

bool SceneCheckSet::has_check_of_its_own() const {
  return std::any_of(held.begin(), held.end(), [](const Held& h) { return h.row->of_its_own; });
}

std::vector<std::string_view> SceneCheckSet::without_reason() const {
  std::vector<std::string_view> missing;
  for (const Held& h : held)
    if (!reasons.contains(std::string(h.row->key))) missing.push_back(h.row->key);
  return missing;
}

SceneCheckSet read_scene_checks(const Scene& scene) {
  // The object under its own key, so that messages name "checks.rest.max_move".
  const nlohmann::json doc = {{"checks", scene.checks.empty() ? nlohmann::json::object()
                                                              : json_input::parse(scene.checks, scene.source)}};
  const JsonNode node = JsonNode(doc, scene.source).at("checks");
  node.expect_object(std::span<const std::string_view>(table().object_keys));
  SceneCheckSet set;
  for (const CheckRow* row : table().rows) {
    std::optional<JsonNode> member = node.find(row->key);
    if (!member && !row->held_by_default) continue;
    set.held.push_back({row, row->read(member, scene)});
  }
  if (const auto r = node.find("reasons")) set.reasons = read_reasons(*r, set);
  return set;
}

Scene load_checked_scene(const std::string& path, const LoadLimits& caps) {
  Scene scene = load_scene(path, caps);
  read_scene_checks(scene);
  return scene;
}

Scene parse_checked_scene(const std::string& text, const std::string& source, const LoadLimits& caps) {
  Scene scene = parse_scene(text, source, caps);
  read_scene_checks(scene);
  return scene;
}

// --- helpers that several checks share ---

int read_check_body(const JsonNode& node, const Scene& scene) {
  const std::string name = node.string();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (scene.bodies[i].name == name) return static_cast<int>(i);
  node.fail("no body named " + json_input::in_quotes(name) + " in the scene");
}

PlaneSide read_plane_side(const JsonNode& node, const Scene& scene) {
  node.expect_object({"body", "normal", "offset"});
  PlaneSide p;
  p.body = read_check_body(node.at("body"), scene);
  const JsonNode normal = node.at("normal");
  p.normal = json_input::read_vec3(normal);
  if (!(p.normal.norm() > 0.0)) normal.fail("must not be zero");
  p.normal.normalize();
  p.offset = node.at("offset").number();
  return p;
}

std::vector<PlaneSide> read_plane_sides(const JsonNode& node, const Scene& scene) {
  std::vector<PlaneSide> sides;
  for (std::size_t i = 0; i < node.array_size(); ++i) sides.push_back(read_plane_side(node.element(i), scene));
  return sides;
}

namespace {

class FigureAtMost final : public Check {
 public:
  FigureAtMost(std::string name, double RunMeasures::*figure, double limit, std::string unit)
      : name_(std::move(name)), figure_(figure), limit_(limit), unit_(std::move(unit)) {}
  void evaluate(const RunView& run, std::vector<SceneCheckResult>& out) const override {
    out.push_back(at_most(name_, run.measures.*figure_, limit_, unit_));
  }

 private:
  std::string name_;
  double RunMeasures::*figure_;
  double limit_;
  std::string unit_;
};

}  // namespace

std::unique_ptr<Check> figure_at_most(std::string name, double RunMeasures::*figure, double limit, std::string unit) {
  return std::make_unique<FigureAtMost>(std::move(name), figure, limit, std::move(unit));
}

SceneCheckResult at_most(std::string name, double value, double limit, std::string unit) {
  return {std::move(name), value, limit, false, value <= limit, std::move(unit), {}, {}};
}

SceneCheckResult at_least(std::string name, double value, double limit, std::string unit) {
  return {std::move(name), value, limit, true, value >= limit, std::move(unit), {}, {}};
}

}  // namespace boxpile
