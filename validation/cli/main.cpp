// boxpile: run box-pile scenes in our simulator and in ODE and Bullet, and compare them.
#include <iostream>

#include "sim/io/input_error.hpp"
#include "validation/cli/commands.hpp"
#include "validation/engine_factory.hpp"

int main(int argc, char** argv) {
  using namespace boxpile::cli;
  CLI::App app{"boxpile: a pile of boxes in our own simulator, checked against ODE and Bullet"};
  app.set_version_flag("--version", std::string("boxpile ") + BOXPILE_VERSION);
  app.require_subcommand(1);

  ContactsOptions contacts;
  add_contacts_command(app, contacts);
  RunOptions run;
  add_run_command(app, run);

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
  } catch (const boxpile::InputError& e) {
    std::cerr << "boxpile: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const boxpile::UnknownEngine& e) {
    std::cerr << "boxpile: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "boxpile: error: " << e.what() << '\n';
    return kExitFailure;
  }
  return kExitFailure;
}
