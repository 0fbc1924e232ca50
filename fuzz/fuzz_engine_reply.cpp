// libFuzzer target: the reader of an engine's answer lines (docs/engine-protocol.md), apart from
// any process. An input is "<bodies><c|s><line>": the scene's body count (one digit), whether
// contacts were asked ('c') or states alone ('s'), then the answer line. What must hold for any
// input: parse_hello and parse_step either throw ReplyError or return what was asked, every
// number finite, every body index in range. Anything else is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "boxpile/reference/process/protocol.hpp"
#include "boxpile/sim/finite.hpp"

namespace {

using namespace boxpile;

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "accepted answer breaks its promise: %s\n", what);
  std::abort();
}

void check(const protocol::StepReply& r, const protocol::StepAsk& ask) {
  if (!std::isfinite(r.time)) finding("time not finite");
  if (r.bodies.size() != ask.bodies) finding("wrong body count");
  if (find_non_finite(r.bodies)) finding("a state not finite");
  for (const BodyContact& c : r.contacts) {
    const int n = static_cast<int>(ask.bodies);
    if (c.body_a < 0 || c.body_a >= n || c.body_b < kGround || c.body_b >= n) finding("a body index out of range");
    if (!c.contact.position.allFinite() || !c.contact.normal.allFinite() || !std::isfinite(c.contact.depth)) {
      finding("a contact not finite");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2 || data[0] < '0' || data[0] > '9') return 0;
  const protocol::StepAsk ask{static_cast<std::size_t>(data[0] - '0'), true, data[1] == 'c'};
  const std::string_view line(reinterpret_cast<const char*>(data) + 2, size - 2);
  try {
    check(protocol::parse_step(line, ask), ask);
  } catch (const protocol::ReplyError&) {
    // refused with a message: fine
  }
  try {
    static_cast<void>(protocol::parse_hello(line));
  } catch (const protocol::ReplyError&) {
  }
  return 0;
}
