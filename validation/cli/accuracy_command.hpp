// `boxpile accuracy SCENE... [--engines LIST] [--dt LIST] [--iteration-scale LIST]
// [--truth analytic|converged|self] [--repetitions N] [--set ENGINE.KEY=VALUE] --report DIR`:
// each engine's error against a truth at a series of time steps, its cost and its order of
// convergence (accuracy.json, accuracy.md, SVG plots; docs/accuracy.md).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "boxpile/validation/cli/run_limits.hpp"
#include "boxpile/validation/cli/starts_options.hpp"

namespace boxpile::cli {

struct AccuracyOptions {
  std::vector<std::string> scenes;   // files or directories of them
  std::vector<std::string> engines;  // empty: the registry's compare list
  std::vector<double> steps;         // s; empty: 1/60, 1/120, 1/240, 1/480
  std::vector<int> iteration_scales;  // empty: 1
  std::string truth;                 // empty: analytic where the scene states one, else converged
  int repetitions = 3;
  std::vector<std::string> set;
  std::string report = "boxpile-accuracy";
  RunLimits limits;
  StartsOptions starts;  // outcome statistics over perturbed starts, at each scene's own step
};
void add_accuracy_command(CLI::App& app, AccuracyOptions& options);
int run_accuracy_command(const AccuracyOptions& options);

}  // namespace boxpile::cli
