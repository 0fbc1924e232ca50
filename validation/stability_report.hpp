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

// stability.md's "The checks and why": a row per check of every scene, its limit and the reason
// the scene gives for it.
std::string checks_markdown(const StabilityResult& result);

// stability.json back into a result (`boxpile stability-merge`): each scene loaded again by
// `load` from the file the report names; the cells' recorded series (the plots' data) are not in
// the file and stay empty. Throws nlohmann::json's errors on a file of another shape.
StabilityResult stability_from_json(const nlohmann::json& doc, const std::function<Scene(const std::string&)>& load);

// The shards of one run (`--shard I/N`) as one result, cells in the run's order. Throws
// std::invalid_argument naming the part (`names`, one per part) that is not a shard of the same
// run as the first, a shard given twice, or a run left incomplete.
StabilityResult merge_stability(const std::vector<StabilityResult>& parts, const std::vector<std::string>& names);

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
