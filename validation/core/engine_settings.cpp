#include "boxpile/validation/core/engine_settings.hpp"

#include <algorithm>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/own_settings.hpp"

namespace boxpile {
namespace {

using json_input::in_quotes;
using json_input::JsonNode;
using nlohmann::json;

constexpr std::string_view kOwn = "own";
const std::string kSetSource = "command line";

// A "key=value" word split; InputError naming the word otherwise.
std::pair<std::string, json> split_word(const std::string& word) {
  const std::size_t eq = word.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(kSetSource, "--set", "expected [ENGINE.]KEY=VALUE, got " + in_quotes(word));
  }
  const std::string text = word.substr(eq + 1);
  json value = json::parse(text, nullptr, false);
  if (value.is_discarded()) value = text;
  return {word.substr(0, eq), value};
}

std::string names_text(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

SettingInfo find_setting(std::string_view engine, std::string_view key, const JsonNode& node) {
  const std::vector<SettingInfo> settings = engine_settings(engine);
  std::vector<std::string_view> names;
  for (const SettingInfo& s : settings) {
    if (s.key == key) return s;
    names.push_back(s.key);
  }
  std::string what = "engine " + in_quotes(engine) + " has no setting " + in_quotes(key);
  if (const auto close = json_input::closest_match(key, names)) what += "; did you mean " + in_quotes(*close) + "?";
  std::string all;
  for (std::string_view n : names) all += (all.empty() ? "" : ", ") + std::string(n);
  what += all.empty() ? " (it has none)" : " (its settings: " + all + ")";
  node.fail(what);
}

void apply_settings(std::string_view engine, const json& settings, EngineConfig& config) {
  const JsonNode root(settings, "settings");
  for (const auto& [key, value] : settings.items()) {
    const SettingInfo s = find_setting(engine, key, root);
    config.settings[key] = check_setting_value(s, root.at(key));
  }
}

std::optional<std::string> setting_method(std::string_view engine, std::string_view key) {
  if (engine != kOwn) return std::nullopt;
  for (const SettingInfo& s : engine_settings(engine))
    if (s.key == key) return s.group.empty() ? std::nullopt : std::optional<std::string>(s.group);
  return std::nullopt;
}

json parse_setting_words(std::string_view engine, const std::vector<std::string>& words, const std::string& source) {
  json settings = json::object();
  for (const std::string& word : words) {
    auto [key, value] = split_word(word);
    if (settings.contains(key)) throw InputError(source, "--set", "setting " + in_quotes(key) + " is given twice");
    settings[key] = std::move(value);
  }
  const JsonNode root(settings, source);
  for (auto& item : settings.items()) {
    const JsonNode value = root.at(item.key());
    item.value() = check_setting_value(find_setting(engine, item.key(), value), value);
  }
  return settings;
}

std::map<std::string, json> parse_set_options(const std::vector<std::string>& words,
                                              const std::vector<std::string>& engines) {
  std::map<std::string, std::vector<std::string>> by_engine;
  for (const std::string& word : words) {
    const std::string name = split_word(word).first;
    const std::size_t dot = name.find('.');
    std::string engine;
    std::string rest = word;
    if (dot != std::string::npos) {
      engine = name.substr(0, dot);
      rest = word.substr(dot + 1);
      check_engine_name(engine);  // UnknownEngine: exit 2, naming it and the available ones
      if (std::find(engines.begin(), engines.end(), engine) == engines.end()) {
        throw InputError(kSetSource, "--set",
                         "engine " + in_quotes(engine) + " is not running (engines: " + names_text(engines) +
                             "), so " + in_quotes(word) + " would do nothing");
      }
    } else if (engines.size() == 1) {
      engine = engines.front();
    } else {
      throw InputError(kSetSource, "--set",
                       in_quotes(word) + " names no engine while several run (" + names_text(engines) +
                           "): write ENGINE." + word);
    }
    by_engine[engine].push_back(rest);
  }
  std::map<std::string, json> out;
  for (const auto& [engine, list] : by_engine) {
    out[engine] = parse_setting_words(engine, list, kSetSource + " (--set " + engine + ".*)");
  }
  return out;
}

std::string settings_markdown() {
  std::string md;
  for (const std::string& engine : available_engine_names()) {
    const EngineRow& row = engine_row(engine);
    md += "### " + engine + "\n\n" + row.title + ".\n\n";
    const std::vector<SettingInfo> settings = engine_settings(engine);
    if (settings.empty()) {
      md += "No settings.\n\n";
      continue;
    }
    md += "| setting | values | default | unit | what it sets |\n|---|---|---|---|---|\n";
    for (const SettingInfo& s : settings) {
      md += "| `" + s.key + "` | " + setting_values_text(s) + " | " + setting_default_text(s) + " | " +
            (s.unit.empty() ? "—" : s.unit) + " | " + s.what + " |\n";
    }
    md += "\n";
  }
  return md;
}

}  // namespace boxpile
