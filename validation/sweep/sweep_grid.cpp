#include "boxpile/validation/sweep/sweep_grid.hpp"

#include <filesystem>
#include <stdexcept>

#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/stability/scene_checks.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;
using json_input::JsonNode;

// More timed repetitions than this say nothing more about the least time and only cost.
constexpr int kMaxRepetitions = 100;

std::vector<GridScene> read_scenes(const JsonNode& node, const fs::path& base, const LoadLimits& caps) {
  std::vector<GridScene> scenes;
  const std::size_t n = node.array_size();
  if (n == 0) node.fail("must list at least one scene");
  for (std::size_t i = 0; i < n; ++i) {
    const JsonNode entry = node.element(i);
    const std::string path = entry.string();
    const fs::path file = fs::path(path).is_absolute() ? fs::path(path) : base / path;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) entry.fail("no scene file " + file.lexically_normal().string());
    scenes.push_back({path, load_checked_scene(file.lexically_normal().string(), caps)});
  }
  return scenes;
}

std::vector<double> read_steps(const JsonNode& node) {
  std::vector<double> dt;
  const std::size_t n = node.array_size();
  if (n == 0) node.fail("must list at least one time step (or leave \"dt\" out for each scene's own)");
  for (std::size_t i = 0; i < n; ++i) dt.push_back(json_input::read_positive(node.element(i)));
  return dt;
}

GridEngine read_engine(const std::string& name, const JsonNode& node) {
  try {
    check_engine_name(name);
  } catch (const UnknownEngine& e) {
    node.fail(e.what());
  }
  GridEngine engine{name, {}};
  if (!node.json().is_object()) node.fail("must be an object {setting: [values]}");
  for (const auto& item : node.json().items()) {
    const JsonNode values = node.at(item.key());
    const SettingInfo setting = find_setting(name, item.key(), values);
    const std::size_t n = values.array_size();
    if (n == 0) values.fail("must list at least one value");
    std::vector<nlohmann::json> list;
    for (std::size_t i = 0; i < n; ++i) {
      const JsonNode v = values.element(i);
      list.push_back(check_setting_value(setting, v));
    }
    engine.axes.emplace_back(item.key(), std::move(list));
  }
  return engine;
}

// Appends the product of `axes[k...]` to `out`, starting from `partial`.
void product(const std::vector<std::pair<std::string, std::vector<nlohmann::json>>>& axes, std::size_t k,
             nlohmann::json& partial, std::vector<nlohmann::json>& out) {
  if (k == axes.size()) {
    out.push_back(partial);
    return;
  }
  for (const nlohmann::json& v : axes[k].second) {
    partial[axes[k].first] = v;
    product(axes, k + 1, partial, out);
  }
  partial.erase(axes[k].first);
}

// "own" runs each scene's method: a setting of one method must not meet a scene of the other,
// where it would do nothing.
void check_methods(const SweepGrid& grid, const JsonNode& engines) {
  for (const GridEngine& engine : grid.engines) {
    for (const auto& axis : engine.axes) {
      const std::optional<std::string> method = setting_method(engine.name, axis.first);
      if (!method) continue;
      for (const GridScene& s : grid.scenes) {
        if (s.scene.solver.method == *method) continue;
        engines.at(engine.name).at(axis.first).fail(
            "a setting of the " + *method + " method, but scene " + s.path + " uses the " + s.scene.solver.method +
            " method; use engine \"own-" + *method + "\" to force one");
      }
    }
  }
}

}  // namespace

SweepGrid load_grid(const std::string& path, const LoadLimits& caps) {
  SweepGrid grid;
  grid.source = path;
  grid.document = json_input::parse(json_input::read_text_file(path, caps.max_input_bytes), path);
  const JsonNode root(grid.document, path);
  root.expect_object({"note", "scenes", "dt", "duration", "repetitions", "engines"});
  if (const auto note = root.find("note")) note->string();

  if (const auto d = root.find("duration")) grid.duration = json_input::read_positive(*d);
  if (const auto r = root.find("repetitions")) {
    grid.repetitions = r->integer();
    if (grid.repetitions < 1 || grid.repetitions > kMaxRepetitions) {
      r->fail("must be in [1, " + std::to_string(kMaxRepetitions) + "], got " + std::to_string(grid.repetitions));
    }
  }
  if (const auto d = root.find("dt")) grid.dt = read_steps(*d);

  const JsonNode engines = root.at("engines");
  if (!engines.json().is_object() || engines.json().empty()) engines.fail("must name at least one engine");
  for (const auto& item : engines.json().items()) grid.engines.push_back(read_engine(item.key(), engines.at(item.key())));

  // An engine's own time steps (its "dt" axis) are its cells' steps: the grid's would be a second.
  if (const auto d = root.find("dt")) {
    for (const GridEngine& engine : grid.engines) {
      if (engine.axis(time_step_setting().key)) {
        d->fail("given beside engine " + json_input::in_quotes(engine.name) +
                "'s own \"dt\": give the time steps in one place");
      }
    }
  }
  grid.scenes = read_scenes(root.at("scenes"), fs::path(path).parent_path(), caps);
  check_methods(grid, engines);
  if (grid.duration) {
    for (GridScene& s : grid.scenes) s.scene.time.duration = *grid.duration;
  }
  return grid;
}

std::vector<CellSpec> grid_cells(const SweepGrid& grid) {
  std::vector<CellSpec> cells;
  const std::string& dt_key = time_step_setting().key;
  for (std::size_t s = 0; s < grid.scenes.size(); ++s) {
    const std::vector<double> steps = grid.dt.empty() ? std::vector<double>{grid.scenes[s].scene.time.dt} : grid.dt;
    for (const GridEngine& engine : grid.engines) {
      std::vector<nlohmann::json> combos;
      nlohmann::json partial = nlohmann::json::object();
      product(engine.axes, 0, partial, combos);
      for (nlohmann::json& settings : combos) {
        // An engine's "dt" axis is the cell's time step, not one of its settings.
        if (const auto dt = settings.find(dt_key); dt != settings.end()) {
          const double own = dt->get<double>();
          settings.erase(dt_key);
          cells.push_back({static_cast<int>(cells.size()), static_cast<int>(s), engine.name, settings, own});
          continue;
        }
        for (double dt : steps) {
          cells.push_back({static_cast<int>(cells.size()), static_cast<int>(s), engine.name, settings, dt});
        }
      }
    }
  }
  return cells;
}

Shard parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  Shard shard;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    std::size_t used = 0;
    shard.index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw std::invalid_argument("not a number");
    const std::string count = text.substr(slash + 1);
    shard.count = std::stoi(count, &used);
    if (used != count.size()) throw std::invalid_argument("not a number");
  } catch (const std::exception&) {
    throw std::invalid_argument("--shard must be I/N (two whole numbers), got \"" + text + "\"");
  }
  if (shard.count < 1 || shard.index < 1 || shard.index > shard.count) {
    throw std::invalid_argument("--shard I/N needs 1 <= I <= N, got \"" + text + "\"");
  }
  return shard;
}

bool in_shard(const CellSpec& cell, const Shard& shard) { return cell.index % shard.count == shard.index - 1; }

}  // namespace boxpile
