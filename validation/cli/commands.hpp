// The boxpile subcommands. Each registers its options on the CLI11 app and returns the exit code.
#pragma once

#include <CLI/CLI.hpp>

namespace boxpile::cli {

// Exit codes: 0 success, 2 bad input (a scene, a query, a flag), 1 anything else.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

// `boxpile contacts QUERY.json [--reduce]`: the contact set of one query on stdout.
struct ContactsOptions {
  std::string query;
  bool reduce = false;
};
void add_contacts_command(CLI::App& app, ContactsOptions& options);
int run_contacts(const ContactsOptions& options);

}  // namespace boxpile::cli
