// The progress line of `boxpile run` and `compare` (validation/cli/progress.hpp) on a clock of the
// test's own: its text, when it is drawn, and its estimate of the time left and of the whole run's
// cost against the cost the clock makes.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "boxpile/validation/cli/progress.hpp"

using namespace boxpile::cli;
using Clock = std::chrono::steady_clock;

namespace {

// A run of `seconds` whose pace is `slow` times the rest's through its first tenth (as a pile's
// first steps, full of contacts, cost more than its settled ones), reported every thousandth of
// its steps to a ProgressPrinter on a terminal; the lines it drew, split at "\r" and "\n".
struct FakeRun {
  double seconds = 0.0;
  double slow = 1.0;
  // The clock's time at fraction f of the steps.
  double at(double f) const {
    const double unit = seconds / (0.1 * slow + 0.9);
    return f <= 0.1 ? unit * slow * f : unit * (0.1 * slow + (f - 0.1));
  }
  std::vector<std::string> lines(bool terminal) const {
    std::ostringstream out;
    double now = 0.0;
    ProgressOutput output{&out, terminal, [&now] {
                            return Clock::time_point(std::chrono::duration_cast<Clock::duration>(
                                std::chrono::duration<double>(now)));
                          }};
    ProgressPrinter progress(output);
    for (int k = 0; k <= 1000; ++k) {
      now = at(k / 1000.0);
      progress({"own", "", 0, 1, k / 1000.0});
    }
    std::vector<std::string> drawn;
    std::string line;
    for (char c : out.str()) {
      if (c == '\r' || c == '\n') {
        if (!line.empty()) drawn.push_back(line);
        line.clear();
      } else {
        line += c;
      }
    }
    return drawn;
  }
};

// "  about 33 min left of 33 min": the two durations in seconds, as duration_text writes them.
bool estimate_of(const std::string& line, double& left, double& all) {
  static const std::regex estimate(R"(about ([0-9.]+) (s|min|h) left of ([0-9.]+) (s|min|h)$)");
  std::smatch m;
  if (!std::regex_search(line, m, estimate)) return false;
  const auto seconds = [](const std::string& value, const std::string& unit) {
    return std::stod(value) * (unit == "h" ? 3600.0 : unit == "min" ? 60.0 : 1.0);
  };
  left = seconds(m[1], m[2]);
  all = seconds(m[3], m[4]);
  return true;
}

}  // namespace

TEST_CASE("duration_text writes seconds, minutes and hours as a person reads an estimate", "[progress]") {
  CHECK(duration_text(40.2) == "40 s");
  CHECK(duration_text(119.4) == "119 s");
  CHECK(duration_text(12 * 60.0) == "12 min");
  CHECK(duration_text(7199.0) == "120 min");
  CHECK(duration_text(3.5 * 3600) == "3.5 h");
}

TEST_CASE("the progress line estimates the time left and the run's cost from its pace", "[progress]") {
  // A steady run of 2,000 s: the estimate is the cost itself from the first one on, which comes
  // after kFirstEstimateSeconds (at 0.05%, before the first percent) and says 33 min.
  FakeRun steady{2000.0, 1.0};
  const std::vector<std::string> lines = steady.lines(true);
  REQUIRE(lines.size() >= 100);
  const std::regex format(R"(^  \[1/1\] own {21} *[0-9]{1,3}%(  about [0-9.]+ (s|min|h) left of [0-9.]+ (s|min|h)|  [0-9]+\.[0-9]{2} s)?$)");
  for (const std::string& line : lines) {
    INFO(line);
    CHECK(std::regex_match(line, format));
  }
  CHECK(lines.front() == "  [1/1] own                        0%");
  double left = 0.0, all = 0.0;
  REQUIRE(estimate_of(lines.at(1), left, all));
  CHECK(lines.at(1) == "  [1/1] own                        0%  about 33 min left of 33 min");
  CHECK(all == Approx(2000.0).epsilon(0.02));  // 33 min: rounded to the minute
  REQUIRE(estimate_of(lines.at(lines.size() / 2), left, all));
  CHECK(left + 60.0 >= 0.3 * all);
  CHECK(lines.back() == "  [1/1] own                      100%  2000.00 s");

  // A run whose first tenth goes at a third of the pace: the first estimate, from the slow
  // steps, is at most 3 times the real cost and never below it (the estimate falls as the pace
  // does: 1,126 s at 57%), and from 80% on within 10% of it (1,041 s at 80%).
  FakeRun uneven{1000.0, 3.0};
  int estimates = 0;
  for (const std::string& line : uneven.lines(true)) {
    if (!estimate_of(line, left, all)) continue;
    const int percent = std::stoi(line.substr(line.find('%') - 3, 3));
    INFO(line);
    CHECK(all >= 1000.0 * 0.97);
    CHECK(all <= 3.0 * 1000.0);
    if (percent >= 80) CHECK(all == Approx(1000.0).epsilon(0.1));
    ++estimates;
  }
  CHECK(estimates >= 99);

  // Not on a terminal (a log): one line when the run ends, with its time.
  const std::vector<std::string> logged = steady.lines(false);
  REQUIRE(logged.size() == 1);
  CHECK(logged.front() == "  [1/1] own                      100%  2000.00 s");
}
