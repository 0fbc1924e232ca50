#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/interruptible.hpp"
#include "boxpile/validation/output_safety.hpp"
#include "boxpile/validation/data_directory.hpp"
#include "boxpile/validation/engine_factory.hpp"
#include "boxpile/validation/report_directory.hpp"
#include "boxpile/validation/stability.hpp"
#include "boxpile/validation/stability_report.hpp"

namespace boxpile::cli {
namespace {

std::string clock_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

// One line per cell on stderr: updated in place on a terminal (with the time left), written once
// when the cell ends otherwise (a log stays readable).
class StabilityPrinter {
 public:
  StabilityPrinter() : terminal_(isatty(STDERR_FILENO) == 1) {}

  void operator()(const StabilityProgress& p) {
    const int percent = static_cast<int>(100.0 * p.fraction);
    const bool done = p.fraction >= 1.0;
    if ((p.index == index_ && percent == percent_) || (!terminal_ && !done)) return;
    index_ = p.index;
    percent_ = percent;
    char line[200];
    std::snprintf(line, sizeof line, "  [%d/%d] %-22s %-7s %3d%%  elapsed %s, about %s left", p.index + 1, p.total,
                  std::string(p.scene).c_str(), std::string(p.engine).c_str(), percent, clock_text(p.elapsed).c_str(),
                  clock_text(p.remaining).c_str());
    std::cerr << (terminal_ ? "\r" : "") << line << (done ? "\n" : "");
    std::cerr.flush();
  }

 private:
  bool terminal_;
  int index_ = -1;
  int percent_ = -1;
};

}  // namespace

void add_stability_command(CLI::App& app, StabilityOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "stability", "Run the catalogue of hard scenes in every engine and judge each run by the scene's checks "
                   "(stability.json, stability.md, plots of failing cells). Exit 0 when our engine passes every "
                   "scene, 1 when it fails one (the reference engines' failures are reported, never fatal)");
  cmd->add_option("--engines", options.engines, "Comma-separated engines among " + engine_choices() + " (default: own,ode,bullet)")->delimiter(',');
  cmd->add_option("--scenes", options.scenes, "Scene files or directories of them (default: fixtures/hard/)");
  cmd->add_option("--report", options.report,
                  "Report directory, replaced as a whole when the report is complete (created if absent; an "
                  "existing one must be empty or hold a previous stability report)")
      ->capture_default_str();
}

int run_stability_command(const StabilityOptions& options) {
  // Every input is checked before the first run: scenes, engines, the report directory.
  std::vector<Scene> scenes;
  for (const std::string& file : catalogue_files(options.scenes.empty() ? std::vector<std::string>{data_path("fixtures/hard").string()}
                                                                        : options.scenes)) {
    scenes.push_back(load_scene(file));
  }
  StabilitySettings settings;
  if (!options.engines.empty()) settings.engines = options.engines;
  for (const std::string& name : settings.engines) check_engine_name(name);
  ReportDirectory dir(options.report, {}, "stability.json");

  StabilityPrinter printer;
  settings.progress = [&printer](const StabilityProgress& p) {
    throw_if_interrupted();
    printer(p);
  };
  std::cerr << "boxpile stability: " << scenes.size() << " scenes in " << settings.engines.size() << " engines\n";
  const std::optional<StabilityResult> ran = run_interruptible([&] { return run_stability(scenes, settings); });
  if (!ran) return kExitInterrupted;
  const StabilityResult& result = *ran;

  std::vector<std::string> notes;
  write_stability_report(result, dir.staging(), notes);
  dir.commit();
  for (const std::string& n : notes) std::cerr << "boxpile: warning: " << n << '\n';
  int own_failed = 0;
  for (const StabilityCell& c : result.cells) {
    if (c.passed) continue;
    if (c.engine == "own") ++own_failed;
    std::cout << (c.engine == "own" ? "FAIL " : "finding ") << c.scene << " in " << c.engine << ": "
              << cell_text(c) << '\n';
  }
  const std::filesystem::path md = std::filesystem::absolute(dir.target()) / "stability.md";
  std::cout << (own_failed == 0 ? "our engine passes every scene" : "our engine fails " + std::to_string(own_failed) +
                                                                         " scene(s)")
            << "; report: " << md.lexically_normal().string() << '\n';
  return own_failed == 0 ? kExitOk : kExitFailure;
}

}  // namespace boxpile::cli
