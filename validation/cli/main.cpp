// boxpile: run box-pile scenes in our simulator and in ODE and Bullet, and compare them.
#include <iostream>

#include "boxpile/reference/mujoco/mujoco_messages.hpp"
#include "boxpile/reference/ode/ode_engine.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/engine_command_options.hpp"
#include "boxpile/reference/process/process_engine.hpp"
#include "boxpile/validation/process_engines.hpp"
#include "boxpile/validation/collider_process.hpp"
#include "boxpile/validation/detectors.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/output_safety.hpp"
#include "boxpile/validation/report_directory.hpp"

namespace {

// Errors of the user's input (a file, a name, a flag, an output path, a collider, an engine that
// breaks docs/engine-protocol.md, a scene outside what ODE can take): exit 2; anything else 1.
bool is_bad_input(const std::exception& e) {
  return dynamic_cast<const boxpile::InputError*>(&e) || dynamic_cast<const boxpile::UnknownEngine*>(&e) ||
         dynamic_cast<const boxpile::UnknownDetector*>(&e) || dynamic_cast<const boxpile::ColliderError*>(&e) ||
         dynamic_cast<const boxpile::OutputError*>(&e) || dynamic_cast<const boxpile::cli::UsageError*>(&e) ||
         dynamic_cast<const boxpile::OdeError*>(&e) || dynamic_cast<const boxpile::EngineProtocolError*>(&e) ||
         dynamic_cast<const boxpile::EngineCommandError*>(&e);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace boxpile::cli;
  // The node-hosted engines join the registry before any help text or engine list is made.
  boxpile::add_node_engines();
  CLI::App app{"boxpile: a pile of boxes in our own simulator, checked against ODE and Bullet"};
  app.set_version_flag("--version", std::string("boxpile ") + BOXPILE_VERSION);
  // No command runs the main job: compare on the default scene (the bone and the pile).
  app.require_subcommand(0, 1);
  app.footer(std::string("Without a command, boxpile runs `compare` on fixtures/scenes/bone_hits_pile.json into "
                          "./boxpile-report/.\n") +
             kExitCodesHelp);

  ContactsOptions contacts;
  add_contacts_command(app, contacts);
  RunOptions run;
  add_run_command(app, run);
  CompareOptions compare;
  add_compare_command(app, compare);
  SweepOptions sweep;
  add_sweep_command(app, sweep);
  StabilityOptions stability;
  add_stability_command(app, stability);
  ConformOptions conform;
  add_conform_command(app, conform);
  ViewOptions view;
  add_view_command(app, view);
  // The commands that run engines take engines over the protocol too.
  EngineCommandOptions engine_commands;
  for (const char* name : {"run", "compare", "stability", "sweep"}) {
    add_engine_command_options(*app.get_subcommand(name), engine_commands);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }

  try {
    apply_engine_command_options(engine_commands);
    if (app.got_subcommand("contacts")) return run_contacts(contacts);
    if (app.got_subcommand("run")) return run_run(run);
    if (app.got_subcommand("compare")) return run_compare_command(compare);
    if (app.got_subcommand("sweep")) return run_sweep_command(sweep);
    if (app.got_subcommand("sweep-merge")) return run_sweep_merge_command(sweep);
    if (app.got_subcommand("settings")) return run_settings_command();
    if (app.got_subcommand("stability")) return run_stability_command(stability);
    if (app.got_subcommand("conform")) return run_conform_command(conform);
    if (app.got_subcommand("view")) return run_view(view);
    std::cerr << "boxpile: no command given: comparing the engines on the default scene "
                 "(`boxpile --help` lists the commands)\n";
    return run_compare_command(default_compare_options());
  } catch (const boxpile::OdeError& e) {
    std::cerr << "boxpile: error: " << e.what() << " (the input is outside what ODE can take)\n";
    return kExitBadInput;
  } catch (const boxpile::MujocoError& e) {
    std::cerr << "boxpile: error: " << e.what() << " (the input is outside what MuJoCo can take)\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "boxpile: error: " << e.what() << '\n';
    return is_bad_input(e) ? kExitBadInput : kExitFailure;
  }
  return kExitFailure;
}
