// What boxpile prints for people passes through terminal_safe() (sim/io/json_input.hpp): a
// scene's names, messages, an outside collider's or engine's text can then neither steer nor
// reorder the terminal. Standard error carries only messages and is always escaped; standard
// output is escaped when it is a terminal, so that JSON and tables piped or redirected stay
// byte for byte what was written (and JSON on a terminal still reads back the same: the escapes
// are JSON's \uXXXX).
#pragma once

#include <ostream>
#include <streambuf>
#include <string>

namespace boxpile::cli {

// A stream buffer that escapes what passes to `target`, line by line (a cut UTF-8 sequence
// waits for its end).
class EscapingBuffer : public std::streambuf {
 public:
  explicit EscapingBuffer(std::streambuf* target) : target_(target) {}
  ~EscapingBuffer() override;

 protected:
  int_type overflow(int_type c) override;
  std::streamsize xsputn(const char* s, std::streamsize n) override;
  int sync() override;

 private:
  void drain(bool all);
  std::streambuf* target_;
  std::string pending_;
};

// Escapes std::cerr, and std::cout when standard output is a terminal, for its lifetime.
class TerminalEscaping {
 public:
  TerminalEscaping();
  ~TerminalEscaping();
  TerminalEscaping(const TerminalEscaping&) = delete;
  TerminalEscaping& operator=(const TerminalEscaping&) = delete;

 private:
  EscapingBuffer err_, out_;
  std::streambuf* old_err_ = nullptr;
  std::streambuf* old_out_ = nullptr;
};

}  // namespace boxpile::cli
