#include "boxpile/validation/cli/terminal_output.hpp"

#include <unistd.h>

#include <iostream>

#include "boxpile/sim/io/json_input.hpp"

namespace boxpile::cli {

EscapingBuffer::~EscapingBuffer() { drain(true); }

void EscapingBuffer::drain(bool all) {
  const std::size_t n = all ? pending_.size() : json_input::whole_utf8_prefix(pending_);
  if (n == 0) return;
  const std::string safe = json_input::terminal_safe(std::string_view(pending_).substr(0, n), true);
  target_->sputn(safe.data(), static_cast<std::streamsize>(safe.size()));
  pending_.erase(0, n);
}

EscapingBuffer::int_type EscapingBuffer::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
  const char ch = traits_type::to_char_type(c);
  xsputn(&ch, 1);
  return c;
}

std::streamsize EscapingBuffer::xsputn(const char* s, std::streamsize n) {
  pending_.append(s, static_cast<std::size_t>(n));
  // An escape sequence ESC [ K is kept whole: it waits for its last byte.
  const std::size_t esc = pending_.rfind('\x1b');
  const bool cut_escape = esc != std::string::npos && pending_.size() - esc < 3;
  if (!cut_escape && (pending_.find('\n') != std::string::npos || pending_.size() >= 4096)) drain(false);
  return n;
}

int EscapingBuffer::sync() {
  drain(false);
  return target_->pubsync();
}

TerminalEscaping::TerminalEscaping() : err_(std::cerr.rdbuf()), out_(std::cout.rdbuf()) {
  std::cerr.flush();
  old_err_ = std::cerr.rdbuf(&err_);
  if (isatty(STDOUT_FILENO) == 1) {
    std::cout.flush();
    old_out_ = std::cout.rdbuf(&out_);
  }
}

TerminalEscaping::~TerminalEscaping() {
  std::cerr.flush();
  std::cerr.rdbuf(old_err_);
  if (old_out_) {
    std::cout.flush();
    std::cout.rdbuf(old_out_);
  }
}

}  // namespace boxpile::cli
