// What a command is doing, for the one message that cannot be written where the failure happens:
// an allocation that fails (std::bad_alloc names nothing). Each phase of a command opens an
// Activity ("loading stack.json", "running ode on stack.json"); main's handler prints the
// innermost one open, and run_loop adds the step (OutOfMemory, validation/core/run_loop.hpp).
#pragma once

#include <string>
#include <utility>

namespace boxpile::cli {

class Activity {
 public:
  explicit Activity(std::string what) : previous_(std::exchange(current(), std::move(what))) {}
  ~Activity() { current() = std::move(previous_); }
  Activity(const Activity&) = delete;
  Activity& operator=(const Activity&) = delete;

  // The innermost activity open; empty outside every one.
  static std::string& current() {
    static std::string text;
    return text;
  }

 private:
  std::string previous_;
};

}  // namespace boxpile::cli
