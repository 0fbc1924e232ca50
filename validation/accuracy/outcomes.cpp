#include "boxpile/validation/accuracy/outcomes.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/sim/metrics.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/core/format_number.hpp"
#include "boxpile/validation/core/run_loop.hpp"
#include "boxpile/validation/rulers/stacks.hpp"

namespace boxpile {
namespace {

// SplitMix64: a few lines, the same numbers on every machine (std::uniform_real_distribution is
// not specified to).
std::uint64_t splitmix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A number in [0, 1) from (seed, index, body).
double start_uniform(std::uint64_t seed, int index, std::size_t body) {
  const std::uint64_t h = splitmix(splitmix(splitmix(seed) ^ static_cast<std::uint64_t>(index)) ^ static_cast<std::uint64_t>(body));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

bool in_the_pile(const Scene& scene, std::size_t i) { return !scene.bodies[i].fixed && !scene.bodies[i].wire; }

// The part of `v` across gravity.
Vec3 across_gravity(const Vec3& v, const Vec3& down) { return v - v.dot(down) * down; }

std::string mean_sd_text(const SampleSummary& s) {
  return format_number(s.mean, "%.4g") + " ± " + format_number(s.sd, "%.2g");
}

}  // namespace

std::map<std::string, double> outcome_measures(const Scene& scene, const std::vector<BodyState>& start,
                                               const std::vector<BodyState>& end) {
  std::vector<RigidBody> bodies = make_bodies(scene);
  const Vec3 down = down_direction(scene.gravity);
  std::map<std::string, double> m;

  set_body_states(bodies, start);
  const double energy_start = measure_energy(bodies, scene.gravity).total();
  double mass = 0.0;
  Vec3 com_start = Vec3::Zero();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!in_the_pile(scene, i)) continue;
    mass += bodies[i].mass;
    com_start += bodies[i].mass * bodies[i].x;
  }

  set_body_states(bodies, end);
  m["energy_lost"] = energy_start - measure_energy(bodies, scene.gravity).total();
  Vec3 com_end = Vec3::Zero();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (in_the_pile(scene, i)) com_end += bodies[i].mass * bodies[i].x;
  }
  if (mass > 0.0) {
    com_start /= mass;
    com_end /= mass;
  }
  m["com_shift"] = across_gravity(com_end - com_start, down).norm();
  double square = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!in_the_pile(scene, i)) continue;
    square += across_gravity(bodies[i].x - com_end, down).squaredNorm();
    ++count;
  }
  m["spread"] = count > 0 ? std::sqrt(square / count) : 0.0;

  double tallest = 0.0;
  int stacked = 0;
  for (const Stack& s : find_stacks(bodies, scene)) {
    tallest = std::max(tallest, s.height);
    for (int i : s.bodies) {
      const RigidBody& b = bodies[static_cast<std::size_t>(i)];
      bool grounded = false;
      for (int k = 0; k < static_cast<int>(b.shapes.size()) && !grounded; ++k) {
        const OrientedBox box = OrientedBox::from(b.shape_pose(k), b.shapes[static_cast<std::size_t>(k)].half_extents);
        grounded = box_plane_depth(box, *scene.ground) >= -kTouchTolerance;
      }
      if (!grounded) ++stacked;
    }
  }
  m["stacked"] = stacked;
  m["tallest"] = tallest;
  return m;
}

Scene perturbed_start(const Scene& scene, double distance, std::uint64_t seed, int index) {
  Scene s = scene;
  const auto [u, v] = across_directions(down_direction(scene.gravity));
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    BodyDesc& b = s.bodies[i];
    if (b.fixed) continue;
    const double r = start_uniform(seed, index, i);
    if (b.wire) {
      b.frame.position += distance * (2.0 * r - 1.0) * (b.wire->to - b.wire->from).normalized();
    } else {
      const double angle = 2.0 * std::numbers::pi * r;
      b.frame.position += distance * (std::cos(angle) * u + std::sin(angle) * v);
    }
  }
  return s;
}

namespace {

// OutcomePair's start-by-start counts: a start agrees when every measure of the two runs from it
// lies within the larger of the engines' spreads of that measure (at least 1e-12 of its size, so
// that two engines that always give one value agree when they give the same one).
void count_agreeing_starts(const EngineOutcomes& a, const EngineOutcomes& b, OutcomePair& p) {
  for (std::size_t ia = 0; ia < a.starts.size(); ++ia) {
    const auto ib = std::find(b.starts.begin(), b.starts.end(), a.starts[ia]);
    if (ib == b.starts.end()) continue;
    const std::size_t jb = static_cast<std::size_t>(ib - b.starts.begin());
    ++p.starts_compared;
    bool agree = true;
    for (const auto& [name, values] : a.samples) {
      const auto other = b.samples.find(name);
      if (other == b.samples.end()) continue;
      const double va = values[ia], vb = other->second[jb];
      const double spread = std::max({a.summary.at(name).sd, b.summary.at(name).sd,
                                      1e-12 * std::max(std::abs(va), std::abs(vb))});
      agree = agree && std::abs(va - vb) <= spread;
    }
    p.starts_agreeing += agree ? 1 : 0;
  }
}

}  // namespace

std::string OutcomePair::verdict() const { return differ ? "differ beyond their own spread" : "within chaos"; }

OutcomeStatistics run_outcomes(const Scene& scene, const std::vector<OutcomeEntry>& entries,
                               const OutcomeSettings& settings) {
  OutcomeStatistics out;
  out.settings = settings;
  out.dt = scene.time.dt;
  for (const OutcomeEntry& entry : entries) {
    EngineOutcomes e;
    e.label = entry.label;
    e.engine = entry.engine;
    for (int i = 0; i < settings.starts; ++i) {
      if (settings.progress) settings.progress(entry.label + " start " + std::to_string(i + 1) + " of " + std::to_string(settings.starts));
      const Scene start = scene_with_settings(entry.engine, perturbed_start(scene, settings.perturbation, settings.seed, i),
                                              entry.settings);
      const std::unique_ptr<Engine> engine = make_engine(entry.engine, start, entry.settings);
      engine->report_contacts(false);  // outcomes are read from the states alone
      std::vector<BodyState> first;
      RunHooks hooks;
      hooks.step = [&](const StepView& view) {
        if (view.step == 0) first = view.states;
      };
      const long steps = step_count(start.time);
      const RunLoopResult r = run_loop(*engine, start.time.dt, steps, steps, hooks);
      if (r.stopped) {
        ++e.non_finite;
        continue;
      }
      for (const auto& [name, value] : outcome_measures(start, first, r.final_states)) e.samples[name].push_back(value);
      e.starts.push_back(i);
    }
    for (const auto& [name, values] : e.samples) e.summary[name] = summarize(values);
    out.engines.push_back(std::move(e));
  }
  const double each = settings.significance / static_cast<double>(kOutcomeMeasures.size());
  for (std::size_t a = 0; a < out.engines.size(); ++a) {
    for (std::size_t b = a + 1; b < out.engines.size(); ++b) {
      OutcomePair p;
      p.a = out.engines[a].label;
      p.b = out.engines[b].label;
      for (const OutcomeMeasure& m : kOutcomeMeasures) {
        const std::string name(m.name);
        const std::vector<double> none;
        const auto& sa = out.engines[a].samples.count(name) ? out.engines[a].samples.at(name) : none;
        const auto& sb = out.engines[b].samples.count(name) ? out.engines[b].samples.at(name) : none;
        MeasureTest t;
        t.measure = name;
        t.ks = kolmogorov_smirnov(sa, sb);
        t.welch = welch_t_test(sa, sb);
        t.differ = !sa.empty() && !sb.empty() && t.ks.p_value < each;
        p.differ = p.differ || t.differ;
        p.tests.push_back(std::move(t));
      }
      count_agreeing_starts(out.engines[a], out.engines[b], p);
      out.pairs.push_back(std::move(p));
    }
  }
  return out;
}

nlohmann::json outcomes_json(const OutcomeStatistics& s) {
  using nlohmann::json;
  json measures = json::array();
  for (const OutcomeMeasure& m : kOutcomeMeasures) measures.push_back({{"name", m.name}, {"unit", m.unit}, {"what", m.what}});
  json engines = json::array();
  for (const EngineOutcomes& e : s.engines) {
    json summary = json::object();
    for (const auto& [name, sum] : e.summary) {
      summary[name] = {{"n", sum.n}, {"mean", sum.mean}, {"sd", sum.sd}, {"min", sum.min}, {"max", sum.max}};
    }
    engines.push_back({{"label", e.label}, {"engine", e.engine}, {"samples", e.samples}, {"summary", summary},
                       {"non_finite", e.non_finite}});
  }
  json pairs = json::array();
  for (const OutcomePair& p : s.pairs) {
    json tests = json::array();
    for (const MeasureTest& t : p.tests) {
      tests.push_back({{"measure", t.measure},
                       {"ks_statistic", t.ks.statistic},
                       {"ks_p", t.ks.p_value},
                       {"ks_exact", t.ks.exact},
                       {"welch_t", t.welch.t},
                       {"welch_df", t.welch.df},
                       {"welch_p", t.welch.p_value},
                       {"differ", t.differ}});
    }
    pairs.push_back({{"a", p.a}, {"b", p.b}, {"differ", p.differ}, {"verdict", p.verdict()},
                     {"starts_compared", p.starts_compared}, {"starts_agreeing", p.starts_agreeing}, {"tests", tests}});
  }
  return {{"starts", s.settings.starts},
          {"perturbation", s.settings.perturbation},
          {"seed", s.settings.seed},
          {"significance", s.settings.significance},
          {"dt", s.dt},
          {"measures", measures},
          {"engines", engines},
          {"pairs", pairs}};
}

std::string outcomes_markdown(const OutcomeStatistics& s) {
  std::ostringstream md;
  md << "### Outcomes over " << s.settings.starts << " perturbed starts\n\n"
     << "Each engine ran the scene from " << s.settings.starts << " starts, every free body's start moved by "
     << format_number(s.settings.perturbation, "%g") << " m in a direction drawn per start and body (seed "
     << s.settings.seed << "), at dt = " << format_number(s.dt, "%.6g") << " s. Per measure the mean ± the sample "
     << "standard deviation:\n\n| engine |";
  for (const OutcomeMeasure& m : kOutcomeMeasures) md << ' ' << m.name << " (" << m.unit << ") |";
  md << " non-finite |\n|---|";
  for (std::size_t i = 0; i < kOutcomeMeasures.size(); ++i) md << "---|";
  md << "---|\n";
  for (const EngineOutcomes& e : s.engines) {
    md << "| " << e.label << " |";
    for (const OutcomeMeasure& m : kOutcomeMeasures) {
      const auto it = e.summary.find(std::string(m.name));
      md << ' ' << (it == e.summary.end() ? std::string("—") : mean_sd_text(it->second)) << " |";
    }
    md << ' ' << e.non_finite << " |\n";
  }
  md << "\nBetween engines, per measure the Kolmogorov-Smirnov distance D and its p-value, and Welch's p-value "
        "for the means; a pair differs beyond its own spread when some measure's KS p-value is below "
     << format_number(s.settings.significance, "%g") << " / " << kOutcomeMeasures.size()
     << " (Bonferroni over the measures). Start by start, the two agree on a start when every measure of their "
        "runs from it lies within the larger of their own spreads (sd):\n\n| pair |";
  for (const OutcomeMeasure& m : kOutcomeMeasures) md << ' ' << m.name << ": D, p (Welch p) |";
  md << " starts agreeing | verdict |\n|---|";
  for (std::size_t i = 0; i < kOutcomeMeasures.size(); ++i) md << "---|";
  md << "---|---|\n";
  for (const OutcomePair& p : s.pairs) {
    md << "| " << p.a << " – " << p.b << " |";
    for (const MeasureTest& t : p.tests) {
      md << ' ' << (t.differ ? "**" : "") << format_number(t.ks.statistic, "%.2f") << ", "
         << format_number(t.ks.p_value, "%.2g") << (t.differ ? "**" : "") << " (" << format_number(t.welch.p_value, "%.2g")
         << ") |";
    }
    md << ' ' << p.starts_agreeing << " of " << p.starts_compared << " | " << p.verdict() << " |\n";
  }
  md << '\n';
  return md.str();
}

}  // namespace boxpile
