// Every setting each engine exposes, by name, with its unit and allowed values: the vocabulary of
// a sweep grid (docs/sweeps.md lists them). A setting changes either the scene's solver and
// collision settings (our engine) or the reference engines' ReferenceSettings (ODE, Bullet).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/reference/settings.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// What one engine is built from: the scene (with our solver's settings) and the references'.
struct EngineConfig {
  Scene scene;
  ReferenceSettings reference;
};

struct EngineSetting {
  enum class Kind { Integer, Number, Boolean, Choice };
  std::string_view key;
  Kind kind = Kind::Number;
  std::string_view unit;  // "" for dimensionless, counts and choices
  std::string_view what;  // one line: what it sets, in the engine's own words
  // Allowed range of an Integer or Number (inclusive).
  double min = 0.0, max = 0.0;
  // The names of a Choice.
  std::span<const std::string_view> choices = {};
  // Sets the value in `config`; the value has already been checked by check_setting_value.
  void (*apply)(EngineConfig& config, const nlohmann::json& value) = nullptr;
};

// The settings `engine` exposes (empty for an engine without any). Throws UnknownEngine for a name
// the factory does not know.
std::span<const EngineSetting> engine_settings(std::string_view engine);

// The setting `key` of `engine`: InputError at `node`'s path naming the key (with the closest
// name) when the engine has no such setting.
const EngineSetting& find_setting(std::string_view engine, std::string_view key, const json_input::JsonNode& node);

// Checks one value of a setting (type, range, choice): InputError at `value`'s path otherwise.
void check_setting_value(const EngineSetting& setting, const json_input::JsonNode& value);

// Applies settings {key: value} (each already checked) to `config`.
void apply_settings(std::string_view engine, const nlohmann::json& settings, EngineConfig& config);

// The contact method a setting of "own" belongs to (it runs each scene's method); empty for the
// settings of both methods and for every other engine (which forces its method or has none).
std::optional<ContactSolver> setting_method(std::string_view engine, std::string_view key);

// Settings given as "key=value" words (a command line's --set): each value read as JSON (5, 0.2,
// true, "world") or, when that fails, as a string (world); checked like a grid's. InputError
// naming `source` and the key otherwise. Returns {key: value}.
nlohmann::json parse_setting_words(std::string_view engine, const std::vector<std::string>& words,
                                   const std::string& source);

// Every available engine's settings as Markdown tables (`boxpile settings`, docs/sweeps.md).
std::string settings_markdown();

}  // namespace boxpile
