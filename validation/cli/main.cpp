// boxpile: run box-pile scenes in our simulator and in other engines, and compare them.
#include "boxpile/validation/cli/command_line.hpp"

int main(int argc, char** argv) { return boxpile::cli::run_command_line(argc, argv); }
