#include "boxpile/reference/process/process_engine.hpp"

#include <cstdio>

#include "boxpile/sim/io/json_input.hpp"

namespace boxpile {
namespace {

using Clock = std::chrono::steady_clock;

// How long the program may take to answer quit when boxpile is done with it: a well-behaved
// engine answers at once; one that does not is killed, which loses nothing.
constexpr std::chrono::milliseconds kQuitWait{500};

std::string seconds_text(std::chrono::milliseconds t) {
  const double s = static_cast<double>(t.count()) / 1000.0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

}  // namespace

ProcessEngine::ProcessEngine(ProcessEngineOptions options) : options_(std::move(options)) {
  child_ = std::make_unique<ChildProcess>(options_.command, ChildProcess::StandardError::Keep, options_.while_waiting);
  const std::string hello_line = exchange(protocol::hello_request(), "hello");
  hello_ = checked("hello", hello_line, [](const std::string& l) { return protocol::parse_hello(l); });
}

ProcessEngine::ProcessEngine(const Scene& scene, ProcessEngineOptions options) : ProcessEngine(std::move(options)) {
  const std::string load_line = exchange(protocol::load_request(scene, options_.settings), "load");
  checked("load", load_line, [](const std::string& l) {
    protocol::parse_ok(l);
    return 0;
  });
  // The start, as every engine reports it: the scene's frames and velocities.
  ask_ = {scene.bodies.size(), true, hello_.contacts};
  reply_.bodies.resize(scene.bodies.size());
  const std::vector<RigidBody> bodies = make_bodies(scene);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    names_.push_back(bodies[i].name);
    const Pose frame = bodies[i].frame_pose();
    reply_.bodies[i] = {bodies[i].name, frame.position, frame.orientation, bodies[i].v, bodies[i].omega};
  }
}

ProcessEngine::~ProcessEngine() {
  if (child_->pid() > 0 && child_->write_all(protocol::quit_request() + "\n")) {
    std::string line;
    try {
      child_->read_line(line, kQuitWait);
    } catch (...) {
      // An interrupt while quitting: the program is stopped below all the same.
    }
  }
  child_->stop();
}

void ProcessEngine::fail(const char* op, const std::string& what, const std::string* line) {
  std::string message = "engine " + json_input::in_quotes(options_.name) + " (" + json_input::shortened(options_.command) + "): ";
  message += std::string(op) == "step" ? "step " + std::to_string(steps_ + 1) : std::string(op);
  message += ": " + what;
  if (line) message += "; the line was: " + quote_output(*line);
  // Its exit status, when it has gone (or once killed), and its last words.
  child_->kill_now();
  const std::string tail = child_->stderr_tail();
  if (!tail.empty()) message += "\n  its standard error ended with:\n" + tail;
  while (!message.empty() && message.back() == '\n') message.pop_back();
  throw EngineProtocolError(message);
}

template <class Parse>
auto ProcessEngine::checked(const char* op, const std::string& line, Parse parse) -> decltype(parse(line)) {
  try {
    return parse(line);
  } catch (const protocol::ReplyError& e) {
    fail(op, std::string("the answer ") + e.what(), &line);
  }
}

std::string ProcessEngine::exchange(const std::string& request, const char* op) {
  const auto gone = [&](const std::string& what) {
    const std::optional<int> status = child_->wait_exit(ChildProcess::kExitGrace);
    fail(op, (status ? "the program " + ChildProcess::describe_status(*status) : "the program " + what));
  };
  if (!child_->write_all(request + "\n")) gone("closed its standard input");
  std::string line;
  switch (child_->read_line(line, options_.timeout)) {
    case ChildProcess::ReadResult::Line: return line;
    case ChildProcess::ReadResult::Timeout:
      fail(op, "no answer within " + seconds_text(options_.timeout) + " s (--engine-timeout)");
    case ChildProcess::ReadResult::Closed:
      if (!line.empty()) {
        fail(op, "the program ended its output in the middle of a line", &line);
      }
      gone("closed its standard output");
  }
  return line;  // not reached
}

void ProcessEngine::step() {
  static const std::string request_with = protocol::step_request(1, true, true);
  static const std::string request_without = protocol::step_request(1, true, false);
  const Clock::time_point start = Clock::now();
  const std::string line = exchange(ask_.contacts ? request_with : request_without, "step");
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  checked("step", line, [this](const std::string& l) {
    protocol::parse_step(l, ask_, reply_);
    return 0;
  });
  if (hello_.timing && !reply_.engine_seconds) {
    fail("step", "the answer has no \"engine_seconds\", which the engine's hello announced (timing: true)", &line);
  }
  ++steps_;
  time_ = reply_.time;
  seconds_ += hello_.timing ? *reply_.engine_seconds : wall;
  for (std::size_t i = 0; i < names_.size(); ++i) reply_.bodies[i].name = names_[i];
}

void ProcessEngine::body_states(std::vector<BodyState>& out) const {
  out.resize(reply_.bodies.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = reply_.bodies[i];
}

void ProcessEngine::contacts(std::vector<BodyContact>& out) const { out = reply_.contacts; }

protocol::Hello ProcessEngine::ask_hello(const std::string& name, const std::string& command,
                                         std::chrono::milliseconds timeout) {
  ProcessEngineOptions options;
  options.name = name;
  options.command = command;
  options.timeout = timeout;
  const ProcessEngine engine(std::move(options));
  return engine.hello_;
}

}  // namespace boxpile
