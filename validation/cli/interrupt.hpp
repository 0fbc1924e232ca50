// Ctrl-C (or SIGTERM) during a long command: the handler only sets a flag; the command checks
// it at its next progress call and stops by throwing Interrupted, so that the staging directory
// of its report is removed on the way out and no report, not even a partial one, is left behind.
#pragma once

#include <csignal>

namespace boxpile::cli {

// Set by the handler while an InterruptGuard is alive.
bool interrupted();

struct Interrupted {};

// Installs the handler for its lifetime and restores the previous one.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

}  // namespace boxpile::cli
