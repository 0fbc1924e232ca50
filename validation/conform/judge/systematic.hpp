// One mistake made everywhere, named: over every failure of a run (CheckResult::symptoms), a depth
// that is a constant ratio of the truth or off it by a constant, a deepest point a constant
// fraction of the depth (or a constant length) from the midway plane, normals reversed in one
// contact kind. A collider with such a mistake fails hundreds of queries for one reason; the
// report says the reason before the cases.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "boxpile/validation/conform/judge/check_collider.hpp"

namespace boxpile {

// A pattern is named when it holds for at least this share of the queries it is looked for in
// (a stray query of another kind among them does not hide it)...
inline constexpr double kSystematicShare = 0.9;
// ... and for at least this many (two failures are a coincidence, not a pattern).
inline constexpr int kSystematicMinimum = 3;
// A value counts as "the same" within this fraction of its distance from right (1 for a ratio, 0
// for an offset or a fraction): 0.9 and 0.91 are one pattern, 0.9 and 1.1 two.
inline constexpr double kSystematicBand = 0.1;

// The median of some values and how many lie within its band.
struct ConstantFit {
  double value = 0.0;   // the median
  double spread = 0.0;  // the largest distance from it among those within the band
  int within = 0;
  int of = 0;
};
// `right` is the value of a right answer (1 for a ratio, 0 for an offset); `floor` the least half
// width of the band (a tolerance).
ConstantFit fit_constant(std::vector<double> values, double right, double floor);

struct SystematicError {
  std::string pattern;  // depth_ratio, depth_offset, position_fraction, position_offset, reversed_normals
  std::string contact;  // the contact kind (reversed_normals), or empty
  double value = 0.0;   // the ratio, the offset (m) or the fraction; 0 for reversed normals
  double spread = 0.0;
  int count = 0;        // queries showing it
  int of = 0;           // queries it was looked for in
  std::string text;     // "depth 0.9 of the truth in 724 of 724 failing depth queries (spread ±2e-16)"
};

std::vector<SystematicError> find_systematic(const CheckResult& result, const JudgeTolerances& tol = {});

}  // namespace boxpile
