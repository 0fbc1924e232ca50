#include "boxpile/validation/sweep/sweep_runner.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>

#include "boxpile/reference/process/process_engine.hpp"
#include "boxpile/validation/core/json_output.hpp"
#include "boxpile/validation/core/output_safety.hpp"
#include "boxpile/validation/core/report_directory.hpp"

namespace boxpile {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// How often the parent looks at its workers' finished cells.
constexpr std::chrono::milliseconds kPollInterval{200};

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

fs::path cell_file(const fs::path& dir, int index) { return dir / ("cell-" + std::to_string(index) + ".json"); }

// A worker's exit status when an engine over the protocol broke it: the sweep then fails as bad
// input (exit 2), as it does without workers.
constexpr int kWorkerEngineBroke = 2;

// The body of worker `w`: its cells, each written as soon as it is done. Never returns.
[[noreturn]] void worker(const SweepGrid& grid, const std::vector<CellSpec>& cells, int w, int jobs, const fs::path& dir,
                         pid_t parent) {
  // A worker dies with its parent (SIGKILL of the parent used to leave the workers writing into
  // its abandoned staging); a parent that died before this line is seen by getppid.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(1);
  // The parent's handlers (which only set a flag) must not keep a worker alive when it is stopped.
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  int code = 0;
  try {
    for (std::size_t k = static_cast<std::size_t>(w); k < cells.size(); k += static_cast<std::size_t>(jobs)) {
      CellResult r = run_cell(grid, cells[k]);
      r.jobs = jobs;
      write_report_file(cell_file(dir, cells[k].index), cell_json(r).dump(2) + "\n");
    }
  } catch (const EngineProtocolError& e) {
    std::cerr << "boxpile: worker " << w + 1 << ": " << e.what() << '\n';
    code = kWorkerEngineBroke;
  } catch (const std::exception& e) {
    std::cerr << "boxpile: worker " << w + 1 << ": " << e.what() << '\n';
    code = 1;
  }
  std::cerr.flush();
  _exit(code);
}

int count_finished(const fs::path& dir, const std::vector<CellSpec>& cells) {
  int n = 0;
  for (const CellSpec& c : cells) n += fs::exists(cell_file(dir, c.index)) ? 1 : 0;
  return n;
}

// Stops and reaps the workers still running (after an error or an interruption).
void stop_workers(std::vector<pid_t>& pids) {
  for (pid_t p : pids) {
    if (p > 0) kill(p, SIGTERM);
  }
  for (pid_t& p : pids) {
    if (p <= 0) continue;
    int status = 0;
    while (waitpid(p, &status, 0) < 0 && errno == EINTR) {
    }
    p = 0;
  }
}

std::vector<CellResult> run_parallel(const SweepGrid& grid, const std::vector<CellSpec>& cells,
                                     const SweepRunOptions& options) {
  fs::create_directories(options.work_dir);
  const Clock::time_point start = Clock::now();
  std::cout.flush();
  std::cerr.flush();
  std::vector<pid_t> pids;
  const pid_t parent = getpid();
  for (int w = 0; w < options.jobs; ++w) {
    const pid_t pid = fork();
    if (pid < 0) {
      stop_workers(pids);
      throw std::runtime_error(std::string("cannot start a worker process: ") + std::strerror(errno));
    }
    if (pid == 0) worker(grid, cells, w, options.jobs, options.work_dir, parent);
    pids.push_back(pid);
  }
  int running = static_cast<int>(pids.size()), reported = -1;
  std::string failure;  // the first worker's failure
  bool engine_broke = false;
  try {
    while (running > 0) {
      for (std::size_t w = 0; w < pids.size(); ++w) {
        pid_t& p = pids[w];
        if (p <= 0) continue;
        int status = 0;
        if (waitpid(p, &status, WNOHANG) == p) {
          if (failure.empty() && WIFSIGNALED(status)) {
            failure = "worker " + std::to_string(w + 1) + " died of signal " + std::to_string(WTERMSIG(status)) +
                      " (" + strsignal(WTERMSIG(status)) + ")";
          } else if (failure.empty() && (!WIFEXITED(status) || WEXITSTATUS(status) != 0)) {
            failure = "worker " + std::to_string(w + 1) + " failed (its message is above)";
          }
          engine_broke = engine_broke || (WIFEXITED(status) && WEXITSTATUS(status) == kWorkerEngineBroke);
          p = 0;
          --running;
        }
      }
      // Ctrl-C reaches the workers too (the terminal signals the whole process group): the
      // command was interrupted, whatever the workers died of.
      throw_if_interrupted();
      const int done = count_finished(options.work_dir, cells);
      if (done != reported && options.progress) {
        options.progress({done, static_cast<int>(cells.size()), seconds_since(start), nullptr});
      }
      reported = done;
      if (running > 0) std::this_thread::sleep_for(kPollInterval);
    }
  } catch (...) {
    stop_workers(pids);
    throw;
  }
  throw_if_interrupted();
  if (engine_broke) throw EngineProtocolError("an engine over the protocol broke in a worker process (its message is above)");
  if (!failure.empty()) throw std::runtime_error(failure);
  std::vector<CellResult> results;
  for (const CellSpec& c : cells) {
    std::ifstream in(cell_file(options.work_dir, c.index));
    results.push_back(cell_from_json(nlohmann::json::parse(in)));
  }
  fs::remove_all(options.work_dir);
  return results;
}

}  // namespace

std::vector<CellResult> run_sweep_cells(const SweepGrid& grid, const std::vector<CellSpec>& cells,
                                        const SweepRunOptions& options) {
  if (options.jobs > 1 && cells.size() > 1) return run_parallel(grid, cells, options);
  const Clock::time_point start = Clock::now();
  std::vector<CellResult> results;
  for (const CellSpec& c : cells) {
    results.push_back(run_cell(grid, c));
    if (options.progress) {
      options.progress({static_cast<int>(results.size()), static_cast<int>(cells.size()), seconds_since(start), &results.back()});
    }
  }
  return results;
}

}  // namespace boxpile
