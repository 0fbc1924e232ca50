#include "boxpile/validation/engine_factory.hpp"

#include <algorithm>
#include <array>

#include "boxpile/reference/bullet_engine.hpp"
#include "boxpile/reference/dart/dart_engine.hpp"
#include "boxpile/reference/ode_engine.hpp"
#include "boxpile/sim/world.hpp"

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
constexpr std::array<EngineEntry, 6> kEngines = {{
    {"own", &build_own, ""},
    {"own-impulse", &build_own_with<ContactSolver::Impulse>, ""},
    {"own-penalty", &build_own_with<ContactSolver::Penalty>, ""},
    {"ode", &build<OdeEngine>, ""},
    {"bullet", &build<BulletEngine>, ""},
    {"dart", &build<DartEngine>, ""},
}};

constexpr std::array<std::string_view, kEngines.size()> kAllNames = [] {
  std::array<std::string_view, kEngines.size()> names{};
  for (std::size_t i = 0; i < kEngines.size(); ++i) names[i] = kEngines[i].name;
  return names;
}();

constexpr std::size_t kAvailableCount = static_cast<std::size_t>(
    std::count_if(kEngines.begin(), kEngines.end(), available));

constexpr std::array<std::string_view, kAvailableCount> kAvailableNames = [] {
  std::array<std::string_view, kAvailableCount> names{};
  std::size_t k = 0;
  for (const EngineEntry& e : kEngines)
    if (available(e)) names[k++] = e.name;
  return names;
}();

std::string available_list() {
  std::string s;
  for (std::string_view n : kAvailableNames) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

}  // namespace

std::span<const std::string_view> engine_names() { return kAllNames; }
std::span<const std::string_view> available_engine_names() { return kAvailableNames; }

void check_engine_name(std::string_view name) {
  for (const EngineEntry& e : kEngines) {
    if (e.name != name) continue;
    if (available(e)) return;
    throw UnknownEngine("engine \"" + std::string(name) + "\": " + std::string(e.unavailable) +
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
  return nullptr;  // not reached: check_engine_name() has thrown
}

}  // namespace boxpile
