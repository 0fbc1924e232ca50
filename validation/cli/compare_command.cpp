#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/interrupt.hpp"
#include "boxpile/validation/compare.hpp"
#include "boxpile/validation/data_directory.hpp"
#include "boxpile/validation/engine_factory.hpp"
#include "boxpile/validation/report.hpp"
#include "boxpile/validation/report_directory.hpp"

namespace boxpile::cli {
namespace {

// One line per run on stderr: updated in place on a terminal, written once when the run ends
// otherwise (a log stays readable).
class ProgressPrinter {
 public:
  ProgressPrinter() : terminal_(isatty(STDERR_FILENO) == 1) {}

  void operator()(const CompareProgress& p) {
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
    std::string label = std::string(p.engine) + (p.baseline ? " (perturbed start)" : "");
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

 private:
  bool terminal_;
  int index_ = -1;
  int percent_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

// The main job: both of our contact methods beside the two references, on the bone scene.
CompareOptions default_compare_options() {
  CompareOptions o;
  o.scene = data_path("fixtures/scenes/bone_hits_pile.json").string();
  o.engines = {"own-impulse", "own-penalty", "ode", "bullet"};
  return o;
}

void add_compare_command(CLI::App& app, CompareOptions& options) {
  CLI::App* cmd = app.add_subcommand("compare", "Run a scene in several engines and write a report comparing them "
                                                "(report.json, report.md, SVG plots)");
  cmd->add_option("scene", options.scene, "Scene file (JSON, docs/scene-format.md)")->required();
  cmd->add_option("--engines", options.engines, "Comma-separated engines: own (the scene's solver.method), own-impulse, own-penalty, ode, "
                  "bullet (default: own,ode,bullet)")->delimiter(',');
  cmd->add_option("--dt", options.dt, "Time step in s (default: the scene's)")->check(CLI::PositiveNumber);
  cmd->add_option("--duration", options.duration, "Simulated time in s (default: the scene's)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--report", options.report,
                  "Report directory, replaced as a whole when the report is complete (created if absent; an "
                  "existing one must be empty or hold a previous report)")
      ->capture_default_str();
}

int run_compare_command(const CompareOptions& options) {
  Scene scene = load_scene(options.scene);
  if (options.dt) scene.time.dt = *options.dt;
  if (options.duration) scene.time.duration = *options.duration;

  CompareSettings settings;
  if (!options.engines.empty()) settings.engines = options.engines;
  for (const std::string& name : settings.engines) check_engine_name(name);
  // Before the run: a report directory that cannot be written fails now, not after minutes.
  ReportDirectory dir(options.report);

  ProgressPrinter progress;
  settings.progress = [&progress](const CompareProgress& p) {
    if (interrupted()) throw Interrupted{};
    progress(p);
  };
  std::cerr << "boxpile compare: " << scene.name << " (" << scene.source << "), "
            << std::lround(scene.time.duration / scene.time.dt) << " steps per run, each engine twice\n";
  CompareResult result;
  try {
    const InterruptGuard guard;
    result = run_compare(scene, settings);
  } catch (const Interrupted&) {
    std::cerr << "\nboxpile: interrupted: no report written\n";
    return kExitInterrupted;
  }

  std::vector<std::string> notes;
  write_report(result, dir.staging(), notes);
  dir.commit();

  std::cout << summary_table(result);
  for (const std::string& n : notes) std::cerr << "boxpile: warning: " << n << '\n';
  for (const EngineRun& run : result.runs) {
    if (!run.finite) std::cerr << "boxpile: warning: " << run.engine << " has non-finite states at the end\n";
  }
  const std::filesystem::path md = std::filesystem::absolute(dir.target()) / "report.md";
  std::cout << "report: " << md.lexically_normal().string() << '\n';
  return kExitOk;
}

}  // namespace boxpile::cli
