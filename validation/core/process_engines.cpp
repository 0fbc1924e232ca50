#include "boxpile/validation/core/process_engines.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/validation/core/data_directory.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/output_safety.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;

// The node-hosted engines: their adapters under the data folder (docs/engine-protocol.md), with
// the npm packages they import in reference/node_modules beside them. The packages an engine
// imports are named once, in its folder's `packages` file (`npm NAME VERSION` lines, which
// scripts/install-deps and package.json follow); its title is made from them.
struct NodeEngine {
  std::string_view name;
  std::string_view title;
  std::string_view adapter;  // relative to the data folder; its folder holds the `packages` file
  std::string_view colour;   // in every plot and replay page (EngineRow::colour)
};
constexpr std::array<NodeEngine, 3> kNodeEngines = {{
    {"jolt", "Jolt Physics, single precision", "reference/jolt/jolt_engine.mjs", "#882255"},
    {"rapier", "Rapier, single precision", "reference/rapier/rapier_engine.mjs", "#44AA99"},
    {"mujoco-wasm", "MuJoCo 3.14, double precision", "reference/mujoco_wasm/mujoco_wasm_engine.mjs", "#999933"},
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

std::chrono::milliseconds& timeout_setting() {
  static std::chrono::milliseconds timeout = kDefaultEngineTimeout;
  return timeout;
}

// A declaration from a hello as the registry's: the engine checked its form (protocol.cpp).
SettingInfo declared_info(const protocol::DeclaredSetting& d) {
  SettingInfo info;
  info.key = d.key;
  info.kind = d.kind == "integer"   ? SettingInfo::Kind::Integer
              : d.kind == "boolean" ? SettingInfo::Kind::Boolean
              : d.kind == "choice"  ? SettingInfo::Kind::Choice
                                    : SettingInfo::Kind::Number;
  info.unit = d.unit;
  info.what = d.what;
  info.min = d.min;
  info.max = d.max;
  info.choices = d.choices;
  info.default_value = d.default_value;
  info.when_unset = "the engine's own";
  return info;
}

// The registry row of the program `command` known as `name`; `unavailable` says why it cannot
// run here (the row then has no factory). Its settings are asked of the program once.
EngineRow process_row(const std::string& name, std::string title, const std::string& command,
                      std::string unavailable) {
  EngineRow row;
  row.name = name;
  row.title = std::move(title);
  row.unavailable = std::move(unavailable);
  if (!row.unavailable.empty()) return row;
  row.make = [name, command](const Scene& scene, const nlohmann::json& settings) -> std::unique_ptr<Engine> {
    ProcessEngineOptions options;
    options.name = name;
    options.command = command;
    options.timeout = engine_timeout();
    options.settings = settings;
    options.while_waiting = throw_if_interrupted;
    return std::make_unique<ProcessEngine>(scene, std::move(options));
  };
  auto declared = std::make_shared<std::optional<std::vector<SettingInfo>>>();
  row.settings = [name, command, declared] {
    if (!*declared) {
      std::vector<SettingInfo> infos;
      for (const protocol::DeclaredSetting& d : ProcessEngine::ask_hello(name, command, engine_timeout()).settings)
        infos.push_back(declared_info(d));
      *declared = std::move(infos);
    }
    return **declared;
  };
  return row;
}

// "jolt-physics 1.1.0": the `npm NAME VERSION` lines of a `packages` file, joined by ", ";
// empty when the file is missing.
std::string npm_packages(const fs::path& list) {
  std::ifstream in(list);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string kind, name, version;
    if (!(words >> kind >> name >> version) || kind != "npm") continue;
    out += (out.empty() ? "" : ", ") + name + " " + version;
  }
  return out;
}

void add_node_row(const NodeEngine& e) {
  const auto add = [&e](EngineRow row) {
    row.colour = e.colour;
    add_engine(std::move(row));
  };
  const std::string plain_title = std::string(e.title) + " (WebAssembly in node)";
  if (!on_path("node")) {
    add(process_row(std::string(e.name), plain_title, "", std::string("node is not installed") + kInstallHint));
    return;
  }
  fs::path data;
  try {
    data = data_directory();
  } catch (const std::exception& error) {
    add(process_row(std::string(e.name), plain_title, "", error.what()));
    return;
  }
  const fs::path adapter = data / e.adapter, modules = data / kNodeModules;
  const std::string packages = npm_packages(adapter.parent_path() / "packages");
  const std::string title =
      packages.empty() ? plain_title : std::string(e.title) + " (WebAssembly in node, npm " + packages + ")";
  std::string unavailable;
  if (packages.empty()) {
    unavailable = "its package list is missing: " + (adapter.parent_path() / "packages").string();
  } else if (!fs::exists(adapter)) {
    unavailable = "its adapter is missing: " + adapter.string();
  } else if (!fs::is_directory(modules)) {
    unavailable = "its npm packages are missing: " + modules.string() + kInstallHint;
  }
  add(process_row(std::string(e.name), title, "node " + shell_quote(adapter.string()), unavailable));
}

bool valid_name(std::string_view name) {
  if (name.empty() || name.front() < 'a' || name.front() > 'z') return false;
  for (char c : name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) return false;
  }
  return true;
}

}  // namespace

void add_node_engines() {
  static const bool added = [] {
    for (const NodeEngine& e : kNodeEngines) add_node_row(e);
    return true;
  }();
  (void)added;
}

void add_engine_command(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos) {
    throw EngineCommandError("--engine-cmd: " + json_input::in_quotes(text) + " is not NAME=COMMAND");
  }
  const std::string name(text.substr(0, eq)), command(text.substr(eq + 1));
  if (!valid_name(name)) {
    throw EngineCommandError("--engine-cmd: the name " + json_input::in_quotes(name) +
                             " is not lowercase letters, digits and hyphens starting with a letter");
  }
  if (command.find_first_not_of(" \t") == std::string::npos) {
    throw EngineCommandError("--engine-cmd " + name + ": the command is empty");
  }
  // The names given by --engine-cmd so far, to tell them from the built-in engines in a message.
  static std::vector<std::string> given;
  if (find_engine_row(name)) {
    const bool earlier = std::find(given.begin(), given.end(), name) != given.end();
    throw EngineCommandError("--engine-cmd " + name + ": the name is taken by " +
                             (earlier ? "an earlier --engine-cmd" : "a built-in engine"));
  }
  add_engine(process_row(name, "a program over the engine protocol: " + command, command, ""));
  given.push_back(name);
}

void set_engine_timeout(double seconds) {
  if (!std::isfinite(seconds) || seconds <= 0.0 || seconds > kMaxEngineTimeoutSeconds) {
    throw EngineCommandError("--engine-timeout: must be a number of seconds in (0, " +
                             std::to_string(static_cast<long>(kMaxEngineTimeoutSeconds)) + "], got " +
                             std::to_string(seconds));
  }
  // At least a millisecond: poll's resolution.
  timeout_setting() = std::chrono::milliseconds(std::max(1L, std::lround(seconds * 1000.0)));
}

std::chrono::milliseconds engine_timeout() { return timeout_setting(); }

}  // namespace boxpile
