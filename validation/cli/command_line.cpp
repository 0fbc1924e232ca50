#include "boxpile/validation/cli/command_line.hpp"

#include <iostream>
#include <new>
#include <string>
#include <string_view>

#include "boxpile/reference/mujoco/mujoco_messages.hpp"
#include "boxpile/reference/ode/ode_engine.hpp"
#include "boxpile/reference/process/process_engine.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/validation/cli/accuracy_command.hpp"
#include "boxpile/validation/cli/activity.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/engine_command_options.hpp"
#include "boxpile/validation/cli/terminal_output.hpp"
#include "boxpile/validation/collider_process.hpp"
#include "boxpile/validation/detectors.hpp"
#include "boxpile/validation/output_safety.hpp"
#include "boxpile/validation/process_engines.hpp"
#include "boxpile/validation/report_directory.hpp"
#include "boxpile/validation/run_loop.hpp"

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

// A CLI11 parse error as one line of ours: "boxpile: error: run: --every: ..." (the command it
// arose in, "$" for the top level, its lines joined), then the hint to --help.
int parse_error(const CLI::App& app, const CLI::ParseError& e) {
  std::string what = e.what();
  for (std::size_t at = what.find('\n'); at != std::string::npos; at = what.find('\n', at)) {
    what.replace(at, 1, "; ");
  }
  while (!what.empty() && (what.back() == ' ' || what.back() == ';')) what.pop_back();
  const CLI::App* where = &app;
  for (const CLI::App* sub : app.get_subcommands()) where = sub;
  const std::string place = where == &app ? "$" : where->get_name();
  std::cerr << "boxpile: error: " << place << ": " << boxpile::json_input::shortened(what) << "\n"
            << "Run with --help for more information.\n";
  return boxpile::cli::kExitBadInput;
}

// Each command's own exit codes, shown by its --help (the top level's help gives the general rule).
struct CommandExits {
  const char* command;
  const char* exits;
};
constexpr CommandExits kCommandExits[] = {
    {"contacts", "0 the contact sets were printed (under --serve: the input ended); 2 bad input (the query, a "
                 "flag, a detector name)"},
    {"run", "0 the run ended (and --out was written); 1 a state became non-finite (nothing written) or anything "
            "unexpected; 2 bad input (scene, flag, output location, a scene outside what an engine can take)"},
    {"compare", "0 every engine ran to the end and the report was written; 1 an engine failed (the report says "
                "where and why) or anything unexpected; 2 bad input (scene, flag, engine name, report directory)"},
    {"sweep", "0 the report was written (cells that failed a check or went unstable are findings in it); 1 "
              "anything unexpected; 2 bad input (the grid, a flag, the report directory)"},
    {"sweep-merge", "0 the merged report was written; 2 bad input (a shard report that is missing, broken or of "
                    "another grid; the report directory)"},
    {"settings", "0 the tables were printed"},
    {"stability", "0 our engine passed every check of every scene (other engines' failures are findings); 1 our "
                  "engine failed a check, or anything unexpected; 2 bad input (a scene, a flag, an engine name, the "
                  "report directory)"},
    {"stability-merge", "0 the merged report was written (our engine's failures are in it, not in the exit code); 2 "
                        "bad input (a shard report that is missing, broken, of another run or given twice; a shard "
                        "missing; the report directory)"},
    {"conform", "0 the collider is within every gate; 1 it is not (conform.md says where); 2 bad input (a flag, "
                "the cases, the report directory) or a collider that dies, hangs or answers what the protocol "
                "does not allow"},
    {"scene", "0 the scene was written; 2 bad input (a kind, a size out of range or not the kind's, the output "
              "location)"},
    {"accuracy", "0 the report was written (an engine that went non-finite at a step is a warning and a finding "
                 "in it); 1 anything unexpected; 2 bad input (a scene, its truth, a flag, an engine name, a time "
                 "step beyond the caps, the report directory)"},
    {"view", "0 the page was written; 2 bad input (a run file or report directory that is missing or broken, "
             "the output location)"},
};

}  // namespace

namespace boxpile::cli {

int run_command_line(int argc, const char* const* argv, CommandLineMode mode) {
  // Before anything else: Ctrl-C while the arguments are parsed or a scene is loaded exits 130
  // like one during a run.
  if (mode == CommandLineMode::Run) install_signal_handlers();
  // Everything printed for people from here on is escaped (terminal_output.hpp).
  const TerminalEscaping escaping;
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
  SceneOptions scene;
  add_scene_command(app, scene);
  AccuracyOptions accuracy;
  add_accuracy_command(app, accuracy);
  for (const CommandExits& c : kCommandExits) {
    app.get_subcommand(c.command)->footer(std::string("Exit codes: ") + c.exits + "; 130 interrupted (nothing written).");
  }
  // The commands that run engines take engines over the protocol too.
  EngineCommandOptions engine_commands;
  for (const char* name : {"run", "compare", "stability", "sweep", "accuracy"}) {
    add_engine_command_options(*app.get_subcommand(name), engine_commands);
  }

  // CLI11 drops the empty names of a list (`--engines own,,ode` would run own and ode).
  for (int i = 1; i + 1 < argc; ++i) {
    const std::string_view flag = argv[i], list = argv[i + 1];
    if (flag != "--engines" && flag != "--regimes") continue;
    if (list.empty() || list.front() == ',' || list.back() == ',' || list.find(",,") != std::string_view::npos) {
      std::cerr << "boxpile: error: " << flag << ": an empty name in " << boxpile::json_input::in_quotes(list)
                << " (two commas together, or one at an end)\n";
      return kExitBadInput;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    // CLI11 answers --version as soon as it meets it, so `--version junk` would pass silently.
    if (argc != 2) {
      std::cerr << "boxpile: error: $: --version takes no other argument (" << argc - 2 << " given)\n";
      return kExitBadInput;
    }
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return parse_error(app, e);
  }
  // The engines of --engine-cmd join the registry, a process-wide table, only when the command runs.
  if (mode == CommandLineMode::ParseOnly) return kExitOk;

  try {
    apply_engine_command_options(engine_commands);
    if (app.got_subcommand("contacts")) return run_contacts(contacts);
    if (app.got_subcommand("run")) return run_run(run);
    if (app.got_subcommand("compare")) return run_compare_command(compare);
    if (app.got_subcommand("sweep")) return run_sweep_command(sweep);
    if (app.got_subcommand("sweep-merge")) return run_sweep_merge_command(sweep);
    if (app.got_subcommand("settings")) return run_settings_command();
    if (app.got_subcommand("stability")) return run_stability_command(stability);
    if (app.got_subcommand("stability-merge")) return run_stability_merge_command(stability);
    if (app.got_subcommand("conform")) return run_conform_command(conform);
    if (app.got_subcommand("view")) return run_view(view);
    if (app.got_subcommand("scene")) return run_scene_command(scene);
    if (app.got_subcommand("accuracy")) return run_accuracy_command(accuracy);
    std::cerr << "boxpile: no command given: comparing the engines on the default scene "
                 "(`boxpile --help` lists the commands)\n";
    return run_compare_command(default_compare_options());
  } catch (const boxpile::OutOfMemory& e) {
    std::cerr << "boxpile: error: " << Activity::current() << ": " << e.what() << '\n';
    return kExitFailure;
  } catch (const std::bad_alloc&) {
    std::cerr << "boxpile: error: out of memory "
              << (Activity::current().empty() ? std::string("(no phase recorded)") : "while " + Activity::current())
              << " (the caps --max-bodies, --max-pairs and --max-input-bytes bound what a run may build)\n";
    return kExitFailure;
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

}  // namespace boxpile::cli
