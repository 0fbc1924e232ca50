// The report of `boxpile conform`: DIR/conform.json (counts, gates, every failure), DIR/conform.md
// (failures by kind, the worst of each) and DIR/failures/NAME.json, each failing query with the
// collider's answer, loadable by `boxpile contacts`. Each failing query is also put to every
// registered detector (ours, ODE's, Bullet's: validation/detectors.hpp) and judged the same way,
// so the report tells the collider's own mistakes from cases where the references go wrong too.
#pragma once

#include <filesystem>
#include <string>

#include "boxpile/validation/judge/check_collider.hpp"

namespace boxpile {

// The report's data (fixed keys, and the file that marks a directory as a conform report) and its
// page for people.
inline constexpr const char* kConformJson = "conform.json";
inline constexpr const char* kConformMarkdown = "conform.md";

// The judge's findings for one registered detector's answer to a query (empty: right).
struct DetectorFindings {
  std::string detector;
  std::vector<Finding> findings;
};

struct ConformRun {
  std::string collider;   // the command, or a detector's name
  std::string cases;      // the folder of fixed cases ("" when none)
  CheckOptions options;   // samples, seed, regimes, tolerances, gates (options.cases unused here)
  CheckResult result;
  double seconds = 0.0;   // wall time of the run
  // Per failure of `result` (same order): every registered detector that answers the query's kind,
  // judged on it (judge_detectors()).
  std::vector<std::vector<DetectorFindings>> detectors;
};

// Fills run.detectors: each failing query through every registered detector and the judge, with
// the run's tolerances and swap setting.
void judge_detectors(ConformRun& run);

// Writes the three parts into `dir` (an existing, empty folder).
void write_conform_report(const ConformRun& run, const std::filesystem::path& dir);

// A few lines for the terminal: queries, failures by kind against their gates, the verdict.
std::string conform_summary(const ConformRun& run);

}  // namespace boxpile
