// The long part of a command that writes its output at the end (compare, stability, sweep, run):
// Ctrl-C and SIGTERM become Interrupted while it runs (output_safety.hpp), the staging is removed
// on the way out, and the command says what was not written and exits with kExitInterrupted.
#pragma once

#include <iostream>
#include <optional>
#include <string_view>
#include <utility>

#include "boxpile/validation/core/output_safety.hpp"

namespace boxpile::cli {

// Runs `work` inside an InterruptScope and returns what it returns; on an interrupt prints
// "boxpile: interrupted: <unwritten>" on stderr and returns nothing (the caller exits with
// kExitInterrupted). An empty `unwritten` prints "boxpile: interrupted" alone.
template <class Work>
auto run_interruptible(Work&& work, std::string_view unwritten = "no report written")
    -> std::optional<decltype(work())> {
  try {
    const InterruptScope scope;
    return std::forward<Work>(work)();
  } catch (const Interrupted&) {
    std::cerr << "\nboxpile: interrupted" << (unwritten.empty() ? "" : ": ") << unwritten << '\n';
    return std::nullopt;
  }
}

}  // namespace boxpile::cli
