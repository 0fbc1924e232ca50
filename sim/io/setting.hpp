// One setting of an engine, declared once: its key, kind, unit, range or choices, meaning and
// default. Every reader of a setting uses its declaration: the scene loader (our solver's
// `solver` and `collision` keys), `--set ENGINE.KEY=VALUE`, sweep grids, `boxpile settings` and
// the docs' tables. An engine's settings are a SettingsTable<S> beside its settings struct S
// (sim/io/own_settings.hpp for ours, reference/ode/ode_settings.hpp, reference/bullet/
// bullet_settings.hpp); a value travels as JSON, is checked against the declaration here, and is
// applied to S by the row's own function.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/io/json_input.hpp"

namespace boxpile {

// What every reader needs to know of a setting, whatever struct it sets.
struct SettingInfo {
  enum class Kind { Integer, Number, Boolean, Choice };
  std::string key = {};
  Kind kind = Kind::Number;
  std::string unit = {};  // "" for dimensionless, counts and choices
  std::string what = {};  // one line: what it sets, in the engine's own words
  // Allowed range of an Integer or Number (inclusive; `min` excluded when open_min).
  double min = 0.0, max = 0.0;
  // The names of a Choice.
  std::vector<std::string> choices = {};
  // The value the engine runs with when the setting is not given; null when it is derived from
  // the scene (our penalty springs) or not known (an engine that does not say).
  nlohmann::json default_value = nullptr;
  // What a null default means, for the docs and `boxpile settings` ("derived from the scene",
  // "none").
  std::string when_unset = "derived from the scene";
  // Where a scene file gives it ("solver.contact_passes"), empty when only `--set` and sweep
  // grids do (the reference engines' settings).
  std::string scene_key = {};
  // The part of the engine that reads it, when the engine has parts that exclude each other (our
  // contact methods: "impulse" or "penalty"); empty when every configuration reads it.
  std::string group = {};
  // The range excludes `min`: (min, max] (a time step must be above 0).
  bool open_min = false;
};

// The time step, a setting of every engine (key "dt", s, in (0, kMaxTimeStep], the scene's
// time.dt when not given). The registry (reference/registry.hpp) lists it first among each
// engine's settings and writes it into the scene the engine is built from, so that the engine,
// the run loop's step count and the rulers all read the same dt.
const SettingInfo& time_step_setting();

// The setting's value at `value` checked against its declaration (type, range, choice) and
// normalised (an integer written 5.0 reads as 5); InputError at `value`'s path otherwise.
nlohmann::json check_setting_value(const SettingInfo& setting, const json_input::JsonNode& value);

// "integer in [1, 64]", "number in [0, 1]", "number in (0, 1]", "true, false", "\"quickstep\", \"world\"".
std::string setting_values_text(const SettingInfo& setting);
// The default as a docs table shows it: 0.2, true, "quickstep", or "derived" (null).
std::string setting_default_text(const SettingInfo& setting);

// One row of an engine's settings table: the declaration, how a checked value is written into
// the engine's settings struct S, and how S's value is read back (for the default, which is S's
// own member initialiser, and for the settings a report records).
template <class S>
struct Setting {
  SettingInfo info;
  void (*apply)(S& settings, const nlohmann::json& value);
  nlohmann::json (*read)(const S& settings);
};

namespace setting_detail {
template <class>
struct MemberOf;
template <class S, class T>
struct MemberOf<T S::*> {
  using Owner = S;
  using Type = T;
};
}  // namespace setting_detail

// The row of a setting that is one member of S, written and read back as it is (the JSON's type is
// the member's: int, double, bool, std::string): member_setting<&OdeSettings::erp>({"erp", ...}).
template <auto Member>
Setting<typename setting_detail::MemberOf<decltype(Member)>::Owner> member_setting(SettingInfo info) {
  using S = typename setting_detail::MemberOf<decltype(Member)>::Owner;
  using T = typename setting_detail::MemberOf<decltype(Member)>::Type;
  return {std::move(info), [](S& settings, const nlohmann::json& value) { settings.*Member = value.get<T>(); },
          [](const S& settings) { return nlohmann::json(settings.*Member); }};
}

// An engine's settings: the rows in the order `boxpile settings` lists them.
template <class S>
class SettingsTable {
 public:
  explicit SettingsTable(std::initializer_list<Setting<S>> rows, const S& defaults = S{})
      : SettingsTable(std::vector<Setting<S>>(rows), defaults) {}
  explicit SettingsTable(std::vector<Setting<S>> rows, const S& defaults = S{}) : rows_(std::move(rows)) {
    for (Setting<S>& row : rows_) row.info.default_value = row.read(defaults);
  }

  const std::vector<Setting<S>>& rows() const { return rows_; }
  // The declarations alone (what a registry row lists).
  std::vector<SettingInfo> infos() const {
    std::vector<SettingInfo> out;
    for (const Setting<S>& row : rows_) out.push_back(row.info);
    return out;
  }
  const Setting<S>* find(std::string_view key) const {
    for (const Setting<S>& row : rows_)
      if (row.info.key == key) return &row;
    return nullptr;
  }
  // Applies settings {key: value}, each already checked against this table (a key it does not
  // declare is a programming error: std::invalid_argument), in the table's row order whatever
  // the order of `values` (a row that sets others, as our impulse variant does, comes first).
  void apply(S& settings, const nlohmann::json& values) const {
    for (const auto& [key, value] : values.items())
      if (!find(key)) throw std::invalid_argument("no setting \"" + key + "\"");
    for (const Setting<S>& row : rows_)
      if (const auto v = values.find(row.info.key); v != values.end()) row.apply(settings, *v);
  }
  // `defaults` with settings {key: value} applied.
  S make(const nlohmann::json& values, S defaults = S{}) const {
    apply(defaults, values);
    return defaults;
  }
  // Every setting's value in `settings`, {key: value}.
  nlohmann::json values(const S& settings) const {
    nlohmann::json out = nlohmann::json::object();
    for (const Setting<S>& row : rows_) out[row.info.key] = row.read(settings);
    return out;
  }

 private:
  std::vector<Setting<S>> rows_;
};

}  // namespace boxpile
