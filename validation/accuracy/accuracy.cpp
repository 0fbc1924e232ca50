#include "boxpile/validation/accuracy/accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/setting.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/core/run_loop.hpp"
#include "boxpile/validation/sweep/sweep.hpp"

namespace boxpile {
namespace {

// The reference steps of a converged truth: the finest cell's step halved, quartered, eighthed.
constexpr int kReferenceRefinements = 3;
// Iteration scales tried at each reference step until the final positions change by less than
// kIterationsSettled (m) from one scale to the next.
constexpr int kReferenceScales[] = {1, 4, 16};
constexpr double kIterationsSettled = 1e-9;
// The order seen between reference steps must reach this for Richardson extrapolation.
constexpr double kLeastExtrapolatedOrder = 0.5;

// The measures against an analytic truth whose orders are fitted one by one.
constexpr std::pair<const char*, std::optional<double> TruthMeasures::*> kMeasureMembers[] = {
    {"position", &TruthMeasures::position},       {"velocity", &TruthMeasures::velocity},
    {"orientation", &TruthMeasures::orientation}, {"trajectory", &TruthMeasures::trajectory},
    {"rebound", &TruthMeasures::rebound}};

bool ends_with(std::string_view s, std::string_view end) {
  return s.size() >= end.size() && s.substr(s.size() - end.size()) == end;
}

struct RunOutcome {
  std::vector<BodyState> final_states;
  std::optional<TruthMeasures> measures;  // against the scene's truth, when asked
  double engine_seconds = 0.0;
  long steps = 0;
  bool finite = true;
};

// One run of `engine` on `scene` with `settings`; `measure`: against the scene's truth.
RunOutcome run_once(const std::string& engine, const Scene& scene, const nlohmann::json& settings, bool measure) {
  const EngineConfig config{scene_with_settings(engine, scene, settings), settings};
  const std::unique_ptr<Engine> e = make_engine(engine, config.scene, config.settings);
  e->report_contacts(false);  // the truth is measured from the states alone
  std::optional<TruthMeter> meter;
  if (measure) meter.emplace(config.scene);
  RunHooks hooks;
  if (meter) hooks.step = [&](const StepView& v) { meter->observe(v.t, v.states); };
  RunOutcome out;
  out.steps = step_count(config.scene.time);
  const RunLoopResult loop = run_loop(*e, config.scene.time.dt, out.steps, out.steps, hooks);
  out.final_states = loop.final_states;
  out.engine_seconds = loop.engine_seconds;
  out.finite = !loop.stopped;
  if (meter) out.measures = meter->measures();
  return out;
}

double largest_distance(const std::vector<BodyState>& states, const std::vector<Vec3>& positions) {
  double worst = 0.0;
  for (std::size_t i = 0; i < states.size() && i < positions.size(); ++i) {
    worst = std::max(worst, (states[i].position - positions[i]).norm());
  }
  return worst;
}

std::vector<Vec3> positions_of(const std::vector<BodyState>& states) {
  std::vector<Vec3> p;
  for (const BodyState& s : states) p.push_back(s.position);
  return p;
}

// The final positions at `dt` with the iterations raised until they stop changing.
std::vector<Vec3> settled_positions(const std::string& engine, const Scene& scene, const nlohmann::json& base,
                                    double dt, nlohmann::json& used, const AccuracySettings& settings) {
  std::vector<Vec3> last;
  nlohmann::json previous;
  for (int scale : kReferenceScales) {
    const nlohmann::json s = iteration_settings(engine, scene, settings_at_step(base, dt), scale);
    // Nothing left to raise (no iteration setting, or each at its cap): the last run is the answer.
    if (!last.empty() && s == previous) break;
    previous = s;
    if (settings.progress) settings.progress(scene.name + " " + engine + " reference dt=" + std::to_string(dt));
    const RunOutcome r = run_once(engine, scene, s, false);
    if (!r.finite) {
      throw std::runtime_error(engine + " went non-finite on " + scene.name + " at the reference step " +
                               std::to_string(dt) + " s");
    }
    const bool settled = !last.empty() && largest_distance(r.final_states, last) < kIterationsSettled;
    last = positions_of(r.final_states);
    used = s;
    if (settled) break;
  }
  return last;
}

ConvergedTruth converged_truth(const std::string& engine, const Scene& scene, const nlohmann::json& base,
                               const AccuracySettings& settings) {
  ConvergedTruth t;
  double h = *std::min_element(settings.steps.begin(), settings.steps.end());
  std::vector<std::vector<Vec3>> refs;
  for (int k = 0; k < kReferenceRefinements; ++k) {
    h /= 2.0;
    t.steps.push_back(h);
    refs.push_back(settled_positions(engine, scene, base, h, t.settings, settings));
  }
  auto distance = [](const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
    return worst;
  };
  const std::vector<Vec3>& r1 = refs[0];
  const std::vector<Vec3>& r2 = refs[1];
  const std::vector<Vec3>& r3 = refs[2];
  const double d1 = distance(r1, r2), d2 = distance(r2, r3);
  t.positions = r3;
  t.uncertainty = d2;
  if (d2 > 1e-15 && d1 > d2) {
    const double p = std::log2(d1 / d2);
    t.order = p;
    if (p >= kLeastExtrapolatedOrder) {
      const double f = 1.0 / (std::pow(2.0, p) - 1.0);
      for (std::size_t i = 0; i < r3.size(); ++i) t.positions[i] = r3[i] + f * (r3[i] - r2[i]);
      t.extrapolated = true;
      t.uncertainty = f * d2;
    }
  }
  return t;
}

}  // namespace

std::string_view truth_kind_name(TruthKind kind) {
  switch (kind) {
    case TruthKind::Analytic: return "analytic";
    case TruthKind::Converged: return "converged";
    case TruthKind::Self: return "self";
  }
  return "analytic";
}

nlohmann::json settings_at_step(const nlohmann::json& settings, double dt) {
  nlohmann::json out = settings.is_null() ? nlohmann::json::object() : settings;
  out[time_step_setting().key] = dt;
  return out;
}

nlohmann::json iteration_settings(std::string_view engine, const Scene& scene, const nlohmann::json& settings,
                                  int scale) {
  if (scale == 1) return settings;
  nlohmann::json out = settings;
  const nlohmann::json resolved = resolved_settings(engine, scene, settings);
  for (const SettingInfo& info : engine_settings(engine)) {
    if (info.kind != SettingInfo::Kind::Integer) continue;
    if (!ends_with(info.key, "iterations") && !ends_with(info.key, "passes")) continue;
    if (const auto method = setting_method(engine, info.key); method && *method != scene.solver.method) continue;
    if (!resolved.contains(info.key) || !resolved.at(info.key).is_number_integer()) continue;
    const long value = resolved.at(info.key).get<long>();
    if (value < 1) continue;
    out[info.key] = static_cast<long>(std::min<double>(info.max, static_cast<double>(value) * scale));
  }
  return out;
}

std::optional<double> fitted_order(const std::vector<double>& x, const std::vector<double>& y, double floor) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (!(y[i] > floor) || !std::isfinite(y[i]) || !(x[i] > 0.0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++n;
  }
  if (n < 2) return std::nullopt;
  const double den = n * sxx - sx * sx;
  if (!(std::abs(den) > 0.0)) return std::nullopt;
  return (n * sxy - sx * sy) / den;
}

AccuracyResult run_accuracy(const std::vector<Scene>& scenes, const AccuracySettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  AccuracyResult result;
  result.settings = settings;
  result.machine = describe_machine();
  auto settings_of = [&](const std::string& engine) {
    const auto it = settings.engine_settings.find(engine);
    return it == settings.engine_settings.end() ? nlohmann::json::object() : it->second;
  };
  for (const Scene& scene : scenes) {
    AccuracyScene as;
    as.path = scene.source;
    as.name = scene.name;
    as.truth = settings.truth.value_or(scene.truth.empty() ? TruthKind::Converged : TruthKind::Analytic);
    if (as.truth == TruthKind::Analytic && scene.truth.empty()) {
      throw InputError(scene.source, "truth", "states no truth, so it cannot be measured against an analytic one "
                                              "(docs/scene-format.md, \"Truth\"; --truth converged or self)");
    }
    if (as.truth == TruthKind::Analytic) TruthMeter check(scene);  // a truth for another duration: refused before any run
    for (const std::string& engine : settings.engines) {
      AccuracyEngine ae;
      ae.engine = engine;
      for (int scale : settings.iteration_scales) {
        for (double dt : settings.steps) {
          AccuracyCell c;
          c.dt = dt;
          c.iteration_scale = scale;
          c.settings = iteration_settings(engine, scene, settings_at_step(settings_of(engine), dt), scale);
          ae.cells.push_back(c);
        }
      }
      as.engines.push_back(std::move(ae));
    }
    // Repetitions interleaved over the engines and cells, so that a change of the machine's load
    // falls on all of them: each cell's least time counts, its first run is measured.
    std::vector<std::vector<std::vector<BodyState>>> finals(as.engines.size());
    for (int rep = 0; rep < std::max(1, settings.repetitions); ++rep) {
      for (std::size_t e = 0; e < as.engines.size(); ++e) {
        AccuracyEngine& ae = as.engines[e];
        finals[e].resize(ae.cells.size());
        for (std::size_t i = 0; i < ae.cells.size(); ++i) {
          AccuracyCell& c = ae.cells[i];
          if (settings.progress) {
            settings.progress(scene.name + " " + ae.engine + " dt=" + std::to_string(c.dt) + " run " +
                              std::to_string(rep + 1));
          }
          const RunOutcome r = run_once(ae.engine, scene, c.settings,
                                        rep == 0 && as.truth == TruthKind::Analytic);
          const double us = 1e6 * r.engine_seconds / (static_cast<double>(r.steps) * c.dt);
          if (rep == 0) {
            c.steps = r.steps;
            c.finite = r.finite;
            c.us_per_simulated_second = us;
            finals[e][i] = r.final_states;
            if (r.measures) c.measures = *r.measures;
          } else {
            c.us_per_simulated_second = std::min(c.us_per_simulated_second, us);
          }
        }
      }
    }
    for (std::size_t e = 0; e < as.engines.size(); ++e) {
      AccuracyEngine& ae = as.engines[e];
      if (as.truth == TruthKind::Converged) ae.converged = converged_truth(ae.engine, scene, settings_of(ae.engine), settings);
      std::vector<Vec3> self_truth;
      if (as.truth == TruthKind::Self) {
        // The finest step at the first scale.
        std::size_t finest = 0;
        for (std::size_t i = 0; i < ae.cells.size(); ++i) {
          if (ae.cells[i].iteration_scale == ae.cells[0].iteration_scale && ae.cells[i].dt < ae.cells[finest].dt) finest = i;
        }
        self_truth = positions_of(finals[e][finest]);
      }
      for (std::size_t i = 0; i < ae.cells.size(); ++i) {
        AccuracyCell& c = ae.cells[i];
        if (!c.finite) {
          c.error = std::numeric_limits<double>::infinity();
          continue;
        }
        switch (as.truth) {
          case TruthKind::Analytic: c.error = c.measures.error(); break;
          case TruthKind::Converged: c.error = largest_distance(finals[e][i], ae.converged->positions); break;
          case TruthKind::Self: c.error = largest_distance(finals[e][i], self_truth); break;
        }
      }
      std::vector<double> x, y;
      for (const AccuracyCell& c : ae.cells) {
        if (c.iteration_scale != settings.iteration_scales.front()) continue;
        x.push_back(c.dt);
        y.push_back(c.error);
      }
      ae.order = fitted_order(x, y);
      if (as.truth == TruthKind::Analytic) {
        for (const auto& [name, member] : kMeasureMembers) {
          std::vector<double> mx, my;
          for (const AccuracyCell& c : ae.cells) {
            if (c.iteration_scale != settings.iteration_scales.front() || !(c.measures.*member)) continue;
            mx.push_back(c.dt);
            my.push_back(*(c.measures.*member));
          }
          if (!my.empty()) ae.orders[name] = fitted_order(mx, my);
        }
      }
    }
    if (settings.outcomes.starts > 0) {
      std::vector<OutcomeEntry> entries;
      for (const std::string& engine : settings.engines) entries.push_back({engine, engine, settings_of(engine)});
      OutcomeSettings o = settings.outcomes;
      if (settings.progress) o.progress = [&](std::string_view what) { settings.progress(scene.name + " outcomes: " + std::string(what)); };
      as.outcomes = run_outcomes(scene, entries, o);
    }
    result.scenes.push_back(std::move(as));
  }
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace boxpile
