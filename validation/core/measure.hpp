// A figure a tool reports over many runs, declared once: its name in reports (a JSON key, a
// column), its unit and what it measures. Sweeps' error measures and the outcome statistics'
// measures are tables of these.
#pragma once

#include <string_view>

namespace boxpile {

struct MeasureDeclaration {
  std::string_view name;
  std::string_view unit;
  std::string_view what;
};

}  // namespace boxpile
