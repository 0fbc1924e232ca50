// printf into a string: the judge's messages of findings and patterns.
#pragma once

#include <cstdio>
#include <string>

namespace boxpile {

template <class... Args>
std::string printed(const char* format, Args... args) {
  const int n = std::snprintf(nullptr, 0, format, args...);
  std::string s(static_cast<std::size_t>(n), '\0');
  std::snprintf(s.data(), s.size() + 1, format, args...);
  return s;
}

}  // namespace boxpile
