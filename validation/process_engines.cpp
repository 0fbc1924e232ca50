#include "boxpile/validation/process_engines.hpp"

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "boxpile/validation/data_directory.hpp"
#include "boxpile/validation/engine_factory.hpp"
#include "boxpile/validation/output_safety.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;

// The node-hosted engines: their adapters under the data folder (docs/engine-protocol.md), with
// the npm packages they import in reference/node_modules beside them.
struct NodeEngine {
  std::string_view name;
  std::string_view adapter;  // relative to the data folder
};
constexpr std::array<NodeEngine, 3> kNodeEngines = {{
    {"jolt", "reference/jolt/jolt_engine.mjs"},
    {"rapier", "reference/rapier/rapier_engine.mjs"},
    {"mujoco-wasm", "reference/mujoco_wasm/mujoco_wasm_engine.mjs"},
}};
constexpr const char* kNodeModules = "reference/node_modules";
constexpr const char* kInstallHint = " (run scripts/install-deps)";

// A word the shell passes on as it is.
std::string shell_quote(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::string_view rest(path);
  while (true) {
    const std::size_t colon = rest.find(':');
    const std::string dir(rest.substr(0, colon));
    if (!dir.empty() && access((dir + "/" + program).c_str(), X_OK) == 0) return true;
    if (colon == std::string_view::npos) return false;
    rest.remove_prefix(colon + 1);
  }
}

ProcessEngineRow node_row(const NodeEngine& e) {
  ProcessEngineRow row{std::string(e.name), "", "", true};
  if (!on_path("node")) {
    row.unavailable = std::string("node is not installed") + kInstallHint;
    return row;
  }
  fs::path data;
  try {
    data = data_directory();
  } catch (const std::exception& error) {
    row.unavailable = error.what();
    return row;
  }
  const fs::path adapter = data / e.adapter, modules = data / kNodeModules;
  if (!fs::exists(adapter)) {
    row.unavailable = "its adapter is missing: " + adapter.string();
  } else if (!fs::is_directory(modules)) {
    row.unavailable = "its npm packages are missing: " + modules.string() + kInstallHint;
  } else {
    row.command = "node " + shell_quote(adapter.string());
  }
  return row;
}

struct Table {
  std::vector<ProcessEngineRow> rows;
  int generation = 0;
  std::chrono::milliseconds timeout = kDefaultEngineTimeout;
};

Table& table() {
  static Table t = [] {
    Table made;
    for (const NodeEngine& e : kNodeEngines) made.rows.push_back(node_row(e));
    return made;
  }();
  return t;
}

bool valid_name(std::string_view name) {
  if (name.empty() || name.front() < 'a' || name.front() > 'z') return false;
  for (char c : name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) return false;
  }
  return true;
}

}  // namespace

const std::vector<ProcessEngineRow>& process_engines() { return table().rows; }

const ProcessEngineRow* find_process_engine(std::string_view name) {
  for (const ProcessEngineRow& row : table().rows) {
    if (row.name == name) return &row;
  }
  return nullptr;
}

int process_engines_generation() { return table().generation; }

void add_engine_command(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos) {
    throw EngineCommandError("--engine-cmd: \"" + std::string(text) + "\" is not NAME=COMMAND");
  }
  const std::string name(text.substr(0, eq)), command(text.substr(eq + 1));
  if (!valid_name(name)) {
    throw EngineCommandError("--engine-cmd: the name \"" + name +
                             "\" is not lowercase letters, digits and hyphens starting with a letter");
  }
  if (command.find_first_not_of(" \t") == std::string::npos) {
    throw EngineCommandError("--engine-cmd " + name + ": the command is empty");
  }
  if (const ProcessEngineRow* row = find_process_engine(name)) {
    throw EngineCommandError("--engine-cmd " + name + ": the name is taken by " +
                             (row->built_in ? "a built-in engine" : "an earlier --engine-cmd"));
  }
  for (std::string_view built_in : linked_engine_names()) {
    if (built_in == name) throw EngineCommandError("--engine-cmd " + name + ": the name is taken by a built-in engine");
  }
  table().rows.push_back({name, command, "", false});
  ++table().generation;
}

void set_engine_timeout(double seconds) {
  if (!std::isfinite(seconds) || seconds <= 0.0 || seconds > kMaxEngineTimeoutSeconds) {
    throw EngineCommandError("--engine-timeout: must be a number of seconds in (0, " +
                             std::to_string(static_cast<long>(kMaxEngineTimeoutSeconds)) + "], got " +
                             std::to_string(seconds));
  }
  // At least a millisecond: poll's resolution.
  table().timeout = std::chrono::milliseconds(std::max(1L, std::lround(seconds * 1000.0)));
}

std::chrono::milliseconds engine_timeout() { return table().timeout; }

std::unique_ptr<Engine> make_process_engine(const ProcessEngineRow& row, const Scene& scene) {
  ProcessEngineOptions options;
  options.name = row.name;
  options.command = row.command;
  options.timeout = engine_timeout();
  options.while_waiting = throw_if_interrupted;
  return std::make_unique<ProcessEngine>(scene, std::move(options));
}

}  // namespace boxpile
