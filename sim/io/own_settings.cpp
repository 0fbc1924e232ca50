#include "boxpile/sim/io/own_settings.hpp"

#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/thread_pool.hpp"
#include "boxpile/sim/solver/contact_method.hpp"

namespace boxpile {

using nlohmann::json;
using Kind = SettingInfo::Kind;

namespace {

// The settings every method reads, by the part of the scene they lie in.
std::vector<Setting<Scene>> shared_rows(std::string_view section) {
  using S = Scene;
  if (section == "solver") return {
      // Every method: the contact set they share.
      {{.key = "contact_margin", .kind = Kind::Number, .unit = "m",
        .what = "points this far apart stay in the step's contact set", .min = 0, .max = limits::kMaxMargin,
        .scene_key = "solver.contact_margin"},
       [](S& s, const json& v) { s.solver.contact_margin = v.get<double>(); },
       [](const S& s) { return json(s.solver.contact_margin); }},
      {{.key = "threads", .kind = Kind::Integer,
        .what = "threads a step runs on: the contact search's pairs and the impulse method's islands of touching "
                "bodies shared among them (0: every core); the result is the same to the bit for any number",
        .min = 0, .max = kMaxThreads, .scene_key = "solver.threads"},
       [](S& s, const json& v) { s.solver.threads = v.get<int>(); },
       [](const S& s) { return json(s.solver.threads); }},
  };
  return {
      // Contact generation, shared by every method (the scene's `collision` object).
      scene_flag<&Scene::collision, &CollisionSettings::reduce_to_four>({.key = "reduce_to_four", .kind = Kind::Boolean, .what = "reduce each box-box manifold to at most 4 points",
        .scene_key = "collision.reduce_to_four"}),
      {{.key = "collision_margin", .kind = Kind::Number, .unit = "m",
        .what = "points up to this far apart count as contacts (speculative contacts)", .min = 0,
        .max = limits::kMaxMargin, .scene_key = "collision.margin"},
       [](S& s, const json& v) { s.collision.margin = v.get<double>(); },
       [](const S& s) { return json(s.collision.margin); }},
  };
}

bool in_section(const Setting<Scene>& row, std::string_view section) {
  return row.info.scene_key.starts_with(std::string(section) + ".");
}

}  // namespace

const SettingsTable<Scene>& own_settings_table() {
  // Built once from the registry: per part of the scene (solver, then collision), the settings
  // every method shares, then each method's in registry order (a method's variant comes first
  // among its own: it sets every addition after it, and the table applies its rows in order, so
  // an addition given beside it wins).
  static const SettingsTable<Scene> table = [] {
    freeze_contact_methods();
    std::vector<Setting<Scene>> rows;
    for (std::string_view section : {"solver", "collision"}) {
      for (Setting<Scene>& r : shared_rows(section)) rows.push_back(std::move(r));
      for (const ContactMethodRow& m : contact_methods())
        for (const Setting<Scene>& r : m.settings)
          if (in_section(r, section)) rows.push_back(r);
    }
    return SettingsTable<Scene>(std::move(rows));
  }();
  return table;
}

}  // namespace boxpile
