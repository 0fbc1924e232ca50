// An engine that is another program: boxpile starts it and speaks docs/engine-protocol.md over
// its standard input and output (hello, load, step, quit). The node-hosted engines (jolt,
// rapier, mujoco-wasm) and a user's --engine-cmd are this class with a command.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "boxpile/reference/process/child_process.hpp"
#include "boxpile/reference/process/protocol.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// The engine program broke the protocol: it exited, wrote something that is no answer, answered
// with wrong counts or numbers that are not finite, answered ok: false, or gave no answer within
// the timeout. what() names the engine, the request and the step, quotes the offending line (at
// most a few hundred characters, control characters escaped) and gives its exit status and the
// last lines of its standard error when it has exited. boxpile exits 2 on it.
class EngineProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ProcessEngineOptions {
  std::string name;     // as boxpile knows the engine (--engines NAME)
  std::string command;  // run through /bin/sh -c
  // Each answer must arrive within this (the load's too, which may build a large scene).
  std::chrono::milliseconds timeout{30'000};
  // The `settings` of load: only keys the engine declared, already checked.
  nlohmann::json settings = nlohmann::json::object();
  // Called while waiting for an answer (on a signal and every few hundred ms): throw from it to
  // end the wait (the interrupt check of the command line). May be empty.
  std::function<void()> while_waiting;
};

class ProcessEngine final : public Engine {
 public:
  // Starts the program, says hello (refusing another protocol version) and loads `scene`.
  ProcessEngine(const Scene& scene, ProcessEngineOptions options);
  // Says quit, closes the program's input, and kills and reaps it when it does not exit.
  ~ProcessEngine() override;

  std::string_view name() const override { return options_.name; }
  void step() override;
  double time() const override { return time_; }
  void body_states(std::vector<BodyState>& out) const override;
  void contacts(std::vector<BodyContact>& out) const override;
  // Asks the program for contacts with each step only while on (and when its hello announced them).
  void report_contacts(bool on) override { ask_.contacts = on && hello_.contacts; }
  // The sum of the engine's `engine_seconds` when it reports them, else the wall time of the
  // round trips of the steps (the protocol's cost included).
  std::optional<double> reported_seconds() const override { return seconds_; }

  // What the program said of itself.
  const protocol::Hello& hello() const { return hello_; }
  // The program's process id (-1 once it is gone), for tests that check it is gone.
  pid_t pid() const { return child_->pid(); }

  // Starts `command`, says hello and quits: what the program says of itself (its settings and
  // capabilities, before any scene). EngineProtocolError as for an engine.
  static protocol::Hello ask_hello(const std::string& name, const std::string& command,
                                   std::chrono::milliseconds timeout);

 private:
  // Starts the program and says hello (the first half of the constructor, and ask_hello).
  explicit ProcessEngine(ProcessEngineOptions options);
  // Sends one request and returns its answer line; EngineProtocolError on an exit, a timeout or
  // a closed pipe.
  std::string exchange(const std::string& request, const char* op);
  [[noreturn]] void fail(const char* op, const std::string& what, const std::string* line = nullptr);
  template <class Parse>
  auto checked(const char* op, const std::string& line, Parse parse) -> decltype(parse(line));

  ProcessEngineOptions options_;
  std::unique_ptr<ChildProcess> child_;
  protocol::Hello hello_;
  protocol::StepAsk ask_;
  protocol::StepReply reply_;
  std::vector<std::string> names_;
  long steps_ = 0;
  double time_ = 0.0;
  double seconds_ = 0.0;
};

}  // namespace boxpile
