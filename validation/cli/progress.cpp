#include "boxpile/validation/cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>

namespace boxpile::cli {

StatusLine::StatusLine() : terminal_(isatty(STDERR_FILENO) == 1) {}

bool StatusLine::due(int index, double fraction) {
  const int percent = static_cast<int>(100.0 * fraction);
  const bool done = fraction >= 1.0;
  if ((index == index_ && percent == percent_) || (!terminal_ && !done)) return false;
  index_ = index;
  percent_ = percent;
  return true;
}

void StatusLine::draw(std::string_view text, bool done) {
  std::cerr << (terminal_ ? "\r" : "") << text << (done ? "\n" : "");
  std::cerr.flush();
}

void ProgressPrinter::operator()(const RunProgress& p) {
  using Clock = std::chrono::steady_clock;
  if (p.index != timed_index_) {
    timed_index_ = p.index;
    start_ = Clock::now();
  }
  if (!line_.due(p.index, p.fraction)) return;
  const bool done = p.fraction >= 1.0;
  std::string label = std::string(p.engine) + (p.note.empty() ? "" : " ") + std::string(p.note);
  label.resize(std::max<std::size_t>(label.size(), 24), ' ');
  char text[160];
  std::snprintf(text, sizeof text, "  [%d/%d] %s %3d%%", p.index + 1, p.total, label.c_str(),
                static_cast<int>(100.0 * p.fraction));
  std::string line = text;
  if (done) {
    std::snprintf(text, sizeof text, "  %.2f s", std::chrono::duration<double>(Clock::now() - start_).count());
    line += text;
  }
  line_.draw(line, done);
}

}  // namespace boxpile::cli
