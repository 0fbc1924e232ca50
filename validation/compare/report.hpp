// The compare report: report.json (fixed keys that other tools read), report.md (a short report
// for people), the plots, and the summary printed on the terminal. docs/compare.md describes them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/validation/compare/compare.hpp"
#include "boxpile/validation/core/plots.hpp"

namespace boxpile {

// The report's data (fixed keys, and the file that marks a directory as a compare report) and its
// page for people.
inline constexpr const char* kReportJson = "report.json";
inline constexpr const char* kReportMarkdown = "report.md";

nlohmann::json report_json(const CompareResult& result);

// The plots of a report: energy (impacts marked), deepest penetration, tallest stack, and the
// position difference between engines with each engine's perturbed baseline.
std::vector<PlotSpec> report_plots(const CompareResult& result);

// report.md; `plots` are the plot names that were rendered (NAME.svg beside report.md), and
// `notes` are lines for a "Notes" section (warnings met while writing).
std::string report_markdown(const CompareResult& result, const std::vector<std::string>& plots,
                            const std::vector<std::string>& notes);

// A table of the main figures per engine and one line per pair of engines, for the terminal.
std::string summary_table(const CompareResult& result);

// The replay page of a report and its data (the page's data, from which `boxpile view DIR` makes
// the page again).
inline constexpr const char* kReplayPage = "replay.html";
inline constexpr const char* kReplayData = "replay.json";

// Writes report.json, report.md, the plots, replay.json and replay.html into `dir`. Plots that
// gnuplot cannot render are reported in `notes` (and in report.md); their data and scripts are
// still written. Without three.js, replay.html is left out and a note says so.
void write_report(const CompareResult& result, const std::filesystem::path& dir,
                  std::vector<std::string>& notes);

}  // namespace boxpile
