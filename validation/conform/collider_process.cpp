#include "boxpile/validation/conform/collider_process.hpp"

#include "boxpile/validation/core/json_output.hpp"

namespace boxpile {
namespace {

std::string query_label(const ContactQuery& q) { return q.name.empty() ? std::string("a query") : "query " + q.name; }

// The collider's exit, when it has exited within the grace, else what it did to its pipe.
std::string exit_or(ChildProcess& child, const std::string& otherwise) {
  const std::optional<int> status = child.wait_exit(ChildProcess::kExitGrace);
  return status ? ChildProcess::describe_status(*status) : otherwise;
}

}  // namespace

// The collider writes its standard error to ours, as before the child process was shared.
ColliderProcess::ColliderProcess(std::string command, std::chrono::milliseconds timeout)
    : child_(std::move(command), ChildProcess::StandardError::Inherit), timeout_(timeout) {}

ColliderProcess::~ColliderProcess() = default;

void ColliderProcess::fail(const std::string& what) {
  child_.kill_now();
  child_.stop();
  throw ColliderError("collider \"" + child_.command() + "\" " + what);
}

Manifold ColliderProcess::ask(const ContactQuery& query) {
  if (!child_.write_all(query_json(query).dump() + "\n")) {
    fail(exit_or(child_, "closed its input") + " before reading " + query_label(query));
  }
  std::string line;
  switch (child_.read_line(line, timeout_)) {
    case ChildProcess::ReadResult::Line: break;
    case ChildProcess::ReadResult::Timeout:
      fail("gave no answer to " + query_label(query) + " within " + std::to_string(timeout_.count()) + " ms");
    case ChildProcess::ReadResult::Closed:
      fail(exit_or(child_, "closed its output") + " before answering " + query_label(query) + " (output line " +
           std::to_string(child_.lines_read() + 1) + ")");
  }
  try {
    return parse_answer(line, "output line " + std::to_string(child_.lines_read()));
  } catch (const InputError& e) {
    const std::string shown = line.size() > 200 ? line.substr(0, 200) + "..." : line;
    fail("answered " + query_label(query) + " with no valid answer: " + e.what() + "; the line was: " + shown);
  }
}

}  // namespace boxpile
