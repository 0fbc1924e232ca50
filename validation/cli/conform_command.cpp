#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <variant>

#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/progress.hpp"
#include "boxpile/validation/cli/report_command.hpp"
#include "boxpile/validation/conform/collider_process.hpp"
#include "boxpile/validation/conform/conform_report.hpp"
#include "boxpile/validation/core/data_directory.hpp"
#include "boxpile/validation/core/format_number.hpp"
#include "boxpile/validation/conform/judge/check_collider.hpp"

namespace boxpile::cli {
namespace {

// `--cases none` judges random pairs only.
constexpr const char* kNoCases = "none";
// More pairs than a day of a slow collider's answers is a typo.
constexpr int kMaxSamples = 100'000'000;
// Seconds per answer: a millisecond is the least a process answers in through a pipe (below it
// every answer would time out), a day the most that is still a timeout rather than none.
constexpr double kMinTimeout = 1e-3;
constexpr double kMaxTimeout = 86'400.0;

// More failures kept whole per kind than anyone reads is a typo.
constexpr int kMaxKeep = 1'000'000;

// The named tolerances of --tolerance; any other value is a relative tolerance.
struct NamedTolerance {
  const char* name;
  JudgeTolerances (*tolerances)();
};
JudgeTolerances double_precision() { return {}; }
constexpr std::array<NamedTolerance, 2> kNamedTolerances = {{{"float64", &double_precision},
                                                             {"float32", &float32_tolerances}}};

// The tolerances --tolerance names, or an error naming the flag.
std::variant<JudgeTolerances, std::string> parse_tolerance(const std::string& text) {
  for (const NamedTolerance& t : kNamedTolerances) {
    if (text == t.name) return t.tolerances();
  }
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value) || value <= 0.0) {
    return "--tolerance: \"" + text + "\" is neither float32, float64 nor a positive finite number";
  }
  JudgeTolerances t;
  t.relative = value;
  return t;
}

std::vector<std::string> regime_names() {
  std::vector<std::string> names;
  for (const Regime r : all_regimes()) names.emplace_back(regime_name(r));
  return names;
}

std::string cases_folder(const ConformOptions& options) {
  if (options.cases == kNoCases) return "";
  if (!options.cases.empty()) return options.cases;
  return data_path("fixtures/contacts").string();
}

CheckOptions check_options(const ConformOptions& options, const std::string& cases) {
  CheckOptions check;
  check.samples = options.samples;
  check.seed = options.seed;
  if (!options.regimes.empty()) {
    check.regimes.clear();
    for (const std::string& name : options.regimes) check.regimes.push_back(*regime_from_name(name));
  }
  if (!cases.empty()) check.cases = load_cases(cases, options.max_input_bytes);
  check.swap = !options.no_swap;
  check.keep = options.keep;
  check.tolerances = std::get<JudgeTolerances>(parse_tolerance(options.tolerance));
  return check;
}

}  // namespace

void add_conform_command(CLI::App& app, ConformOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "conform", "Judge an outside box-box/box-plane collider through the line protocol (docs/conform.md): "
                 "the contact fixtures and random pose pairs, held to the conformance gates (conform.json, "
                 "conform.md, failures/)");
  cmd->add_option("--collider", options.collider,
                  "Command that reads one query per line on stdin and writes one answer per line "
                  "(run through /bin/sh)")
      ->required();
  cmd->add_option("--samples", options.samples, "Random pose pairs")->check(CLI::Range(0, kMaxSamples))->capture_default_str();
  cmd->add_option("--seed", options.seed, "Seed of the random pose pairs, a whole number >= 0")
      ->check(whole_number())
      ->capture_default_str();
  cmd->add_option("--cases", options.cases,
                  "Folder of contact queries judged first (default: the installed fixtures/contacts; \"none\": "
                  "no fixed cases)");
  cmd->add_option("--regimes", options.regimes, "Comma-separated regimes of the random pairs (default: all)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(CLI::IsMember(regime_names()));
  cmd->add_option("--timeout", options.timeout, "Seconds the collider may take per answer, in [0.001, 86400]")
      ->capture_default_str();
  cmd->add_flag("--no-swap", options.no_swap, "Do not ask each box-box query again with A and B swapped");
  cmd->add_option("--tolerance", options.tolerance,
                  "float64 (1e-9 m on depth, 1e-7 m on points, 1e-12 on |n| - 1: a double-precision collider), "
                  "float32 (each at least 64 single-precision roundoffs, 3.8e-6, of the query's scale: its "
                  "largest coordinate or half extent; a depth is a difference of sums of some tens of rounded "
                  "numbers), or a number: each tolerance at least that fraction of the query's scale")
      ->check([](const std::string& text) {
        const auto parsed = parse_tolerance(text);
        return std::holds_alternative<std::string>(parsed) ? std::get<std::string>(parsed) : std::string();
      })
      ->capture_default_str();
  options.keep = kDefaultKeep;
  cmd->add_option("--keep", options.keep, "Failures saved whole per failure kind, the worst first (the rest are counted)")
      ->check(CLI::Range(0, kMaxKeep))
      ->capture_default_str();
  cmd->add_flag("--progress", options.progress,
                "Show progress and the time left on stderr even when it is not a terminal (on a terminal it is shown anyway)");
  add_report_option(*cmd, options.report, "conform");
  add_input_limit_option(*cmd, options.max_input_bytes);
}

int run_conform_command(const ConformOptions& options) {
  // Checked here, not by a CLI11 range: NaN passes every comparison of one, and the bound of
  // PositiveNumber prints as 309 digits.
  if (!(options.timeout >= kMinTimeout && options.timeout <= kMaxTimeout)) {
    throw UsageError("--timeout: must be a number of seconds in [0.001, 86400], got " + format_number(options.timeout, "%.6g"));
  }
  ConformRun run;
  run.collider = options.collider;
  run.cases = cases_folder(options);
  run.options = check_options(options, run.cases);
  // Before the run: a report directory that cannot be written fails now.
  ReportDirectory dir(options.report, {}, kConformJson);

  run.tolerance = options.tolerance;
  EtaLine progress("conform", "queries", options.progress);
  run.options.progress = [&progress](int done, int total) { progress(done, total); };
  {
    ColliderProcess process(options.collider, std::chrono::milliseconds(std::lround(options.timeout * 1000.0)));
    run_conform(run, [&process](const ContactQuery& q) { return process.ask(q); });
  }

  write_conform_report(run, dir.staging());
  finish_report(dir, {}, conform_summary(run), kConformMarkdown);
  return run.result.within_gates() ? kExitOk : kExitFailure;
}

}  // namespace boxpile::cli
