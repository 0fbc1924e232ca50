// The messages of the engine protocol (docs/engine-protocol.md), apart from any process: the
// requests boxpile writes and the checks of each answer line, so that the answer reader can be
// tested and fuzzed on its own (fuzz/fuzz_engine_reply.cpp).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile::protocol {

// The version this boxpile speaks; an engine that answers hello with another is refused.
inline constexpr int kVersion = 1;

// An answer line that breaks the protocol, or an answer {"ok": false}; what() says what is wrong
// (without the engine, request or step: the caller adds them).
class ReplyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One setting an engine declares in its hello (`settings`), checked for shape.
struct DeclaredSetting {
  std::string key;
  std::string kind;  // "integer", "number", "boolean" or "choice"
  std::string unit;
  std::string what;
  double min = 0.0, max = 0.0;  // integer and number
  std::vector<std::string> choices;  // choice
  nlohmann::json default_value;
};

// What an engine says of itself in its hello.
struct Hello {
  std::string name;
  std::string version;
  std::string precision;  // "float32" or "float64"
  bool contacts = false;
  bool timing = false;
  std::vector<DeclaredSetting> settings;
};

// What boxpile expects of a step's answer.
struct StepAsk {
  std::size_t bodies = 0;  // the scene's body count
  bool state = true;
  bool contacts = false;
};

struct StepReply {
  double time = 0.0;
  std::optional<double> engine_seconds;
  std::vector<BodyState> bodies;  // names left empty: the caller knows them
  std::vector<BodyContact> contacts;
};

// Requests, each one line without its '\n'.
std::string hello_request();
std::string load_request(const Scene& scene, const nlohmann::json& settings);
std::string step_request(int n, bool state, bool contacts);
std::string quit_request();

// The scene in the protocol's resolved form (the `scene` of load): mass properties from
// make_bodies() (so every engine shares ours), materials with the effects applied.
nlohmann::json scene_message(const Scene& scene);

// Parses and checks one answer line. Each throws ReplyError when the line is no JSON object,
// `ok` is missing or false (then with the engine's `error`), or a field is missing, of the wrong
// type, count or range, or not finite.
Hello parse_hello(std::string_view line);
void parse_ok(std::string_view line);  // the answer of load and quit
StepReply parse_step(std::string_view line, const StepAsk& ask);
// The same into `out`, reusing its storage (the per-step path).
void parse_step(std::string_view line, const StepAsk& ask, StepReply& out);

}  // namespace boxpile::protocol
