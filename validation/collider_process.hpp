// An outside collider run as a program that speaks the line protocol (docs/conform.md): one
// contact query per line on its standard input, one answer per line on its standard output.
#pragma once

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <sys/types.h>

#include "boxpile/sim/io/query_loader.hpp"

namespace boxpile {

// The collider died, hung past its timeout, or answered something that is no answer; what()
// names the command, the query and the output line.
class ColliderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ColliderProcess {
 public:
  // Starts `command` through /bin/sh; each answer must arrive within `timeout`.
  ColliderProcess(std::string command, std::chrono::milliseconds timeout);
  ~ColliderProcess();
  ColliderProcess(const ColliderProcess&) = delete;
  ColliderProcess& operator=(const ColliderProcess&) = delete;

  // Sends the query, waits for its answer line and parses it.
  Manifold ask(const ContactQuery& query);

 private:
  void send(const std::string& line, const ContactQuery& query);
  std::string receive_line(const ContactQuery& query);
  [[noreturn]] void fail(const std::string& what);
  // Waits up to `grace` for the collider to exit: its wait status when it did (it is then reaped).
  std::optional<int> wait_exit(std::chrono::milliseconds grace);
  void stop();

  std::string command_;
  std::chrono::milliseconds timeout_;
  pid_t pid_ = -1;
  int to_child_ = -1;
  int from_child_ = -1;
  std::string buffer_;  // output read past the last full line
  int lines_read_ = 0;  // output lines so far (the next answer is line lines_read_ + 1)
};

}  // namespace boxpile
