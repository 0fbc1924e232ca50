// The report of `boxpile stability`: stability.json (fixed keys for tools), stability.md (the
// matrix of scenes by engines, each cell's verdict with the figure that decided it) and SVG plots
// of the failing cells' energy and kinetic energy. docs/stability.md describes them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/validation/core/plots.hpp"
#include "boxpile/validation/stability/stability.hpp"

namespace boxpile {

// The report's data (fixed keys, and the file that marks a directory as a stability report) and
// its page for people.
inline constexpr const char* kStabilityJson = "stability.json";
inline constexpr const char* kStabilityMarkdown = "stability.md";

nlohmann::json stability_json(const StabilityResult& result);

// One plot per failing cell: total and kinetic energy against time (log scale for the kinetic).
std::vector<PlotSpec> stability_plots(const StabilityResult& result);

// stability.md; `plots` are the plot names rendered beside it, `notes` warnings met on the way.
std::string stability_markdown(const StabilityResult& result, const std::vector<std::string>& plots,
                               const std::vector<std::string>& notes);

// What a cell shows in the matrix: "pass" or "FAIL", with the deciding figure.
std::string cell_text(const StabilityCell& cell);

// For the terminal: a line per failing cell ("FAIL" for our engine, "finding" for a reference
// engine) and whether our engine passes every scene.
std::string stability_summary(const StabilityResult& result);

// Writes stability.json, stability.md and the plots into `dir`. Plots that gnuplot cannot render
// are reported in `notes` (and in stability.md).
void write_stability_report(const StabilityResult& result, const std::filesystem::path& dir,
                            std::vector<std::string>& notes);

}  // namespace boxpile
