// Ctrl-C (or SIGTERM) during a long command: the handler only sets a flag; the command's progress
// callback throws Interrupted when it sees it, so that staging directories are removed on the way
// out and no report, not even a partial one, is left behind.
#pragma once

namespace boxpile::cli {

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

// Whether a signal has arrived since the guard was installed.
bool interrupted();

}  // namespace boxpile::cli
