// A number as a printf format with one double conversion writes it: the tables of the reports and
// of the command line. Callers that print non-finite numbers their own way check before calling.
#pragma once

#include <cstdio>
#include <string>

namespace boxpile {

inline std::string format_number(double x, const char* printf_format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, x);
  return buf;
}

}  // namespace boxpile
