#include "boxpile/reference/process/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace boxpile {
namespace {

constexpr std::chrono::milliseconds kExitPoll{10};
// Standard error kept: enough for a stack trace's last lines, little enough to show.
constexpr std::size_t kStderrKept = 4096;
constexpr int kStderrLinesShown = 8;

// The watcher's answer to boxpile's death (its parent-death signal) and to SIGTERM: the whole
// process group, itself included, killed at once. Async-signal-safe.
extern "C" void kill_own_group(int) { kill(0, SIGKILL); }

void close_fd(int& fd) {
  if (fd >= 0) close(fd);
  fd = -1;
}

}  // namespace

ChildProcess::ChildProcess(std::string command, StandardError standard_error, std::function<void()> while_waiting)
    : command_(std::move(command)), while_waiting_(std::move(while_waiting)) {
  const bool keep_stderr = standard_error == StandardError::Keep;
  int in[2], out[2], err[2] = {-1, -1};
  if (pipe2(in, O_CLOEXEC) != 0 || pipe2(out, O_CLOEXEC) != 0 || (keep_stderr && pipe2(err, O_CLOEXEC) != 0)) {
    throw ChildStartError(std::string("cannot make pipes: ") + std::strerror(errno));
  }
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) throw ChildStartError(std::string("cannot fork: ") + std::strerror(errno));
  if (pid_ == 0) {
    // The watcher: the leader of the child's own process group (a timeout kills the shell and
    // everything it started, and a Ctrl-C at the terminal reaches boxpile alone), which kills
    // that group when boxpile dies, however it dies. PR_SET_PDEATHSIG alone would reach the shell
    // only: /bin/sh -c may fork the program instead of replacing itself by it.
    setpgid(0, 0);
    signal(SIGINT, SIG_IGN);
    signal(SIGTERM, kill_own_group);
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) kill_own_group(SIGTERM);  // boxpile died before the line above
    const pid_t program = fork();
    if (program == 0) {
      signal(SIGINT, SIG_DFL);
      signal(SIGTERM, SIG_DFL);
      signal(SIGPIPE, SIG_DFL);
      dup2(in[0], STDIN_FILENO);
      dup2(out[1], STDOUT_FILENO);
      if (keep_stderr) dup2(err[1], STDERR_FILENO);
      execl("/bin/sh", "sh", "-c", command_.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    for (int fd : {in[0], in[1], out[0], out[1], err[0], err[1]}) {
      if (fd >= 0) close(fd);
    }
    if (program < 0) _exit(127);
    // The program's end is the watcher's: boxpile reads the program's exit status from it.
    int status = 0;
    while (waitpid(program, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFSIGNALED(status)) {
      signal(WTERMSIG(status), SIG_DFL);
      raise(WTERMSIG(status));
    }
    _exit(WIFEXITED(status) ? WEXITSTATUS(status) : 127);
  }
  setpgid(pid_, pid_);
  close(in[0]);
  close(out[1]);
  to_child_ = in[1];
  from_child_ = out[0];
  if (keep_stderr) {
    close(err[1]);
    stderr_from_child_ = err[0];
    fcntl(stderr_from_child_, F_SETFL, fcntl(stderr_from_child_, F_GETFL) | O_NONBLOCK);
  }
  // A child that exits makes writes fail with EPIPE instead of killing boxpile.
  signal(SIGPIPE, SIG_IGN);
}

ChildProcess::~ChildProcess() { stop(); }

bool ChildProcess::write_all(std::string_view text) {
  std::size_t done = 0;
  while (done < text.size()) {
    if (to_child_ < 0) return false;
    const ssize_t n = write(to_child_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) {
      if (while_waiting_) while_waiting_();
      continue;
    }
    if (n < 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

void ChildProcess::read_stderr_available() {
  if (stderr_from_child_ < 0) return;
  char chunk[4096];
  while (true) {
    const ssize_t n = read(stderr_from_child_, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) close_fd(stderr_from_child_);  // the child closed it: nothing more will come
      return;
    }
    stderr_buf_.append(chunk, static_cast<std::size_t>(n));
    if (stderr_buf_.size() > kStderrKept) stderr_buf_.erase(0, stderr_buf_.size() - kStderrKept);
  }
}

ChildProcess::ReadResult ChildProcess::read_line(std::string& line, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (const auto end = buffer_.find('\n'); end != std::string::npos) {
      line = buffer_.substr(0, end);
      buffer_.erase(0, end + 1);
      ++lines_read_;
      return ReadResult::Line;
    }
    if (from_child_ < 0) {
      line = buffer_;
      return ReadResult::Closed;
    }
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return ReadResult::Timeout;
    if (while_waiting_) left = std::min(left, kWaitSlice);
    pollfd p[2] = {{from_child_, POLLIN, 0}, {stderr_from_child_, POLLIN, 0}};
    const int ready = poll(p, stderr_from_child_ >= 0 ? 2 : 1, static_cast<int>(left.count()));
    if (while_waiting_) while_waiting_();
    if (ready <= 0) continue;  // a signal, or the slice ended: the deadline check above decides
    if (p[1].revents != 0) read_stderr_available();
    if (p[0].revents == 0) continue;
    char chunk[4096];
    const ssize_t n = read(from_child_, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      close_fd(from_child_);
      continue;  // reported above as Closed, after any full line still buffered
    }
    buffer_.append(chunk, static_cast<std::size_t>(n));
  }
}

std::optional<int> ChildProcess::wait_exit(std::chrono::milliseconds grace) {
  if (pid_ <= 0) return std::nullopt;
  const auto deadline = std::chrono::steady_clock::now() + grace;
  int status = 0;
  while (true) {
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_ || (done < 0 && errno != EINTR)) break;
    if (std::chrono::steady_clock::now() > deadline) return std::nullopt;
    usleep(static_cast<useconds_t>(std::chrono::microseconds(kExitPoll).count()));
  }
  pid_ = -1;
  return status;
}

void ChildProcess::kill_now() {
  if (pid_ <= 0) return;
  kill(-pid_, SIGKILL);
  while (waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
}

void ChildProcess::stop() {
  close_fd(to_child_);
  if (pid_ > 0 && !wait_exit(kExitGrace)) kill_now();
  close_fd(from_child_);
  close_fd(stderr_from_child_);
}

std::string ChildProcess::stderr_tail() {
  read_stderr_available();
  std::string text = stderr_buf_;
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  if (text.empty()) return {};
  // The last kStderrLinesShown lines, each indented.
  std::size_t start = text.size();
  for (int lines = 0; lines < kStderrLinesShown && start > 0; ++lines) {
    const std::size_t nl = text.rfind('\n', start - 1);
    start = nl == std::string::npos ? 0 : nl;
  }
  if (text[start] == '\n') ++start;
  std::string out;
  for (std::size_t pos = start; pos <= text.size();) {
    const std::size_t nl = std::min(text.find('\n', pos), text.size());
    out += "  " + text.substr(pos, nl - pos) + "\n";
    pos = nl + 1;
  }
  return out;
}

std::string ChildProcess::describe_status(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "was killed by signal " + std::to_string(WTERMSIG(status));
  return "stopped";
}

std::string quote_output(std::string_view text, std::size_t limit) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size() && i < limit; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c == '\r') out += "\\r";
    else if (c == '"') out += "\\\"";
    else if (c == '\\') out += "\\\\";
    else if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  out += '"';
  if (text.size() > limit) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

}  // namespace boxpile
