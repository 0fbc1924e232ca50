// What every command that writes a report directory shares (compare, stability, sweep,
// sweep-merge, conform): its --report option, and its end: the run (interruptible), the report's
// files written into the staging directory (report_directory.hpp), the directory put in place,
// the notes met while writing printed as warnings, the summary, and last the report's page.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "boxpile/validation/cli/interruptible.hpp"
#include "boxpile/validation/core/report_directory.hpp"

namespace boxpile::cli {

// --report DIR, `dir` its default; `kind` names the report an existing directory may hold (e.g.
// "stability" for `boxpile stability`, empty for compare's report).
CLI::Option* add_report_option(CLI::App& cmd, std::string& dir, std::string_view kind);

// Commits `dir`, prints each of `notes` as "boxpile: warning: NOTE" on stderr, then `summary` and
// "report: PATH" on stdout, PATH the absolute path of `page` (the report's Markdown file) in the
// committed directory.
void finish_report(ReportDirectory& dir, const std::vector<std::string>& notes, std::string_view summary,
                   std::string_view page);

// Writes `result` into the staging directory of `dir` with `write(result, staging, notes)` (e.g.
// write_report, report.hpp), then finish_report() with `summary(result)` (e.g. summary_table).
template <class Result, class Write, class Summary>
void report_to(ReportDirectory& dir, const Result& result, Write&& write, Summary&& summary, std::string_view page) {
  std::vector<std::string> notes;
  write(result, dir.staging(), notes);
  finish_report(dir, notes, summary(result), page);
}

// `run()` inside run_interruptible, then report_to() with its result. Returns the result, or
// nothing when interrupted (nothing written; the command exits with kExitInterrupted).
template <class Run, class Write, class Summary>
auto run_and_report(ReportDirectory& dir, Run&& run, Write&& write, Summary&& summary, std::string_view page)
    -> std::optional<decltype(run())> {
  auto result = run_interruptible(std::forward<Run>(run));
  if (result) report_to(dir, *result, std::forward<Write>(write), std::forward<Summary>(summary), page);
  return result;
}

}  // namespace boxpile::cli
