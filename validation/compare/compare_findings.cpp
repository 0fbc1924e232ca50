#include "boxpile/validation/compare/compare_findings.hpp"

#include <algorithm>
#include <cmath>

#include "boxpile/validation/compare/compare.hpp"
#include "boxpile/validation/core/format_number.hpp"

namespace boxpile {
namespace {

// Three significant digits: the findings are sentences, not tables.
std::string figure(double x) { return format_number(x, "%.3g"); }
std::string at(double t) { return format_number(t, "%.3f") + " s"; }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Whom engine `e` is measured against, in words: the other engine of a pair, else the median.
std::string against_whom(const CompareResult& r, std::size_t e) {
  return r.runs.size() == 2 ? r.runs[1 - e].engine + "'s" : std::string("the engines' median");
}

// What engine `e` is measured against: the median of every engine's value (its own among them)
// when three or more ran, so that one odd engine does not move it; the other engine's when two did.
double consensus(const std::vector<double>& values, std::size_t e) {
  if (values.size() == 2) return values[1 - e];
  return median(values);
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? (i + 1 == names.size() ? " and " : ", ") : "") + names[i];
  return out;
}

void add_checks(const CompareResult& r, std::vector<CompareFinding>& out) {
  for (const EngineRun& run : r.runs) {
    for (const SceneCheckResult& c : run.checks)
      out.push_back({run.engine, "check", (c.passed ? "passes " : "fails ") + describe(c), std::nullopt});
  }
  if (r.runs.size() < 3) return;
  for (std::size_t e = 0; e < r.runs.size(); ++e) {
    for (const SceneCheckResult& c : r.runs[e].checks) {
      if (c.passed) continue;
      std::vector<std::string> others;
      bool others_pass = true;
      for (std::size_t o = 0; o < r.runs.size() && others_pass; ++o) {
        if (o == e) continue;
        const auto it = std::find_if(r.runs[o].checks.begin(), r.runs[o].checks.end(),
                                     [&](const SceneCheckResult& x) { return x.name == c.name; });
        others_pass = it != r.runs[o].checks.end() && it->passed;
        others.push_back(r.runs[o].engine);
      }
      if (others_pass) {
        out.push_back({r.runs[e].engine, "odd_check",
                       "alone fails " + describe(c) + "; " + join(others) + " pass it", std::nullopt});
      }
    }
  }
}

// The earliest time any engine passes the position threshold against its own perturbed start:
// after it, when an impact happens is chaos's to decide, and the energies of engines whose
// impacts fall at different times part and meet again without meaning anything.
std::optional<double> chaos_time(const CompareResult& r) {
  std::optional<double> t;
  for (const Baseline& b : r.baselines) {
    const std::optional<double>& passes = b.divergence.position_passes;
    if (passes && (!t || *passes < *t)) t = passes;
  }
  return t;
}

void add_energy(const CompareResult& r, const FindingLimits& limits, std::vector<CompareFinding>& out) {
  if (r.runs.size() < 2) return;
  double in_motion = 0.0, scale = 0.0;
  for (const EngineRun& run : r.runs) {
    for (double k : run.recording.frames.kinetic) in_motion = std::max(in_motion, k);
    scale = std::max(scale, std::abs(run.energy_initial));
  }
  const double gap_limit = std::max(limits.energy_fraction * in_motion, limits.energy_floor * scale);
  if (!(gap_limit > 0.0)) return;
  // A gap as a share of what set its limit: the energy in motion, or (a scene nearly at rest) the
  // scene's energy.
  const bool by_motion = limits.energy_fraction * in_motion >= limits.energy_floor * scale;
  const auto share = [&](double gap) {
    return by_motion ? figure(std::abs(gap) / in_motion) + " of the " + figure(in_motion) + " J in motion"
                     : figure(std::abs(gap) / scale) + " of the scene's " + figure(scale) + " J (" + figure(in_motion) +
                           " J in motion)";
  };
  const std::optional<double> chaos = chaos_time(r);
  for (std::size_t e = 0; e < r.runs.size(); ++e) {
    const FrameSeries& f = r.runs[e].recording.frames;
    const std::size_t n = std::min(f.t.size(), f.energy.size());
    if (n == 0) continue;
    std::vector<double> theirs(n), gap(n);
    for (std::size_t k = 0; k < n; ++k) {
      std::vector<double> all;
      for (std::size_t o = 0; o < r.runs.size(); ++o)
        all.push_back(o == e ? f.energy[k] : value_at_time(r.runs[o].recording.frames.t, r.runs[o].recording.frames.energy, f.t[k]));
      theirs[k] = consensus(all, e);
      gap[k] = f.energy[k] - theirs[k];
    }
    const std::string whose = against_whom(r, e);
    const auto gap_text = [&](std::size_t k) {
      return figure(std::abs(gap[k])) + " J " + (gap[k] < 0 ? "lower" : "higher") + " (" + figure(f.energy[k]) +
             " J against " + figure(theirs[k]) + " J at " + at(f.t[k]) + ")";
    };
    // The first frame from which the gap stays past the limit, with one sign, for
    // `energy_persistence` (or to the end): an impact that merely falls a few steps earlier in one
    // engine opens a gap that closes when the others' impact comes.
    std::size_t parted = n;
    for (std::size_t k = 0; k < n && parted == n; ++k) {
      if (std::abs(gap[k]) <= gap_limit) continue;
      std::size_t j = k;
      while (j + 1 < n && std::abs(gap[j + 1]) > gap_limit && gap[j + 1] * gap[k] > 0.0) ++j;
      if (j + 1 == n || f.t[j] - f.t[k] >= limits.energy_persistence) parted = k;
    }
    if (parted < n && (!chaos || f.t[parted] < *chaos)) {
      // The gap the parting opens: followed while it grows with the same sign (an impact's loss
      // takes a few frames), then its value there.
      std::size_t k = parted;
      while (k + 1 < n && gap[k + 1] * gap[k] > 0.0 && std::abs(gap[k + 1]) >= std::abs(gap[k])) ++k;
      out.push_back({r.runs[e].engine, "energy",
                     "total energy parts from " + whose + " at " + at(f.t[parted]) + ", before chaos" +
                         (chaos ? " (" + at(*chaos) + ")" : std::string()) + ": " + gap_text(k) + ", " + share(gap[k]) +
                         "; at the end " + gap_text(n - 1),
                     f.t[parted]});
    } else if (std::abs(gap[n - 1]) > gap_limit) {
      out.push_back({r.runs[e].engine, "energy",
                     "total energy ends apart from " + whose + ": " + gap_text(n - 1) + ", " + share(gap[n - 1]),
                     f.t[n - 1]});
    }
  }
}

void add_odd_one_out(const CompareResult& r, std::vector<CompareFinding>& out) {
  if (r.runs.size() < 3) return;
  const double threshold = r.settings.position_threshold;
  for (const EngineRun& run : r.runs) {
    // When it had left every other engine (the latest of its pairs' passing times), and when the
    // first two of the others parted.
    std::optional<double> left_all = 0.0, others_part;
    for (const PairComparison& p : r.pairs) {
      const RunDifference& d = p.difference;
      const bool mine = d.a == run.engine || d.b == run.engine;
      if (mine) {
        if (!d.position_passes) left_all.reset();
        else if (left_all) left_all = std::max(*left_all, *d.position_passes);
      } else if (d.position_passes && (!others_part || *d.position_passes < *others_part)) {
        others_part = d.position_passes;
      }
    }
    if (!left_all || (others_part && *others_part <= *left_all)) continue;
    std::vector<std::string> others;
    for (const EngineRun& o : r.runs)
      if (o.engine != run.engine) others.push_back(o.engine);
    out.push_back({run.engine, "odd_one_out",
                   "leaves the others first: more than " + figure(threshold) + " m from each of " + join(others) +
                       " by " + at(*left_all) + ", while they " +
                       (others_part ? "agree with each other until " + at(*others_part) : "agree with each other throughout"),
                   left_all});
  }
}

void add_penetration(const CompareResult& r, const FindingLimits& limits, std::vector<CompareFinding>& out) {
  if (r.runs.size() < 2) return;
  // The scene's smallest box edge, as the run's checks measured it.
  const double floor = limits.penetration_edge_fraction * r.runs.front().measures.smallest_edge;
  std::vector<double> all;
  for (const EngineRun& run : r.runs) all.push_back(run.deepest.depth);
  for (std::size_t e = 0; e < r.runs.size(); ++e) {
    const double mine = r.runs[e].deepest.depth, theirs = consensus(all, e);
    if (mine <= floor || mine <= limits.penetration_factor * theirs) continue;
    out.push_back({r.runs[e].engine, "penetration",
                   "goes " + figure(mine) + " m deep at " + at(r.runs[e].deepest_t) + ", " +
                       (theirs > 0.0 ? figure(mine / theirs) + " times " + against_whom(r, e) + " (" + figure(theirs) + " m)"
                                     : std::string("where the others do not penetrate")) +
                       "; " + figure(100.0 * limits.penetration_edge_fraction) + "% of the smallest box edge is " + figure(floor) + " m",
                   r.runs[e].deepest_t});
  }
}

}  // namespace

std::vector<CompareFinding> compare_findings(const CompareResult& result, const FindingLimits& limits) {
  std::vector<CompareFinding> out;
  add_checks(result, out);
  add_odd_one_out(result, out);
  add_energy(result, limits, out);
  add_penetration(result, limits, out);
  return out;
}

}  // namespace boxpile
