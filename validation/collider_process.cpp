#include "boxpile/validation/collider_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "boxpile/validation/json_output.hpp"

namespace boxpile {
namespace {

// After the collider's input closes (or it closes one of its ends), how long it may take to exit
// before it is killed. Also the wait for its exit status once a pipe broke: the pipe closes before
// the process can be reaped, and a machine under load may take a while in between.
constexpr std::chrono::milliseconds kExitGrace{1000};
constexpr std::chrono::milliseconds kExitPoll{10};

std::string describe_status(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "was killed by signal " + std::to_string(WTERMSIG(status));
  return "stopped";
}

std::string query_label(const ContactQuery& q) { return q.name.empty() ? std::string("a query") : "query " + q.name; }

}  // namespace

ColliderProcess::ColliderProcess(std::string command, std::chrono::milliseconds timeout)
    : command_(std::move(command)), timeout_(timeout) {
  int in[2], out[2];
  if (pipe2(in, O_CLOEXEC) != 0 || pipe2(out, O_CLOEXEC) != 0) fail(std::string("cannot make pipes: ") + std::strerror(errno));
  pid_ = fork();
  if (pid_ < 0) fail(std::string("cannot fork: ") + std::strerror(errno));
  if (pid_ == 0) {
    // The child: its own process group (a timeout kills the shell and what it started).
    setpgid(0, 0);
    dup2(in[0], STDIN_FILENO);
    dup2(out[1], STDOUT_FILENO);
    execl("/bin/sh", "sh", "-c", command_.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid_, pid_);
  close(in[0]);
  close(out[1]);
  to_child_ = in[1];
  from_child_ = out[0];
  // A collider that exits makes writes fail with EPIPE instead of killing boxpile.
  signal(SIGPIPE, SIG_IGN);
}

ColliderProcess::~ColliderProcess() { stop(); }

std::optional<int> ColliderProcess::wait_exit(std::chrono::milliseconds grace) {
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

void ColliderProcess::stop() {
  if (to_child_ >= 0) close(to_child_);
  to_child_ = -1;
  if (pid_ > 0 && !wait_exit(kExitGrace)) {
    kill(-pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  if (from_child_ >= 0) close(from_child_);
  from_child_ = -1;
}

void ColliderProcess::fail(const std::string& what) {
  if (pid_ > 0) kill(-pid_, SIGKILL);
  stop();
  throw ColliderError("collider \"" + command_ + "\" " + what);
}

void ColliderProcess::send(const std::string& line, const ContactQuery& query) {
  std::size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = write(to_child_, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::optional<int> status = wait_exit(kExitGrace);
      fail((status ? describe_status(*status) : std::string("closed its input")) + " before reading " +
           query_label(query));
    }
    done += static_cast<std::size_t>(n);
  }
}

std::string ColliderProcess::receive_line(const ContactQuery& query) {
  const auto deadline = std::chrono::steady_clock::now() + timeout_;
  while (true) {
    if (const auto end = buffer_.find('\n'); end != std::string::npos) {
      std::string line = buffer_.substr(0, end);
      buffer_.erase(0, end + 1);
      ++lines_read_;
      return line;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      fail("gave no answer to " + query_label(query) + " within " + std::to_string(timeout_.count()) + " ms");
    }
    pollfd p{from_child_, POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;  // the deadline check above reports the timeout
    char chunk[4096];
    const ssize_t n = read(from_child_, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::optional<int> status = wait_exit(kExitGrace);
      fail((status ? describe_status(*status) : std::string("closed its output")) + " before answering " +
           query_label(query) + " (output line " + std::to_string(lines_read_ + 1) + ")");
    }
    buffer_.append(chunk, static_cast<std::size_t>(n));
  }
}

Manifold ColliderProcess::ask(const ContactQuery& query) {
  send(query_json(query).dump() + "\n", query);
  const std::string line = receive_line(query);
  try {
    return parse_answer(line, "output line " + std::to_string(lines_read_));
  } catch (const InputError& e) {
    const std::string shown = line.size() > 200 ? line.substr(0, 200) + "..." : line;
    fail("answered " + query_label(query) + " with no valid answer: " + e.what() + "; the line was: " + shown);
  }
}

}  // namespace boxpile
