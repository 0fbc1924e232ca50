// --starts N and --start-perturbation M of `compare` and `accuracy`: outcome statistics over N
// perturbed starts per engine (validation/accuracy/outcomes.hpp, docs/accuracy.md "Chaotic scenes").
#pragma once

#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

#include "boxpile/validation/cli/run_limits.hpp"
#include "boxpile/validation/accuracy/outcomes.hpp"

namespace boxpile::cli {

// At most this many starts per engine: the exact two-sample test counts n m lattice cells.
inline constexpr int kMostStarts = 500;

struct StartsOptions {
  int starts = 0;
  double perturbation = OutcomeSettings{}.perturbation;  // m
};

inline void add_starts_options(CLI::App& cmd, StartsOptions& options) {
  cmd.add_option("--starts", options.starts,
                 "Also run each engine from N starts, every free body moved by --start-perturbation, and report the "
                 "outcomes' mean and spread per engine and a two-sample test per pair of engines (0: none; at most " +
                     std::to_string(kMostStarts) + ")")
      ->capture_default_str();
  cmd.add_option("--start-perturbation", options.perturbation,
                 "Distance each free body's start moves for --starts, m, in (0, 1] (a body on a wire: along it, up to "
                 "this either way)")
      ->capture_default_str();
}

// UsageError naming the flag for a value out of range.
inline OutcomeSettings outcome_settings(const StartsOptions& options) {
  if (options.starts < 0 || options.starts > kMostStarts) {
    throw UsageError("--starts: must be in [0, " + std::to_string(kMostStarts) + "], got " + std::to_string(options.starts));
  }
  if (!(options.perturbation > 0.0) || !(options.perturbation <= 1.0)) {
    throw UsageError("--start-perturbation: must be in (0, 1] m, got " + std::to_string(options.perturbation));
  }
  OutcomeSettings s;
  s.starts = options.starts;
  s.perturbation = options.perturbation;
  return s;
}

}  // namespace boxpile::cli
