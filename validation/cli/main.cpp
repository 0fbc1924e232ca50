// boxpile: run box-pile scenes in our simulator and in ODE and Bullet, and compare them.
#include <iostream>

#include "reference/ode_engine.hpp"
#include "sim/io/input_error.hpp"
#include "validation/cli/commands.hpp"
#include "validation/engine_factory.hpp"
#include "validation/output_safety.hpp"

int main(int argc, char** argv) {
  using namespace boxpile::cli;
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
    if (app.got_subcommand("contacts")) return run_contacts(contacts);
    if (app.got_subcommand("run")) return run_run(run);
    if (app.got_subcommand("compare")) return run_compare_command(compare);
    std::cerr << "boxpile: no command given: comparing the engines on the default scene "
                 "(`boxpile --help` lists the commands)\n";
    return run_compare_command(default_compare_options());
  } catch (const boxpile::InputError& e) {
    std::cerr << "boxpile: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const boxpile::UnknownEngine& e) {
    std::cerr << "boxpile: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const boxpile::OutputError& e) {
    std::cerr << "boxpile: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const UsageError& e) {
    std::cerr << "boxpile: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const boxpile::OdeError& e) {
    std::cerr << "boxpile: error: " << e.what() << " (the input is outside what ODE can take)\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "boxpile: error: " << e.what() << '\n';
    return kExitFailure;
  }
  return kExitFailure;
}
