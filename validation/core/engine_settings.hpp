// The settings of the registry's engines as the command line and sweep grids give them: a key
// checked against the engine's declaration (reference/registry.hpp: each row's settings table),
// a value against its kind and range, `--set ENGINE.KEY=VALUE` words read into one checked
// object per engine, and every engine's table as Markdown (`boxpile settings`, docs/sweeps.md).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/io/setting.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// What one engine is built from: the scene and the engine's settings {key: value}, each checked
// against its declaration (make_engine(name, config.scene, config.settings)).
struct EngineConfig {
  Scene scene;
  nlohmann::json settings = nlohmann::json::object();
};

// The setting `key` of `engine`: InputError at `node`'s path naming the key (with the closest
// name and the engine's settings) when the engine has no such setting.
SettingInfo find_setting(std::string_view engine, std::string_view key, const json_input::JsonNode& node);

// Adds settings {key: value} (each already checked) to `config`; InputError for a key `engine`
// does not declare.
void apply_settings(std::string_view engine, const nlohmann::json& settings, EngineConfig& config);

// The contact method a setting of "own" belongs to (it runs each scene's method); empty for the
// settings of both methods and for every other engine (which forces its method or has none).
std::optional<std::string> setting_method(std::string_view engine, std::string_view key);

// Settings given as "key=value" words for one engine: each value read as JSON (5, 0.2, true,
// "world") or, when that fails, as a string (world); checked like a grid's. InputError naming
// `source` and the key otherwise (a key given twice too). Returns {key: value}.
nlohmann::json parse_setting_words(std::string_view engine, const std::vector<std::string>& words,
                                   const std::string& source);

// `--set ENGINE.KEY=VALUE` words (repeatable) for the engines that run: the prefix may be left
// out when one engine runs. Refused (UsageError, InputError or UnknownEngine, all exit 2): a word
// without "=", an unknown engine, an engine that is not running, an unknown key or a value out of
// its declaration, and a key given twice. Returns {engine: {key: value}} for the engines given.
std::map<std::string, nlohmann::json> parse_set_options(const std::vector<std::string>& words,
                                                        const std::vector<std::string>& engines);

// Every available engine's settings as Markdown tables (`boxpile settings`, docs/sweeps.md).
std::string settings_markdown();

}  // namespace boxpile
