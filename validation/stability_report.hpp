// The report of `boxpile stability`: stability.json (fixed keys for tools), stability.md (the
// matrix of scenes by engines, each cell's verdict with the figure that decided it) and SVG plots
// of the failing cells' energy and kinetic energy. docs/stability.md describes them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/validation/plots.hpp"
#include "boxpile/validation/stability.hpp"

namespace boxpile {

nlohmann::json stability_json(const StabilityResult& result);

// One plot per failing cell: total and kinetic energy against time (log scale for the kinetic).
std::vector<PlotSpec> stability_plots(const StabilityResult& result);

// stability.md; `plots` are the plot names rendered beside it, `notes` warnings met on the way.
std::string stability_markdown(const StabilityResult& result, const std::vector<std::string>& plots,
                               const std::vector<std::string>& notes);

// What a cell shows in the matrix: "pass" or "FAIL", with the deciding figure.
std::string cell_text(const StabilityCell& cell);

// Writes stability.json, stability.md and the plots into `dir`.
void write_stability_report(const StabilityResult& result, const std::filesystem::path& dir,
                            std::vector<std::string>& notes);

}  // namespace boxpile
