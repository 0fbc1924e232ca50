#include "boxpile/validation/core/output_safety.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>

namespace boxpile {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void refuse(const fs::path& target, const std::string& why) {
  throw OutputError("output", target, why);
}

// --- the staging registry, read by signal handlers -------------------------------------------
// Fixed storage and atomics only: a handler must not allocate or take locks.

constexpr int kMaxStaged = 16;
std::array<std::array<char, PATH_MAX>, kMaxStaged> g_staged{};
std::array<std::atomic<bool>, kMaxStaged> g_staged_used{};

std::atomic<int> g_scope_depth{0};
volatile std::sig_atomic_t g_interrupted = 0;

// How deep remove_tree() goes: a staging directory holds a report's files and a folder or two.
constexpr int kMaxRemoveDepth = 16;
// remove_tree()'s directory buffer, per level (on the stack: the handler must not allocate).
constexpr std::size_t kDirentBuffer = 1024;

// Removes a file, or a directory and everything in it, with system calls only (openat,
// getdents64, unlinkat, close). Used on the way out of a dying process from a signal handler,
// which may have interrupted malloc: opendir() and readdir() allocate, and would deadlock there.
void remove_tree(int parent_fd, const char* name, int depth = 0) {
  if (unlinkat(parent_fd, name, 0) == 0 || errno != EISDIR || depth > kMaxRemoveDepth) return;
  const int fd = openat(parent_fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  alignas(dirent64) char buffer[kDirentBuffer];
  for (ssize_t n; (n = getdents64(fd, buffer, sizeof buffer)) > 0;) {
    for (ssize_t at = 0; at < n;) {
      const auto* e = reinterpret_cast<const dirent64*>(buffer + at);
      at += e->d_reclen;
      if (std::strcmp(e->d_name, ".") == 0 || std::strcmp(e->d_name, "..") == 0) continue;
      remove_tree(fd, e->d_name, depth + 1);
    }
  }
  close(fd);
  unlinkat(parent_fd, name, AT_REMOVEDIR);
}

void remove_all_staged() {
  for (int i = 0; i < kMaxStaged; ++i) {
    if (g_staged_used[static_cast<std::size_t>(i)].exchange(false)) {
      remove_tree(AT_FDCWD, g_staged[static_cast<std::size_t>(i)].data());
    }
  }
}

// The handlers that were in place before ours (a sanitizer's or a test framework's crash report),
// restored for a fatal signal once the staging is gone.
constexpr int kFatalSignals[] = {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL};
struct sigaction g_previous[sizeof kFatalSignals / sizeof kFatalSignals[0]];

// The exit code of an interrupted command (docs/reliability.md): 128 + SIGINT, for SIGTERM too.
constexpr int kInterruptedExitCode = 130;

extern "C" void on_fatal_signal(int sig) {
  remove_all_staged();
  for (std::size_t i = 0; i < std::size(kFatalSignals); ++i) {
    if (kFatalSignals[i] == sig) sigaction(sig, &g_previous[i], nullptr);
  }
  // Returning re-runs the faulting instruction (or, for a raised signal, the handler restored
  // above runs when it is raised again), now under the previous handler.
  if (sig == SIGABRT) std::raise(sig);
}

extern "C" void on_stop_signal(int) {
  if (g_scope_depth.load() > 0 && !g_interrupted) {
    g_interrupted = 1;
    return;
  }
  // Outside a run (parsing, loading, writing a report) or at a second signal: the staging goes
  // and the process exits with the documented code (write and _exit are async-signal-safe).
  remove_all_staged();
  constexpr char kMessage[] = "\nboxpile: interrupted: nothing written\n";
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
  std::_Exit(kInterruptedExitCode);
}

void install_stop_handlers() {
  for (const int sig : {SIGINT, SIGTERM}) std::signal(sig, on_stop_signal);
}

void install_handlers_once() {
  static const bool installed = [] {
    for (std::size_t i = 0; i < std::size(kFatalSignals); ++i) {
      struct sigaction action {};
      action.sa_handler = on_fatal_signal;
      sigemptyset(&action.sa_mask);
      sigaction(kFatalSignals[i], &action, &g_previous[i]);
    }
    install_stop_handlers();
    return true;
  }();
  static_cast<void>(installed);
}

std::string kind_refusal(const fs::file_status& st, OutputKind kind) {
  switch (st.type()) {
    case fs::file_type::symlink:
      return "is a symbolic link: refused, so that a link cannot send the output elsewhere";
    case fs::file_type::character:
    case fs::file_type::block:
      return "is a device node: refused, boxpile writes only ordinary files";
    case fs::file_type::fifo:
      return "is a FIFO (named pipe): refused, boxpile writes only ordinary files";
    case fs::file_type::socket:
      return "is a socket: refused, boxpile writes only ordinary files";
    case fs::file_type::directory:
      return kind == OutputKind::File ? "is a directory: give a file name" : "";
    case fs::file_type::regular:
      return kind == OutputKind::Directory ? "exists and is not a directory" : "";
    default:
      return "is not an ordinary file or directory";
  }
}

// The staging file's permissions: those of any new file (0666 less the umask), not mkstemp's 0600.
void give_default_permissions(const fs::path& path, mode_t base) {
  const mode_t mask = umask(0);
  umask(mask);
  chmod(path.c_str(), base & ~mask);
}

// A staging path left by a run that was killed outright (SIGKILL, a power cut: no handler ran).
// Another run may be writing the same target right now, so it is named, not deleted.
void warn_of_abandoned_staging(const fs::path& parent, const std::string& prefix) {
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() == prefix.size() + 6 && name.starts_with(prefix)) {
      std::cerr << "boxpile: warning: " << it->path().string()
                << " is the staging of an earlier run that was killed before it could clean up (or of a run "
                   "writing the same output now): remove it once no such run is left\n";
    }
  }
}

}  // namespace

void install_signal_handlers() { install_handlers_once(); }

void check_output_path(const fs::path& target, OutputKind kind, const std::vector<fs::path>& inputs) {
  if (target.empty()) refuse(target, "no path given");
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(target, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) refuse(target, ec.message());
  if (!fs::exists(st)) return;
  if (const std::string why = kind_refusal(st, kind); !why.empty()) refuse(target, why);
  for (const fs::path& input : inputs) {
    if (fs::equivalent(target, input, ec)) {
      refuse(target, "is the input file " + input.string() + ": refused, it would be overwritten");
    }
    if (kind == OutputKind::Directory) {
      const fs::path dir = fs::weakly_canonical(target, ec);
      const fs::path file = fs::weakly_canonical(input, ec);
      const auto [end, ignored] = std::mismatch(dir.begin(), dir.end(), file.begin(), file.end());
      if (end == dir.end()) refuse(target, "holds the input file " + input.string() + ": it would be deleted");
    }
  }
}

PreparedParent::PreparedParent(const fs::path& target)
    : parent_(target.has_parent_path() ? target.parent_path() : fs::path(".")) {
  std::error_code ec;
  // The folders missing, outermost first, so that each is created (and later removed) in turn.
  std::vector<fs::path> missing;
  for (fs::path p = parent_; !p.empty() && !fs::exists(fs::symlink_status(p, ec)); p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (!fs::create_directory(*it, ec) && ec) refuse(target, "cannot create " + it->string() + ": " + ec.message());
    created_.push_back(*it);
  }
  fs::create_directories(parent_, ec);  // whatever the loop could not see (a race): fails alike
  if (ec) refuse(target, "cannot create " + parent_.string() + ": " + ec.message());
}

PreparedParent::~PreparedParent() {
  // Deepest first; a folder that is no longer empty (someone wrote into it) stays, and so do its
  // parents.
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) {
    if (::rmdir(it->c_str()) != 0) break;
  }
}

fs::path prepare_parent(const fs::path& target) {
  PreparedParent p(target);
  p.keep();
  return p.path();
}

StagedPath::StagedPath(const fs::path& path) {
  install_handlers_once();
  std::error_code ec;
  const std::string absolute = fs::absolute(path, ec).string();
  if (ec || absolute.size() >= PATH_MAX) refuse(path, "path too long");
  for (int i = 0; i < kMaxStaged; ++i) {
    auto& used = g_staged_used[static_cast<std::size_t>(i)];
    if (used.load()) continue;
    std::memcpy(g_staged[static_cast<std::size_t>(i)].data(), absolute.c_str(), absolute.size() + 1);
    used.store(true);
    slot_ = i;
    return;
  }
  refuse(path, "too many outputs staged at once");
}

StagedPath::~StagedPath() {
  if (slot_ >= 0) g_staged_used[static_cast<std::size_t>(slot_)].store(false);
}

HeldSignals::HeldSignals() {
  sigset_t held;
  sigemptyset(&held);
  for (const int sig : {SIGINT, SIGTERM, SIGABRT}) sigaddset(&held, sig);
  pthread_sigmask(SIG_BLOCK, &held, &previous_);
}

HeldSignals::~HeldSignals() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }

Staging create_staging(const fs::path& target, const fs::path& parent, OutputKind kind) {
  install_handlers_once();
  // A hidden sibling, so that the final rename stays on one file system.
  // (Built by appending: GCC 12 warns falsely about "." + string, -Wrestrict.)
  std::string name(1, '.');
  name += target.filename().string();
  warn_of_abandoned_staging(parent, name + ".tmp-");
  name += ".tmp-XXXXXX";
  std::string pattern = (parent / name).string();
  // A signal arriving between the staging's creation and its registration would leave it behind.
  const HeldSignals held;
  bool created = false;
  if (kind == OutputKind::File) {
    const int fd = mkstemp(pattern.data());
    if (fd >= 0) close(fd);
    created = fd >= 0;
  } else {
    created = mkdtemp(pattern.data()) != nullptr;
  }
  const int create_error = errno;
  Staging staging;
  if (created) {
    staging.path = pattern;
    try {
      staging.registration = std::make_unique<StagedPath>(staging.path);
    } catch (...) {
      std::error_code ignored;
      fs::remove(staging.path, ignored);
      throw;
    }
  }
  if (!created) refuse(target, "cannot write in " + parent.string() + ": " + std::strerror(create_error));
  return staging;
}

OutputFile::OutputFile(fs::path target, const std::vector<fs::path>& inputs)
    : target_(std::move(target)), parent_((check_output_path(target_, OutputKind::File, inputs), target_)) {
  Staging staging = create_staging(target_, parent_.path(), OutputKind::File);
  staging_ = std::move(staging.path);
  registration_ = std::move(staging.registration);
}

OutputFile::~OutputFile() {
  if (committed_ || staging_.empty()) return;
  std::error_code ignored;
  fs::remove(staging_, ignored);
}

void OutputFile::commit(std::string_view content) {
  const int fd = open(staging_.c_str(), O_WRONLY | O_TRUNC | O_NOFOLLOW);
  if (fd < 0) refuse(target_, std::string("cannot write: ") + std::strerror(errno));
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      close(fd);
      refuse(target_, std::string("write failed: ") + std::strerror(err));
    }
    written += static_cast<std::size_t>(n);
  }
  if (fsync(fd) != 0 || close(fd) != 0) refuse(target_, std::string("write failed: ") + std::strerror(errno));
  give_default_permissions(staging_, 0666);
  check_output_path(target_, OutputKind::File, {});  // it may have changed during the run
  std::error_code ec;
  fs::rename(staging_, target_, ec);
  if (ec) refuse(target_, "cannot rename the finished file into place: " + ec.message());
  committed_ = true;
  parent_.keep();
}

InterruptScope::InterruptScope() {
  install_handlers_once();
  // The outermost scope installs the SIGINT/SIGTERM handlers again: something else (a test
  // framework) may have replaced them since.
  if (g_scope_depth.fetch_add(1) == 0) {
    g_interrupted = 0;
    install_stop_handlers();
  }
}

InterruptScope::~InterruptScope() {
  // Past the outermost scope a pending interrupt is spent: it was thrown, or nothing polled it.
  if (g_scope_depth.fetch_sub(1) == 1) g_interrupted = 0;
}

bool interrupted() { return g_interrupted != 0; }

void throw_if_interrupted() {
  if (g_interrupted) throw Interrupted{};
}

}  // namespace boxpile
