#include "boxpile/validation/cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>

namespace boxpile::cli {

ProgressPrinter::ProgressPrinter() : terminal_(isatty(STDERR_FILENO) == 1) {}

void ProgressPrinter::operator()(const RunProgress& p) {
  using Clock = std::chrono::steady_clock;
  if (p.index != index_) {
    index_ = p.index;
    start_ = Clock::now();
    percent_ = -1;
  }
  const int percent = static_cast<int>(100.0 * p.fraction);
  const bool done = p.fraction >= 1.0;
  if (percent == percent_ || (!terminal_ && !done)) return;
  percent_ = percent;
  std::string label = std::string(p.engine) + (p.note.empty() ? "" : " ") + std::string(p.note);
  label.resize(std::max<std::size_t>(label.size(), 24), ' ');
  char line[160];
  std::snprintf(line, sizeof line, "  [%d/%d] %s %3d%%", p.index + 1, p.total, label.c_str(), percent);
  std::cerr << (terminal_ ? "\r" : "") << line;
  if (done) {
    const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    std::snprintf(line, sizeof line, "  %.2f s\n", seconds);
    std::cerr << line;
  }
  std::cerr.flush();
}

}  // namespace boxpile::cli
