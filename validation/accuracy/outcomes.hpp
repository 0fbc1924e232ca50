// Chaotic scenes by statistics (docs/accuracy.md, "Chaotic scenes"): where no trajectory is a
// truth (a pile falling, the bone knocking the pile), the distribution of outcomes is. Each engine
// runs the scene from N starts, each free body's start moved by a stated small distance in a
// direction drawn per start and body; the outcome measures of each run's end are summarized per
// engine (mean, spread) and every pair of engines is put to two two-sample tests
// (validation/accuracy/two_sample.hpp): they "differ beyond their own spread" or agree "within chaos".
// `boxpile compare --starts N` and `boxpile accuracy --starts N` report them.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/validation/accuracy/two_sample.hpp"
#include "boxpile/validation/core/measure.hpp"

namespace boxpile {

// The measures of a run's end, in report order. "The pile" is the free bodies not on a wire (a
// bone on its wire is left out; the scene's energy counts every body).
inline constexpr std::array<MeasureDeclaration, 5> kOutcomeMeasures = {{
    {"stacked", "bodies", "bodies of the pile resting on another body at the end (in a stack, not touching the ground)"},
    {"tallest", "m", "height of the tallest stack's highest point above the ground at the end"},
    {"com_shift", "m", "distance across gravity of the pile's centre of mass at the end from its start"},
    {"spread", "m", "root mean square distance across gravity of the pile's bodies from its centre of mass at the end"},
    {"energy_lost", "J", "total energy (kinetic and potential, every body) at the start minus at the end"},
}};

// The outcome measures of one run, by name (kOutcomeMeasures), from its start and final states.
std::map<std::string, double> outcome_measures(const Scene& scene, const std::vector<BodyState>& start,
                                               const std::vector<BodyState>& end);

// The scene from start number `index`: every free body's start moved by `distance` (m) in a
// direction across gravity drawn from (seed, index, body); a body on a wire along its wire by up
// to `distance`, either way. The same (seed, index) gives the same start on every machine.
Scene perturbed_start(const Scene& scene, double distance, std::uint64_t seed, int index);

struct OutcomeSettings {
  int starts = 0;               // runs per engine (0: none)
  double perturbation = 1e-3;   // m: the distance each free body's start moves
  std::uint64_t seed = 1;
  // Two engines' samples of a measure differ when the Kolmogorov-Smirnov p-value falls below
  // this divided by the number of measures (Bonferroni: the chance of a false "differ" over the
  // five measures of a pair is then at most `significance`).
  double significance = 0.01;
  std::function<void(std::string_view what)> progress;  // before each run
};

// One entry runs: a label (the engine's name, or another for the same engine with other
// settings), the engine and its settings.
struct OutcomeEntry {
  std::string label;
  std::string engine;
  nlohmann::json settings = nlohmann::json::object();
};

struct EngineOutcomes {
  std::string label;
  std::string engine;
  std::map<std::string, std::vector<double>> samples;  // measure -> one value per start
  std::vector<int> starts;  // the start number of each sample (a start that went non-finite has none)
  std::map<std::string, SampleSummary> summary;
  int non_finite = 0;  // starts whose run went non-finite (left out of the samples)
};

struct MeasureTest {
  std::string measure;
  KsResult ks;
  WelchResult welch;
  bool differ = false;  // ks.p_value below significance / kOutcomeMeasures.size()
};

struct OutcomePair {
  std::string a, b;  // labels
  std::vector<MeasureTest> tests;  // per measure, kOutcomeMeasures' order
  bool differ = false;             // any measure differs
  // Start by start: the starts both engines finished, and those on which the two agree, every
  // measure within the larger of the two engines' own spreads (sd over the starts: what a
  // perturbed start alone already changes).
  int starts_compared = 0;
  int starts_agreeing = 0;
  // "differ beyond their own spread" or "within chaos".
  std::string verdict() const;
};

struct OutcomeStatistics {
  OutcomeSettings settings;
  double dt = 0.0;  // s: the step every run took (the scene's)
  std::vector<EngineOutcomes> engines;
  std::vector<OutcomePair> pairs;  // every pair of entries, in order
};

// Runs every entry from settings.starts perturbed starts (start i the same for every entry) and
// tests every pair.
OutcomeStatistics run_outcomes(const Scene& scene, const std::vector<OutcomeEntry>& entries,
                               const OutcomeSettings& settings);

nlohmann::json outcomes_json(const OutcomeStatistics& s);
// A Markdown section (from "### " down): the settings, per engine mean ± spread of each measure,
// and per pair the tests and the verdict.
std::string outcomes_markdown(const OutcomeStatistics& s);

}  // namespace boxpile
