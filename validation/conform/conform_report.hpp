// The report of `boxpile conform`: DIR/conform.json (counts by failure kind, regime and contact
// kind, the systematic errors recognised, the saved failures), DIR/conform.md (the same for
// people, the worst of each kind) and DIR/failures/NAME.json, each saved failing query with the
// collider's answer, loadable by `boxpile contacts`. Each failing query is also put to every
// registered detector (ours, ODE's, Bullet's: validation/contacts/detectors.hpp) and judged the same way,
// so the report tells the collider's own mistakes from cases where the references go wrong too;
// a reference wrong only within its known bias (known_biases.hpp) is counted apart.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "boxpile/validation/conform/judge/check_collider.hpp"
#include "boxpile/validation/conform/judge/systematic.hpp"

namespace boxpile {

// The report's data (fixed keys, and the file that marks a directory as a conform report) and its
// page for people.
inline constexpr const char* kConformJson = "conform.json";
inline constexpr const char* kConformMarkdown = "conform.md";

// The judge's findings for one registered detector's answer to a query (empty: right).
struct DetectorFindings {
  std::string detector;
  std::vector<Finding> findings;
  std::vector<std::string> biases;  // per finding: the known bias that explains it, or empty

  bool wrong() const { return !findings.empty(); }
  // Wrong, but every finding within the detector's known biases.
  bool within_bias() const;
};

// One registered detector over every failing query of a run.
struct DetectorTally {
  std::string detector;
  int judged = 0;       // failing queries of a kind it answers
  int wrong = 0;        // of those, judged wrong beyond its known biases
  int within_bias = 0;  // judged wrong, but only within its known biases
  std::map<std::string, int> biases;  // queries per known bias
};

struct ConformRun {
  std::string collider;   // the command, or a detector's name
  std::string cases;      // the folder of fixed cases ("" when none)
  std::string tolerance = "float64";  // the name of options.tolerances (--tolerance)
  CheckOptions options;   // samples, seed, regimes, tolerances, gates, keep (options.cases unused here)
  CheckResult result;
  double seconds = 0.0;   // wall time of the run
  // Per saved failure of `result` (same order): every registered detector that answers the
  // query's kind, judged on it (judge_detectors()).
  std::vector<std::vector<DetectorFindings>> detectors;
  // Every registered detector over every failure, saved or not (run_conform()).
  std::vector<DetectorTally> detector_tallies;
  std::vector<SystematicError> systematic;
};

// Every registered detector that answers the query's kind, judged on it with the run's tolerances
// and swap setting, each finding matched against the detector's known biases.
std::vector<DetectorFindings> judge_on_detectors(const ContactQuery& query, const CheckOptions& options);

// Fills run.detectors: each saved failing query through judge_on_detectors().
void judge_detectors(ConformRun& run);

// The whole run: check_collider() with every failure put to the detectors (run.detector_tallies),
// judge_detectors() on the saved ones, find_systematic(), the wall time.
void run_conform(ConformRun& run, const Collider& collider);

// Writes the three parts into `dir` (an existing, empty folder).
void write_conform_report(const ConformRun& run, const std::filesystem::path& dir);

// A few lines for the terminal: queries, failures by kind against their gates, the verdict.
std::string conform_summary(const ConformRun& run);

}  // namespace boxpile
