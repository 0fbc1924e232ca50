#include "boxpile/sim/solver/contact_method.hpp"

#include <stdexcept>

namespace boxpile {

namespace {

struct Registry {
  std::vector<ContactMethodRow> rows;
  bool frozen = false;
};

// The method's "variant" setting, made from its variants: it comes first among the method's
// settings, since it sets the others and the table applies its rows in order (so a setting given
// beside it wins).
Setting<Scene> variant_setting(const ContactMethodRow& row) {
  std::string what = "the " + row.name + " method: ";
  std::vector<std::string> names;
  for (std::size_t i = 0; i < row.variants.size(); ++i) {
    const MethodVariant& v = row.variants[i];
    what += (i == 0 ? "" : i + 1 == row.variants.size() ? " or " : ", ") + ("\"" + v.name + "\" (" + v.what + ")");
    names.push_back(v.name);
  }
  what += "; additions given beside it apply after it";
  return {{.key = "variant", .kind = SettingInfo::Kind::Choice, .what = what, .choices = names,
           .scene_key = "solver.variant"},
          [](Scene& s, const nlohmann::json& value) {
            // One method at most has the key (add_row): its variant of that name.
            const std::string name = value.get<std::string>();
            for (const ContactMethodRow& m : contact_methods()) {
              for (const MethodVariant& v : m.variants) {
                if (v.name != name) continue;
                s.solver.variant = name;
                v.apply(s);
                return;
              }
            }
            throw std::invalid_argument("solver.variant: unknown variant \"" + name + "\"");
          },
          [](const Scene& s) { return nlohmann::json(s.solver.variant); }};
}

void add_row(Registry& r, ContactMethodRow row) {
  if (row.name.empty() || !row.make) throw std::logic_error("a contact method needs a name and a make function");
  if (!row.variants.empty()) row.settings.insert(row.settings.begin(), variant_setting(row));
  for (const ContactMethodRow& other : r.rows) {
    if (other.name == row.name) throw std::logic_error("contact method \"" + row.name + "\" is registered twice");
    for (const Setting<Scene>& a : other.settings)
      for (const Setting<Scene>& b : row.settings)
        if (a.info.key == b.info.key)
          throw std::logic_error("contact method \"" + row.name + "\": setting \"" + b.info.key +
                                 "\" is the " + other.name + " method's already");
  }
  for (Setting<Scene>& s : row.settings) s.info.group = row.name;
  r.rows.push_back(std::move(row));
}

Registry& registry() {
  static Registry r = [] {
    Registry built;
    add_row(built, impulse_method_row());
    add_row(built, penalty_method_row());
    return built;
  }();
  return r;
}

}  // namespace

const std::vector<ContactMethodRow>& contact_methods() { return registry().rows; }

const ContactMethodRow* find_contact_method(std::string_view name) {
  for (const ContactMethodRow& row : contact_methods())
    if (row.name == name) return &row;
  return nullptr;
}

std::vector<std::string_view> contact_method_names() {
  std::vector<std::string_view> names;
  for (const ContactMethodRow& row : contact_methods()) names.push_back(row.name);
  return names;
}

const ContactMethodRow& contact_method(std::string_view name, std::string_view field) {
  if (const ContactMethodRow* row = find_contact_method(name)) return *row;
  std::string all;
  for (std::string_view n : contact_method_names()) all += (all.empty() ? "\"" : ", \"") + std::string(n) + "\"";
  throw std::invalid_argument(std::string(field) + ": unknown contact method \"" + std::string(name) +
                              "\"; expected one of " + all);
}

void register_contact_method(ContactMethodRow row) {
  Registry& r = registry();
  if (r.frozen) {
    throw std::logic_error("contact method \"" + row.name +
                           "\" registered after the settings table was built from the registry");
  }
  add_row(r, std::move(row));
}

void freeze_contact_methods() { registry().frozen = true; }

std::unique_ptr<ContactMethod> make_contact_method(const Scene& scene, const std::vector<RigidBody>& bodies) {
  return contact_method(scene.solver.method).make(scene, bodies);
}

}  // namespace boxpile
