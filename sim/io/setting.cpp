#include "boxpile/sim/io/setting.hpp"

#include "boxpile/sim/limits.hpp"

namespace boxpile {

using json_input::format_number;
using json_input::JsonNode;
using Kind = SettingInfo::Kind;

namespace {

// Integers are written in full ([1, 100000]), numbers as the loader writes them ([0, 1e+12]).
std::string bound_text(const SettingInfo& s, double x) {
  return s.kind == Kind::Integer ? std::to_string(static_cast<long long>(x)) : format_number(x);
}

// Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "[" + a temporary string.
std::string range_text(const SettingInfo& s) {
  std::string text(s.open_min ? "(" : "[");
  text += bound_text(s, s.min);
  text += ", ";
  text += bound_text(s, s.max);
  text += "]";
  return text;
}

}  // namespace

const SettingInfo& time_step_setting() {
  static const SettingInfo dt{.key = "dt", .kind = Kind::Number, .unit = "s",
                              .what = "the time step: every engine steps the scene by it",
                              .min = 0.0, .max = limits::kMaxTimeStep,
                              .when_unset = "the scene's time.dt", .open_min = true};
  return dt;
}

nlohmann::json check_setting_value(const SettingInfo& setting, const JsonNode& value) {
  switch (setting.kind) {
    case Kind::Integer: {
      const int n = value.integer();
      if (n < setting.min || n > setting.max) {
        value.fail("must be in " + range_text(setting) + ", got " + std::to_string(n));
      }
      return n;
    }
    case Kind::Number: {
      const double x = value.number();
      if (!(setting.open_min ? x > setting.min : x >= setting.min) || x > setting.max) {
        value.fail("must be in " + range_text(setting) + (setting.unit.empty() ? "" : " " + setting.unit) +
                   ", got " + format_number(x));
      }
      return x;
    }
    case Kind::Boolean:
      return value.boolean();
    case Kind::Choice: {
      const std::vector<std::string_view> names(setting.choices.begin(), setting.choices.end());
      return setting.choices[value.choice(names, setting.key)];
    }
  }
  return nullptr;  // not reached
}

std::string setting_values_text(const SettingInfo& s) {
  switch (s.kind) {
    case Kind::Integer:
      return "integer in " + range_text(s);
    case Kind::Number:
      return "number in " + range_text(s);
    case Kind::Boolean:
      return "true, false";
    case Kind::Choice: {
      std::string values;
      for (const std::string& c : s.choices) values += (values.empty() ? "" : ", ") + std::string("\"") + c + "\"";
      return values;
    }
  }
  return "";
}

std::string setting_default_text(const SettingInfo& s) {
  const nlohmann::json& d = s.default_value;
  if (d.is_null()) return s.when_unset;
  if (d.is_number_float()) return format_number(d.get<double>());
  return d.dump();
}

}  // namespace boxpile
