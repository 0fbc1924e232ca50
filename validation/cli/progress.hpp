// Progress of long runs on stderr, shared by the commands that run scenes.
#pragma once

#include <chrono>
#include <string_view>

namespace boxpile::cli {

// Where a run is: run `index` of `total`, `fraction` of its steps done.
struct RunProgress {
  std::string_view engine;
  std::string_view note;  // e.g. "(perturbed start)"; may be empty
  int index = 0;          // 0-based
  int total = 1;
  double fraction = 0.0;
};

// One line per run: updated in place on a terminal, written once when the run ends otherwise
// (a log stays readable).
class ProgressPrinter {
 public:
  ProgressPrinter();
  void operator()(const RunProgress& p);

 private:
  bool terminal_;
  int index_ = -1;
  int percent_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace boxpile::cli
