// The report of `boxpile conform`: DIR/conform.json (counts, gates, every failure), DIR/conform.md
// (failures by kind, the worst of each) and DIR/failures/NAME.json, each failing query with the
// collider's answer, loadable by `boxpile contacts`.
#pragma once

#include <filesystem>
#include <string>

#include "boxpile/validation/judge/check_collider.hpp"

namespace boxpile {

struct ConformRun {
  std::string collider;   // the command, or a detector's name
  std::string cases;      // the folder of fixed cases ("" when none)
  CheckOptions options;   // samples, seed, regimes, tolerances, gates (options.cases unused here)
  CheckResult result;
  double seconds = 0.0;   // wall time of the run
};

// Writes the three parts into `dir` (an existing, empty folder).
void write_conform_report(const ConformRun& run, const std::filesystem::path& dir);

// A few lines for the terminal: queries, failures by kind against their gates, the verdict.
std::string conform_summary(const ConformRun& run);

}  // namespace boxpile
