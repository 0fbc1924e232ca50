// Progress of long runs on stderr, shared by the commands that run scenes.
#pragma once

#include <chrono>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

namespace boxpile::cli {

// "40 s", "12 min", "3.5 h": a duration as a person reads an estimate.
std::string duration_text(double seconds);

// Where a progress line goes and the clock it reads: stderr, whether stderr is a terminal, and
// the steady clock, unless given (tests give a stream, a terminal and a clock of their own).
struct ProgressOutput {
  std::ostream* stream = nullptr;
  std::optional<bool> terminal;
  std::function<std::chrono::steady_clock::time_point()> now;
};

// One line per run (or cell) on stderr: rewritten in place on a terminal at each new whole
// percent, written once when the run ends otherwise (a log stays readable).
class StatusLine {
 public:
  explicit StatusLine(const ProgressOutput& out = {});
  // Whether run `index` at `fraction` of its work needs its line drawn now.
  bool due(int index, double fraction);
  // Draws the line; `done` (the run's end) finishes it with a newline.
  void draw(std::string_view text, bool done);
  bool terminal() const { return terminal_; }

 private:
  std::ostream* stream_;
  bool terminal_;
  int index_ = -1;
  int percent_ = -1;
};

// Where a run is: run `index` of `total`, `fraction` of its steps done.
struct RunProgress {
  std::string_view engine;
  std::string_view note;  // e.g. "(perturbed start)"; may be empty
  int index = 0;          // 0-based
  int total = 1;
  double fraction = 0.0;
};

// A run's first estimate of its cost waits for this much of its time (the pace of its first steps).
inline constexpr double kFirstEstimateSeconds = 1.0;

// A StatusLine per run: engine, note, percent and the time left estimated from the pace so far
// ("about 3.5 h left of 3.6 h"), and at the end the run's wall time.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(const ProgressOutput& out = {});
  void operator()(const RunProgress& p);

 private:
  StatusLine line_;
  std::function<std::chrono::steady_clock::time_point()> now_;
  int timed_index_ = -1;  // the run start_ belongs to
  bool estimated_ = false;  // the run's line has shown an estimate
  std::chrono::steady_clock::time_point start_;
};

// Work counted in items, with the time left estimated from the pace so far: "conform: 4512 of
// 20023 queries, 22%, 9 s left" on stderr. Drawn only on a terminal, or when asked for
// (`forced`): in place on a terminal, at most every kEtaRedraw; elsewhere a line per tenth of the
// work, so that a log stays short. The last call (done == total) ends the line with the time taken.
class EtaLine {
 public:
  EtaLine(std::string label, std::string unit, bool forced);
  void operator()(int done, int total);

 private:
  std::string label_, unit_;
  bool terminal_;
  bool shown_;
  int tenth_ = -1;
  std::chrono::steady_clock::time_point start_, drawn_;
};

}  // namespace boxpile::cli
