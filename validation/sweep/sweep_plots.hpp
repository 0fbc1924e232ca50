// The plots of a sweep report: for each scene and error measure the cells and the fronts (error
// against µs per simulated second, both logarithmic); our impulse method's residual after each
// pass; ODE's and Bullet's error against their iterations.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace boxpile {

struct SweepReport;

// Writes and renders the plots into `dir`; returns their names (file stems). A plot gnuplot cannot
// render keeps its data and script and adds a note to `warnings`.
std::vector<std::string> write_sweep_plots(const SweepReport& report, const std::filesystem::path& dir,
                                           std::vector<std::string>& warnings);

}  // namespace boxpile
