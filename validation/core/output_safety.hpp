// Output safety: every file or directory boxpile writes (run --out, compare --report, and every
// later writer) goes through this module, so that an output
//   - is written only where it is absent or an ordinary file/directory: device nodes, FIFOs,
//     sockets, symbolic links and the run's own input files are refused before any work starts;
//   - is found unwritable before the run (the staging file or directory is created up front);
//   - appears whole or not at all: it is written beside its target and renamed into place;
//   - leaves no staging behind on failure, on SIGINT/SIGTERM, or when a library aborts.
//
// How a writer adopts it:
//
//   // before loading heavy input or running anything:
//   OutputFile out(options.out, {options.scene});          // a single file
//   ReportDirectory dir(options.report, {options.scene});  // a directory (report_directory.hpp)
//   {
//     const InterruptScope scope;          // Ctrl-C now sets a flag instead of killing
//     for (...) { throw_if_interrupted(); step(); }   // poll in long loops
//   }                                      // (catch Interrupted: exit kExitInterrupted, 130)
//   out.commit(text);                      // or: write into dir.staging(), then dir.commit()
//
// Errors are OutputError (bad output location: the command line exits with 2). Outside an
// InterruptScope, SIGINT and SIGTERM remove every staged path and end the process as the signal
// would; SIGABRT, SIGSEGV, SIGBUS, SIGFPE and SIGILL (an engine's failed assertion, a crash) remove
// them too before the process dies.
#pragma once

#include <signal.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace boxpile {

// The output location cannot be used. Bad input: the command line exits with 2.
class OutputError : public std::runtime_error {
 public:
  // "output PATH: WHY" (`what` names the kind of output: "output", "report directory", ...).
  OutputError(const std::string& what, const std::filesystem::path& target, const std::string& why)
      : std::runtime_error(what + " " + target.string() + ": " + why), why_(why) {}
  const std::string& why() const { return why_; }

 private:
  std::string why_;
};

enum class OutputKind { File, Directory };

// Refuses (OutputError naming the path and why) an empty path, a symbolic link, a device node,
// a FIFO, a socket, a directory where a file is wanted (and a file where a directory is), a path
// that is one of `inputs`, and a directory that contains one of `inputs`. An absent target is fine.
void check_output_path(const std::filesystem::path& target, OutputKind kind,
                       const std::vector<std::filesystem::path>& inputs);

// The directory an output's staging goes into (the target's parent, "." for a bare name), created
// with its parents when missing; OutputError when that fails. The folders it created are removed
// again (while empty) when it is destroyed before keep(): a run refused after its output was
// checked (a bad --dt, a scene over a cap) leaves no folders behind.
class PreparedParent {
 public:
  explicit PreparedParent(const std::filesystem::path& target);
  ~PreparedParent();
  PreparedParent(PreparedParent&&) = default;
  PreparedParent& operator=(PreparedParent&&) = default;
  const std::filesystem::path& path() const { return parent_; }
  // The output is in place: the folders stay.
  void keep() { created_.clear(); }

 private:
  std::filesystem::path parent_;
  std::vector<std::filesystem::path> created_;  // deepest last
};
// The parent of an output, kept: for writers that commit at once.
std::filesystem::path prepare_parent(const std::filesystem::path& target);

// Installs the SIGINT and SIGTERM handlers at the start of a command, before its arguments are
// parsed: outside an InterruptScope they remove any staged path, say "boxpile: interrupted" and
// exit 130 (the documented code, whatever the signal and whenever it comes).
void install_signal_handlers();

// Registers a staging path (file or directory) for removal if the process is interrupted outside
// an InterruptScope or killed by a fatal signal. RAII: unregisters when destroyed. At most 16 at
// once (OutputError beyond that).
class StagedPath {
 public:
  explicit StagedPath(const std::filesystem::path& path);
  ~StagedPath();
  StagedPath(const StagedPath&) = delete;
  StagedPath& operator=(const StagedPath&) = delete;

 private:
  int slot_ = -1;
};

// While one is alive, SIGINT, SIGTERM and SIGABRT sent from outside are held back (delivered when
// it ends): for the few system calls during which a staged path and its registration disagree
// (between a staging's creation and its registration, between the renames of a commit). abort()
// itself unblocks SIGABRT, and faults are never held.
class HeldSignals {
 public:
  HeldSignals();
  ~HeldSignals();
  HeldSignals(const HeldSignals&) = delete;
  HeldSignals& operator=(const HeldSignals&) = delete;

 private:
  sigset_t previous_;
};

// A staging file or directory beside a target: ".NAME.tmp-XXXXXX" in `parent`, registered for
// removal. boxpile's signal handlers are installed before it exists, and signals are held back
// (HeldSignals) from its creation until it is registered, so that no signal finds it unregistered.
// OutputError ("cannot write in PARENT: ...") when it cannot be created.
struct Staging {
  std::filesystem::path path;
  std::unique_ptr<StagedPath> registration;
};
Staging create_staging(const std::filesystem::path& target, const std::filesystem::path& parent, OutputKind kind);

// A single output file: checked and staged (an empty hidden file beside the target) when
// constructed, written and renamed over the target by commit(). Destroyed without a commit, it
// removes the staging file and leaves any previous target untouched.
class OutputFile {
 public:
  OutputFile(std::filesystem::path target, const std::vector<std::filesystem::path>& inputs);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::filesystem::path& target() const { return target_; }
  // Writes `content`, flushes it to disk and renames it into place (after checking the target
  // once more: it may have changed during the run).
  void commit(std::string_view content);

 private:
  std::filesystem::path target_;
  PreparedParent parent_;
  std::filesystem::path staging_;
  std::unique_ptr<StagedPath> registration_;
  bool committed_ = false;
};

// Thrown by throw_if_interrupted() after SIGINT or SIGTERM inside an InterruptScope.
struct Interrupted {};

// While one is alive, SIGINT and SIGTERM only set a flag that long loops poll with
// throw_if_interrupted(), so that the exception unwinds through the destructors that remove
// staging. A second signal while the first is pending ends the process at once (after removing
// the staged paths). Scopes nest.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};

bool interrupted();
void throw_if_interrupted();

}  // namespace boxpile
