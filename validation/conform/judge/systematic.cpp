#include "boxpile/validation/conform/judge/systematic.hpp"

#include "boxpile/validation/conform/judge/printed.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace boxpile {
namespace {

bool named(const ConstantFit& f) {
  return f.within >= kSystematicMinimum && f.within >= kSystematicShare * f.of;
}

// The better of two fits of the same queries: the one that holds for more of them, a ratio (or
// fraction) on a tie.
const ConstantFit& better(const ConstantFit& relative, const ConstantFit& absolute) {
  return absolute.within > relative.within ? absolute : relative;
}

std::string depth_text(bool ratio, const ConstantFit& f) {
  if (ratio) return printed("depth %.3g of the truth", f.value);
  return printed("depth %.3g m %s than the truth", std::abs(f.value), f.value > 0 ? "deeper" : "shallower");
}

std::string position_text(bool fraction, const ConstantFit& f) {
  const char* side = f.value > 0 ? "toward A" : "toward B";
  if (fraction) return printed("deepest point %.3g of the depth %s from the midway plane", std::abs(f.value), side);
  return printed("deepest point %.3g m %s from the midway plane", std::abs(f.value), side);
}

void add_fit(std::vector<SystematicError>& out, const std::vector<AnsweredTruth>& pairs, bool depth, double tol) {
  std::vector<double> relative, absolute;
  for (const AnsweredTruth& p : pairs) {
    if (p.truth <= tol) continue;  // no ratio of a zero depth
    relative.push_back(p.answered / p.truth);
    absolute.push_back(depth ? p.answered - p.truth : p.answered);
  }
  const double right_relative = depth ? 1.0 : 0.0;
  const ConstantFit r = fit_constant(relative, right_relative, 0.0);
  const ConstantFit a = fit_constant(absolute, 0.0, tol);
  const ConstantFit& f = better(r, a);
  if (!named(f)) return;
  const bool is_relative = &f == &r;
  SystematicError e;
  e.pattern = depth ? (is_relative ? "depth_ratio" : "depth_offset") : (is_relative ? "position_fraction" : "position_offset");
  e.value = f.value;
  e.spread = f.spread;
  e.count = f.within;
  e.of = f.of;
  e.text = (depth ? depth_text(is_relative, f) : position_text(is_relative, f)) +
           printed(" in %d of %d failing %s queries (spread ±%.2g%s)", f.within, f.of, depth ? "depth" : "outside",
                   f.spread, is_relative ? "" : " m");
  out.push_back(std::move(e));
}

}  // namespace

ConstantFit fit_constant(std::vector<double> values, double right, double floor) {
  ConstantFit f;
  f.of = static_cast<int>(values.size());
  if (values.empty()) return f;
  std::sort(values.begin(), values.end());
  f.value = values[values.size() / 2];
  const double band = std::max(kSystematicBand * std::abs(f.value - right), floor);
  for (const double v : values) {
    const double d = std::abs(v - f.value);
    if (d > band) continue;
    ++f.within;
    f.spread = std::max(f.spread, d);
  }
  return f;
}

std::vector<SystematicError> find_systematic(const CheckResult& result, const JudgeTolerances& tol) {
  std::vector<SystematicError> out;
  std::vector<AnsweredTruth> depths, positions;
  for (const Symptom& s : result.symptoms) {
    if (s.depth) depths.push_back(*s.depth);
    if (s.position) positions.push_back(*s.position);
  }
  add_fit(out, depths, true, tol.depth);
  add_fit(out, positions, false, tol.region);
  for (const auto& [contact, t] : result.by_contact) {
    if (t.reversed < kSystematicMinimum || t.reversed < kSystematicShare * t.answered) continue;
    SystematicError e;
    e.pattern = "reversed_normals";
    e.contact = std::string(contact_kind_name(contact));
    e.count = t.reversed;
    e.of = t.answered;
    e.text = printed("%s normals reversed in %d of %d %s queries answered with a contact", e.contact.c_str(),
                     t.reversed, t.answered, e.contact.c_str());
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace boxpile
