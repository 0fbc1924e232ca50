// compare's findings: what a reader of a comparison most needs named, engine by engine, beside the
// pairwise verdicts. Each is one line with its figures (report.json "findings", report.md, the
// terminal); docs/compare.md, "Findings", gives each rule and why its limit is what it is.
//   check        each of the scene's checks in each engine, passed or failed, with its value;
//   odd_check    an engine fails a check that every other engine (two at least) passes;
//   energy       an engine's total energy leaves the others' median by more than a tenth of the
//                energy in motion (the first impact's loss, say), when and by how much;
//   odd_one_out  an engine differs from each of the others before any two of the others differ
//                (three engines at least): the one that left first;
//   penetration  an engine's deepest penetration is past 1% of the smallest box edge and more
//                than 3 times the others' median.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace boxpile {

struct CompareResult;

struct CompareFinding {
  std::string engine;
  std::string kind;  // "check", "odd_check", "energy", "odd_one_out", "penetration"
  std::string what;  // one sentence, with its figures
  std::optional<double> t;  // s, when it happened (none for a whole-run figure)
};

// The rules' limits (docs/compare.md gives the reasons).
struct FindingLimits {
  // An engine's energy parts from the others' when it is this fraction of the energy in motion
  // (the largest kinetic energy any engine reached) away from their median, and at least
  // `energy_floor` of the scene's largest initial |energy| (so that rounding at rest is not one).
  double energy_fraction = 0.1;
  double energy_floor = 1e-3;
  // ... and stays so, with one sign, for this long (s) or to the end of the run: an impact that
  // merely comes a few steps earlier in one engine opens a gap that closes when the others' comes.
  double energy_persistence = 0.2;
  // A penetration is past the others' when it is this many times their median and deeper than
  // `penetration_edge_fraction` of the smallest box edge.
  double penetration_factor = 3.0;
  double penetration_edge_fraction = 0.01;
};

std::vector<CompareFinding> compare_findings(const CompareResult& result, const FindingLimits& limits = {});

}  // namespace boxpile
