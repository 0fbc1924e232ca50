#include "boxpile/validation/cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>

namespace boxpile::cli {

StatusLine::StatusLine(const ProgressOutput& out)
    : stream_(out.stream ? out.stream : &std::cerr), terminal_(out.terminal.value_or(isatty(STDERR_FILENO) == 1)) {}

bool StatusLine::due(int index, double fraction) {
  const int percent = static_cast<int>(100.0 * fraction);
  const bool done = fraction >= 1.0;
  if ((index == index_ && percent == percent_) || (!terminal_ && !done)) return false;
  index_ = index;
  percent_ = percent;
  return true;
}

void StatusLine::draw(std::string_view text, bool done) {
  *stream_ << (terminal_ ? "\r" : "") << text << (done ? "\n" : "");
  stream_->flush();
}

std::string duration_text(double seconds) {
  char text[32];
  if (seconds < 120) {
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  } else if (seconds < 7200) {
    std::snprintf(text, sizeof text, "%.0f min", seconds / 60);
  } else {
    std::snprintf(text, sizeof text, "%.1f h", seconds / 3600);
  }
  return text;
}


ProgressPrinter::ProgressPrinter(const ProgressOutput& out)
    : line_(out), now_(out.now ? out.now : [] { return std::chrono::steady_clock::now(); }) {}

void ProgressPrinter::operator()(const RunProgress& p) {
  if (p.index != timed_index_) {
    timed_index_ = p.index;
    start_ = now_();
    estimated_ = false;
  }
  const double elapsed = std::chrono::duration<double>(now_() - start_).count();
  const bool can_estimate = p.fraction > 0.0 && elapsed >= kFirstEstimateSeconds;
  // On a terminal the first estimate is drawn as soon as there is one, before the next percent.
  const bool first_estimate = line_.terminal() && can_estimate && !estimated_;
  if (!line_.due(p.index, p.fraction) && !first_estimate) return;
  const bool done = p.fraction >= 1.0;
  std::string label = std::string(p.engine) + (p.note.empty() ? "" : " ") + std::string(p.note);
  label.resize(std::max<std::size_t>(label.size(), 24), ' ');
  char text[160];
  std::snprintf(text, sizeof text, "  [%d/%d] %s %3d%%", p.index + 1, p.total, label.c_str(),
                static_cast<int>(100.0 * p.fraction));
  std::string line = text;
  if (done) {
    std::snprintf(text, sizeof text, "  %.2f s", elapsed);
    line += text;
  } else if (can_estimate) {
    // The cost of the run estimated from its pace so far.
    const double all = elapsed / p.fraction;
    line += "  about " + duration_text(all - elapsed) + " left of " + duration_text(all);
    estimated_ = true;
  }
  line_.draw(line, done);
}

// A terminal line redrawn more often than this only flickers.
constexpr std::chrono::milliseconds kEtaRedraw{200};

EtaLine::EtaLine(std::string label, std::string unit, bool forced)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      terminal_(isatty(STDERR_FILENO) == 1),
      shown_(terminal_ || forced),
      start_(std::chrono::steady_clock::now()),
      drawn_(start_) {}

void EtaLine::operator()(int done, int total) {
  if (!shown_ || total <= 0) return;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point now = Clock::now();
  const bool finished = done >= total;
  const int tenth = 10 * done / total;
  if (!finished) {
    if (terminal_ && now - drawn_ < kEtaRedraw) return;
    if (!terminal_ && tenth == tenth_) return;
  }
  drawn_ = now;
  tenth_ = tenth;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  char text[200];
  if (finished) {
    std::snprintf(text, sizeof text, "%s: %d %s in %.1f s", label_.c_str(), done, unit_.c_str(), elapsed);
  } else {
    const double left = done > 0 ? elapsed * (total - done) / done : 0.0;
    std::snprintf(text, sizeof text, "%s: %d of %d %s, %d%%, %.0f s left", label_.c_str(), done, total,
                  unit_.c_str(), 100 * done / total, left);
  }
  // On a terminal: back to the line's start and erase it (ANSI "erase in line"), then the text.
  std::cerr << (terminal_ ? "\r\033[K" : "") << text << (finished || !terminal_ ? "\n" : "");
  std::cerr.flush();
}

}  // namespace boxpile::cli
