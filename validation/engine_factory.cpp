#include "boxpile/validation/engine_factory.hpp"

#include <algorithm>
#include <array>
#include <vector>

#include "boxpile/reference/bullet_engine.hpp"
#include "boxpile/reference/ode_engine.hpp"
#include "boxpile/sim/world.hpp"
#include "boxpile/validation/process_engines.hpp"

namespace boxpile {
namespace {

using Factory = std::unique_ptr<Engine> (*)(const Scene&, const ReferenceSettings&);

struct EngineEntry {
  std::string_view name;
  Factory make;                  // null: not yet available
  std::string_view unavailable;  // why, when make is null (empty when available)
};

// Availability is read from the reason, not from `make`: GCC rejects comparing a function
// template's address in a constant expression under -fsanitize=null (the sanitizer build), so
// the tables below must not depend on it.
constexpr bool available(const EngineEntry& e) { return e.unavailable.empty(); }

template <class E>
std::unique_ptr<Engine> build(const Scene& scene, const ReferenceSettings& settings) {
  return std::make_unique<E>(scene, settings);
}

std::unique_ptr<Engine> build_own(const Scene& scene, const ReferenceSettings&) {
  return std::make_unique<World>(scene);
}

// Our simulator with its contact method forced, whatever the scene's solver.method says. The
// settings of the other method are then not read (docs/penalty.md, "Engines").
template <ContactSolver method>
std::unique_ptr<Engine> build_own_with(const Scene& scene, const ReferenceSettings&) {
  Scene forced = scene;
  forced.solver.method = method;
  return std::make_unique<World>(forced, method == ContactSolver::Impulse ? "own-impulse" : "own-penalty");
}

// Adding an engine is one line here.
constexpr std::array<EngineEntry, 5> kEngines = {{
    {"own", &build_own, ""},
    {"own-impulse", &build_own_with<ContactSolver::Impulse>, ""},
    {"own-penalty", &build_own_with<ContactSolver::Penalty>, ""},
    {"ode", &build<OdeEngine>, ""},
    {"bullet", &build<BulletEngine>, ""},
}};

constexpr std::array<std::string_view, kEngines.size()> kLinkedNames = [] {
  std::array<std::string_view, kEngines.size()> names{};
  for (std::size_t i = 0; i < kEngines.size(); ++i) names[i] = kEngines[i].name;
  return names;
}();

// The name lists with the engines over the protocol after the linked ones, rebuilt when a row is
// added to that table.
struct NameLists {
  int generation = -1;
  std::vector<std::string_view> all, available;
};

const NameLists& name_lists() {
  static NameLists lists;
  if (lists.generation == process_engines_generation()) return lists;
  lists = {process_engines_generation(), {}, {}};
  for (const EngineEntry& e : kEngines) {
    lists.all.push_back(e.name);
    if (available(e)) lists.available.push_back(e.name);
  }
  for (const ProcessEngineRow& row : process_engines()) {
    lists.all.push_back(row.name);
    if (row.unavailable.empty()) lists.available.push_back(row.name);
  }
  return lists;
}

std::string available_list() {
  std::string s;
  for (std::string_view n : name_lists().available) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

}  // namespace

std::span<const std::string_view> engine_names() { return name_lists().all; }
std::span<const std::string_view> available_engine_names() { return name_lists().available; }
std::span<const std::string_view> linked_engine_names() { return kLinkedNames; }

void check_engine_name(std::string_view name) {
  for (const EngineEntry& e : kEngines) {
    if (e.name != name) continue;
    if (available(e)) return;
    throw UnknownEngine("engine \"" + std::string(name) + "\": " + std::string(e.unavailable) +
                        "; available: " + available_list());
  }
  if (const ProcessEngineRow* row = find_process_engine(name)) {
    if (row->unavailable.empty()) return;
    throw UnknownEngine("engine \"" + std::string(name) + "\" is unavailable: " + row->unavailable +
                        "; available: " + available_list());
  }
  throw UnknownEngine("unknown engine \"" + std::string(name) + "\"; available: " + available_list());
}

std::unique_ptr<Engine> make_engine(std::string_view name, const Scene& scene,
                                    const ReferenceSettings& settings) {
  check_engine_name(name);
  for (const EngineEntry& e : kEngines) {
    if (e.name == name) return e.make(scene, settings);
  }
  if (const ProcessEngineRow* row = find_process_engine(name)) return make_process_engine(*row, scene);
  return nullptr;  // not reached: check_engine_name() has thrown
}

}  // namespace boxpile
