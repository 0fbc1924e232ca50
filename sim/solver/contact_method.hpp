// The seam between the world and the way it resolves contacts, and the registry of the methods.
// The world owns what every method shares (bodies, the contact set, the integrators, the wires)
// and, for each step, finds the contact set and hands it to the method the scene's
// `solver.method` names (the shape of qu3e's q3Island::Solve and of MuJoCo's mj_step, whose
// integrator is a switch).
//
// A contact method is one row of the registry (contact_methods()): its name, its meaning, its
// settings (declared once: the scene loader, `--set own.KEY`, sweep grids and `boxpile settings`
// read them from the row), its variants, how it is built, and what it reports of its work
// (ContactMethod::diagnostics). Adding a method is adding a row (register_contact_method).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/io/setting.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/sim/solver/step_context.hpp"

namespace boxpile {

class ContactMethod {
 public:
  virtual ~ContactMethod() = default;
  // How many steps of dt / n the method takes per scene step; the world finds the contact set
  // before each of them.
  virtual int substeps() const { return 1; }
  // Whether the world grows each body's contact margin by its motion in the step (speculative
  // contacts); without them only touching or overlapping points are contacts.
  virtual bool speculative_margins() const { return true; }
  // Whether the world may copy a pair's contacts from the last step while neither body moves.
  virtual bool reuses_contacts() const { return false; }
  // Resolves the contact set of ctx and advances the bodies by ctx.dt.
  virtual void step(StepContext& ctx) = 0;
  // What the method did, from its own records (its statistics of the last step, its counters so
  // far), as `run --out` records it per frame ({"method": name, ...}); `events` is the world's
  // collision events so far.
  virtual nlohmann::json diagnostics(std::size_t events) const = 0;
};

// A problem a method finds with a scene it is to run: the field (a JSON pointer into the scene
// file, e.g. "/time/dt") and what is wrong with it.
struct SceneProblem {
  std::string pointer;
  std::string message;
};

// One variant of a method: a named preset of its settings (applied before any setting given
// beside it).
struct MethodVariant {
  std::string name;
  std::string what;  // one line
  std::function<void(Scene&)> apply;
};

// One contact method.
struct ContactMethodRow {
  std::string name;  // the scene's solver.method, engine "own-NAME"
  std::string what;  // one line: what it is
  // Its settings, each one declared once (group: this method's name, filled in on registration).
  std::vector<Setting<Scene>> settings;
  // Its variants, the first one the default; none: it has no "variant" setting.
  std::vector<MethodVariant> variants;
  // The method built for a scene and its bodies; throws std::invalid_argument on settings it
  // cannot run.
  std::function<std::unique_ptr<ContactMethod>(const Scene&, const std::vector<RigidBody>&)> make;
  // Steps of the method per scene step (the work of a step); none: 1.
  std::function<long(const Scene&)> work_per_step;
  // Why the scene's time step is one the method cannot run ("" when it can); none: never.
  std::function<std::string(const Scene&)> time_step_problem;
  // A problem with a loaded scene that its settings alone do not show (root: the scene file);
  // none: never.
  std::function<std::optional<SceneProblem>(const nlohmann::json& root, const Scene&)> check_scene;
};

// Every method, in the order help texts list them (impulse, penalty, then registered ones).
const std::vector<ContactMethodRow>& contact_methods();
// The row of that name, or none.
const ContactMethodRow* find_contact_method(std::string_view name);
// The row of that name; std::invalid_argument naming `field` and the available names otherwise.
const ContactMethodRow& contact_method(std::string_view name, std::string_view field = "solver.method");
// The methods' names, in registry order.
std::vector<std::string_view> contact_method_names();
// Adds a method (its settings' group set to its name). Must happen before the settings table is
// first read (a static registration does): std::logic_error after that, or for a name taken.
void register_contact_method(ContactMethodRow row);
// Called when the settings table is built from the registry: later registrations are refused.
void freeze_contact_methods();

// The method the scene's solver settings name, built for its bodies.
std::unique_ptr<ContactMethod> make_contact_method(const Scene& scene, const std::vector<RigidBody>& bodies);

// The built-in rows (defined beside each method).
ContactMethodRow impulse_method_row();
ContactMethodRow penalty_method_row();

}  // namespace boxpile
