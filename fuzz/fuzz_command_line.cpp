// libFuzzer target: the command line (`boxpile ARGS...`) parsed and checked, nothing run. The
// input is split at NUL bytes into arguments (at most kMaxArguments, each at most kMaxArgument
// bytes: the command line's own limits are not what is fuzzed). What must hold: every vector
// either parses (exit 0) or is refused with the bad-input code 2 (or is help or the version,
// exit 0), without a crash, a sanitizer report or an exception escaping.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "boxpile/validation/cli/command_line.hpp"

namespace {

constexpr std::size_t kMaxArguments = 32;
constexpr std::size_t kMaxArgument = 4096;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> words{"boxpile"};
  std::string word;
  for (std::size_t i = 0; i < size && words.size() <= kMaxArguments; ++i) {
    if (data[i] == 0) {
      words.push_back(word);
      word.clear();
    } else if (word.size() < kMaxArgument) {
      word.push_back(static_cast<char>(data[i]));
    }
  }
  if (!word.empty() && words.size() <= kMaxArguments) words.push_back(word);
  std::vector<const char*> argv;
  for (const std::string& w : words) argv.push_back(w.c_str());
  argv.push_back(nullptr);
  const int code = boxpile::cli::run_command_line(static_cast<int>(words.size()), argv.data(),
                                                  boxpile::cli::CommandLineMode::ParseOnly);
  if (code != 0 && code != 2) {
    std::fprintf(stderr, "command line parse exited %d (only 0 and 2 are documented for parsing)\n", code);
    std::abort();
  }
  return 0;
}
