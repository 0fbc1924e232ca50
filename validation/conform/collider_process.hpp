// An outside collider run as a program that speaks the line protocol (docs/conform.md): one
// contact query per line on its standard input, one answer per line on its standard output.
#pragma once

#include <chrono>
#include <stdexcept>
#include <string>

#include "boxpile/reference/process/child_process.hpp"
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
  [[noreturn]] void fail(const std::string& what);

  ChildProcess child_;
  std::chrono::milliseconds timeout_;
};

}  // namespace boxpile
