// A program run as a child process that speaks a line protocol over its standard input and
// output: the one piece behind every outside program boxpile talks to (an engine over
// docs/engine-protocol.md, a collider of `conform --collider`). It starts the command through
// /bin/sh in its own process group, writes requests, reads answer lines with a deadline, keeps
// the tail of the child's standard error when asked, and never lets the child outlive it: a
// small watcher process leads the group and kills it when boxpile dies (PR_SET_PDEATHSIG), and
// the destructor kills and reaps it.
// What a failure means is the caller's: this class reports what happened, it throws nothing
// about the protocol.
#pragma once

#include <chrono>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <sys/types.h>

namespace boxpile {

// The child could not be started (no pipes, no fork).
class ChildStartError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ChildProcess {
 public:
  enum class StandardError {
    Inherit,  // the child writes to boxpile's standard error
    Keep,     // read by boxpile; its last lines are stderr_tail()
  };

  // Starts `command` through /bin/sh -c. `while_waiting` is called whenever a wait for output is
  // interrupted by a signal (and at least every kWaitSlice), so that the caller can end the wait
  // by throwing (validation's interrupt check); empty: waits are not interruptible.
  ChildProcess(std::string command, StandardError standard_error, std::function<void()> while_waiting = {});
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Writes all of `text` to the child's standard input; false when the pipe broke (the child
  // closed it or exited).
  bool write_all(std::string_view text);

  enum class ReadResult { Line, Timeout, Closed };
  // The next line of the child's standard output (without its '\n') into `line`; Timeout when
  // none was complete within `timeout`, Closed when the output ended first (`line` then holds
  // what came after the last full line, if anything).
  ReadResult read_line(std::string& line, std::chrono::milliseconds timeout);
  // Output lines read so far.
  int lines_read() const { return lines_read_; }

  // Waits up to `grace` for the child to exit: its wait status when it did (it is then reaped).
  std::optional<int> wait_exit(std::chrono::milliseconds grace);
  // Kills the child's process group and reaps it.
  void kill_now();
  // Closes the child's input, lets it exit within kExitGrace, else kills it; reaps it. Idempotent.
  void stop();

  // The last few lines the child wrote to standard error (StandardError::Keep), each prefixed
  // by "  "; empty when it wrote none. Reads what is waiting in the pipe first.
  std::string stderr_tail();

  // The watcher's process id (the leader of the child's process group); -1 once reaped.
  pid_t pid() const { return pid_; }
  const std::string& command() const { return command_; }

  // "exited with status 3", "was killed by signal 9".
  static std::string describe_status(int status);

  // After the child's input closes (or a pipe broke), how long it may take to exit before it is
  // killed: the pipe closes before the process can be reaped, and a machine under load may take a
  // while in between.
  static constexpr std::chrono::milliseconds kExitGrace{1000};
  // The longest single wait on the pipes before `while_waiting` is called again.
  static constexpr std::chrono::milliseconds kWaitSlice{200};

 private:
  void read_stderr_available();

  std::string command_;
  std::function<void()> while_waiting_;
  pid_t pid_ = -1;
  int to_child_ = -1;
  int from_child_ = -1;
  int stderr_from_child_ = -1;
  std::string buffer_;      // output read past the last full line
  std::string stderr_buf_;  // the last kStderrKept bytes of the child's standard error
  int lines_read_ = 0;
};

// `text` shown in a message: control characters escaped (\n, \t, \xNN), cut to `limit` bytes
// with "..." when longer, in double quotes.
std::string quote_output(std::string_view text, std::size_t limit = 300);

}  // namespace boxpile
