// Chaotic scenes by statistics (docs/accuracy.md, "Chaotic scenes"): the two-sample tests against
// known values (exact counts of the orderings, closed forms, published examples), the outcome
// measures against a hand computation, the perturbed starts, and a cheap scene on which an engine
// run twice is found not to differ from itself while a deliberately biased one is found to differ.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/accuracy/outcomes.hpp"
#include "boxpile/validation/accuracy/two_sample.hpp"
#include "boxpile/validation/compare/compare.hpp"

using namespace boxpile;

namespace {

// The exact p-values, counted over every ordering of the pooled sample (C(n + m, n) of them) by an
// independent enumeration: the share whose empirical distributions part by D or more.
struct ExactKs {
  int n, m;
  double d;
  double p;
};
constexpr ExactKs kExactKs[] = {
    {5, 5, 0.8, 5.0 / 63.0},       // 20 of the 252 orderings
    {5, 5, 0.6, 5.0 / 14.0},       // 90 of 252
    {5, 5, 1.0, 1.0 / 126.0},      // 2 of 252: one sample wholly below the other
    {4, 6, 2.0 / 3.0, 19.0 / 105.0},  // 38 of 210
    {6, 8, 0.5, 302.0 / 1001.0},   // 906 of 3003
};

// Two dropped boxes, the upper one tilted, 1 s at 1/120 s: a few milliseconds per run.
constexpr const char* kCheapScene = R"({
  "name": "tilted_drop",
  "gravity": [0, 0, -9.81],
  "ground": {"normal": [0, 0, 1], "offset": 0},
  "material": {"friction": 0.5, "restitution": 0.0},
  "bodies": [
    {"name": "low", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5]},
    {"name": "high", "mass": 1, "half_extents": [0.5, 0.3, 0.2], "position": [0.3, 0, 1.8],
     "orientation": [0.97, 0.2, 0.1, 0]}
  ],
  "time": {"dt": 0.008333333333333333, "duration": 1.0}
})";

const OutcomePair& pair_of(const OutcomeStatistics& s, const std::string& a, const std::string& b) {
  for (const OutcomePair& p : s.pairs) {
    if (p.a == a && p.b == b) return p;
  }
  FAIL("no pair " << a << " - " << b);
  return s.pairs.front();
}

}  // namespace

TEST_CASE("the exact two-sample Kolmogorov-Smirnov p-value is the share of the orderings counted", "[outcomes]") {
  for (const ExactKs& k : kExactKs) {
    INFO("n " << k.n << ", m " << k.m << ", D " << k.d);
    CHECK(ks_exact_p(k.d, k.n, k.m) == Approx(k.p).epsilon(1e-12));
    CHECK(ks_exact_p(k.d, k.m, k.n) == Approx(k.p).epsilon(1e-12));
  }
  // n = m, D = 1: only the two orderings with one sample wholly below, 2 / C(2n, n).
  CHECK(ks_exact_p(1.0, 10, 10) == Approx(2.0 / 184756.0).epsilon(1e-9));
  CHECK(ks_exact_p(0.0, 5, 5) == 1.0);
}

TEST_CASE("the two-sample Kolmogorov-Smirnov statistic of known samples", "[outcomes]") {
  const KsResult apart = kolmogorov_smirnov({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10});
  CHECK(apart.statistic == Approx(1.0));
  CHECK(apart.p_value == Approx(1.0 / 126.0).epsilon(1e-12));
  CHECK(apart.exact);
  // Interleaved one by one: the distributions never part by more than one step, D = 1/5.
  const KsResult mixed = kolmogorov_smirnov({1, 3, 5, 7, 9}, {2, 4, 6, 8, 10});
  CHECK(mixed.statistic == Approx(0.2));
  CHECK(mixed.p_value == Approx(1.0));
  // Identical samples, ties and all: D = 0.
  const KsResult same = kolmogorov_smirnov({1, 1, 2, 3}, {1, 1, 2, 3});
  CHECK(same.statistic == 0.0);
  CHECK(same.p_value == 1.0);
  // {1, 2} against {2, 3}: at 1, 1/2 against 0; at 2, 1 against 1/2 (the tie moves both): D = 1/2.
  CHECK(kolmogorov_smirnov({1, 2}, {2, 3}).statistic == Approx(0.5));
  // Large samples take Kolmogorov's limit: 600 values against the same shifted by half their range.
  std::vector<double> a, b;
  for (int i = 0; i < 600; ++i) {
    a.push_back(i);
    b.push_back(i + 300);
  }
  const KsResult large = kolmogorov_smirnov(a, b);
  CHECK_FALSE(large.exact);
  CHECK(large.statistic == Approx(0.5));
  CHECK(large.p_value < 1e-30);
}

TEST_CASE("Kolmogorov's limit at its tabled critical values", "[outcomes]") {
  // The asymptotic critical values of the Kolmogorov distribution: Q = 0.10, 0.05, 0.01.
  CHECK(kolmogorov_q(1.22385) == Approx(0.10).margin(2e-5));
  CHECK(kolmogorov_q(1.35810) == Approx(0.05).margin(2e-5));
  CHECK(kolmogorov_q(1.62762) == Approx(0.01).margin(2e-5));
  CHECK(kolmogorov_q(0.0) == 1.0);
}

TEST_CASE("Student's t tail against its closed forms and table", "[outcomes]") {
  // df = 1 (Cauchy): P(|T| >= t) = 1 - 2 atan(t) / pi.
  CHECK(student_t_two_sided_p(1.0, 1.0) == Approx(0.5).epsilon(1e-12));
  CHECK(student_t_two_sided_p(3.0, 1.0) == Approx(1.0 - 2.0 * std::atan(3.0) / std::numbers::pi).epsilon(1e-12));
  // df = 2: P(|T| >= t) = 1 - t / sqrt(t^2 + 2).
  CHECK(student_t_two_sided_p(2.0, 2.0) == Approx(1.0 - 2.0 / std::sqrt(6.0)).epsilon(1e-12));
  // The table's two-sided 5% point for df = 10.
  CHECK(student_t_two_sided_p(2.228138851986, 10.0) == Approx(0.05).epsilon(1e-9));
  CHECK(student_t_two_sided_p(0.0, 7.0) == Approx(1.0));
  CHECK(regularized_incomplete_beta(0.3, 1.0, 1.0) == Approx(0.3).epsilon(1e-14));
  CHECK(regularized_incomplete_beta(0.3, 2.0, 1.0) == Approx(0.09).epsilon(1e-14));  // x^a for b = 1
}

TEST_CASE("Welch's test on a published example", "[outcomes]") {
  // Two samples of 15 with unequal spreads (the first example of Wikipedia's "Welch's t-test"):
  // t = -2.46, 24.99 degrees of freedom, p = 0.021.
  const std::vector<double> a1 = {27.5, 21.0, 19.0, 23.6, 17.0, 17.9, 16.9, 20.1, 21.9, 22.6, 23.1, 19.6, 19.0, 21.7, 21.4};
  const std::vector<double> a2 = {27.1, 22.0, 20.8, 23.4, 23.4, 23.5, 25.8, 22.0, 24.8, 20.2, 21.9, 22.1, 22.9, 20.5, 24.4};
  const WelchResult w = welch_t_test(a1, a2);
  CHECK(w.t == Approx(-2.455356).epsilon(1e-6));
  CHECK(w.df == Approx(24.98853).epsilon(1e-6));
  CHECK(w.p_value == Approx(0.021378).epsilon(1e-4));
  // No spread at all: equal means agree, different ones differ.
  CHECK(welch_t_test({2, 2, 2}, {2, 2}).p_value == 1.0);
  CHECK(welch_t_test({2, 2, 2}, {3, 3}).p_value == 0.0);
  CHECK(welch_t_test({2}, {3, 4}).p_value == 1.0);  // too few values to test
  const SampleSummary s = summarize({1, 2, 3, 4});
  CHECK(s.mean == Approx(2.5));
  CHECK(s.sd == Approx(std::sqrt(5.0 / 3.0)));
  CHECK(s.min == 1.0);
  CHECK(s.max == 4.0);
}

TEST_CASE("the outcome measures of a run's end by hand", "[outcomes]") {
  const Scene scene = parse_scene(R"({
    "name": "two_stacked", "gravity": [0, 0, -10], "ground": {"normal": [0, 0, 1], "offset": 0},
    "bodies": [{"name": "a", "mass": 2, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5]},
               {"name": "b", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 1.5]}],
    "time": {"dt": 0.01, "duration": 1}})", "two_stacked");
  std::vector<BodyState> start(2), end(2);
  start[0].position = {0, 0, 0.5};
  start[1].position = {0, 0, 1.5};
  start[1].velocity = {3, 0, 0};  // 1/2 m v^2 = 4.5 J of kinetic energy at the start
  // The stack moved 0.3 m along x and 0.4 m along y, at rest.
  end[0].position = {0.3, 0.4, 0.5};
  end[1].position = {0.3, 0.4, 1.5};
  std::map<std::string, double> m = outcome_measures(scene, start, end);
  CHECK(m.at("stacked") == 1.0);            // b rests on a
  CHECK(m.at("tallest") == Approx(2.0));    // b's top face
  CHECK(m.at("com_shift") == Approx(0.5));  // |(0.3, 0.4)|
  CHECK(m.at("spread") == Approx(0.0).margin(1e-15));
  CHECK(m.at("energy_lost") == Approx(4.5));
  // b knocked off beside a, 1 m along x, resting on the ground; it fell 1 m: 10 J of potential energy.
  end[1].position = {1.3, 0.4, 0.5};
  m = outcome_measures(scene, start, end);
  CHECK(m.at("stacked") == 0.0);
  CHECK(m.at("tallest") == Approx(1.0));
  // The centre of mass (2 at x 0.3, 1 at x 1.3): x 0.6333, y 0.4; the bodies 1/3 and 2/3 m from it.
  CHECK(m.at("com_shift") == Approx(std::hypot(0.3 + 1.0 / 3.0, 0.4)));
  CHECK(m.at("spread") == Approx(std::sqrt((1.0 / 9.0 + 4.0 / 9.0) / 2.0)));
  CHECK(m.at("energy_lost") == Approx(14.5));
}

TEST_CASE("perturbed starts move each free body by the stated distance across gravity", "[outcomes]") {
  const Scene scene = parse_scene(kCheapScene, "tilted_drop");
  const Scene a = perturbed_start(scene, 1e-3, 1, 0);
  const Scene again = perturbed_start(scene, 1e-3, 1, 0);
  const Scene b = perturbed_start(scene, 1e-3, 1, 1);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Vec3 move = a.bodies[i].frame.position - scene.bodies[i].frame.position;
    CHECK(move.norm() == Approx(1e-3).epsilon(1e-9));
    CHECK(std::abs(move.z()) < 1e-15);
    CHECK(again.bodies[i].frame.position == a.bodies[i].frame.position);
    CHECK((b.bodies[i].frame.position - a.bodies[i].frame.position).norm() > 1e-6);
  }
}

TEST_CASE("an engine run twice does not differ from itself; a biased one differs beyond the spread", "[outcomes]") {
  const Scene scene = parse_scene(kCheapScene, "tilted_drop");
  OutcomeSettings s;
  s.starts = 8;
  s.perturbation = 1e-2;
  // The same engine twice, and once biased on purpose: our penalty method with soft springs, 1e3
  // N/m per contact point, on which the boxes rest sunk by millimetres (m g / (n k): 2.5 mm for
  // the upper box on four points), where the starts spread the tallest stack by 0.05 mm.
  const std::vector<OutcomeEntry> entries = {{"own", "own", nlohmann::json::object()},
                                             {"own again", "own", nlohmann::json::object()},
                                             {"soft springs", "own-penalty", {{"stiffness", 1e3}}}};
  const OutcomeStatistics r = run_outcomes(scene, entries, s);
  REQUIRE(r.engines.size() == 3);
  REQUIRE(r.pairs.size() == 3);
  for (const EngineOutcomes& e : r.engines) {
    CHECK(e.non_finite == 0);
    CHECK(e.samples.at("energy_lost").size() == 8u);
  }
  // The starts spread the outcomes: the centre of mass's shift varies from start to start.
  CHECK(r.engines[0].summary.at("com_shift").sd > 1e-4);
  const OutcomePair& same = pair_of(r, "own", "own again");
  CHECK_FALSE(same.differ);
  CHECK(same.verdict() == "within chaos");
  // Start by start: the same engine from the same start gives the same outcome every time.
  CHECK(same.starts_compared == 8);
  CHECK(same.starts_agreeing == 8);
  for (const MeasureTest& t : same.tests) {
    INFO(t.measure);
    CHECK(t.ks.statistic == 0.0);
    CHECK(t.ks.p_value == 1.0);
  }
  INFO(outcomes_markdown(r));
  const OutcomePair& biased = pair_of(r, "own", "soft springs");
  CHECK(biased.differ);
  CHECK(biased.verdict() == "differ beyond their own spread");
  // The soft springs' 2.5 mm sink is fifty times the spread the starts cause: no start agrees.
  CHECK(biased.starts_compared == 8);
  CHECK(biased.starts_agreeing == 0);
  // compare's verdict: a pair that chaos would explain by its trajectories, but whose outcomes
  // differ beyond their spread, is "differ", naming the measures; one within chaos stays "chaos".
  std::vector<PairComparison> pairs(2);
  pairs[0].difference.a = "own";
  pairs[0].difference.b = "soft springs";
  pairs[1].difference.a = "own again";
  pairs[1].difference.b = "own";
  for (PairComparison& p : pairs) p.verdict = "chaos";
  judge_chaos_by_outcomes(r, pairs);
  CHECK(pairs[0].verdict == "differ");
  CHECK(pairs[0].beyond_chaos.find("the outcomes over 8 perturbed starts differ beyond their own spread (") == 0);
  CHECK(pairs[0].beyond_chaos.find("tallest") != std::string::npos);
  CHECK(pairs[0].starts_agreeing == 0);
  CHECK(pairs[1].verdict == "chaos");
  CHECK(pairs[1].starts_agreeing == 8);
  CHECK(pairs[1].beyond_chaos.empty());
  bool tallest_differs = false;
  for (const MeasureTest& t : biased.tests) {
    if (t.measure == "tallest") tallest_differs = t.differ;
  }
  CHECK(tallest_differs);
  // The report's shape.
  const nlohmann::json j = outcomes_json(r);
  CHECK(j.at("starts") == 8);
  CHECK(j.at("pairs").size() == 3u);
  CHECK(j.at("pairs").at(0).at("verdict") == "within chaos");
  CHECK(outcomes_markdown(r).find("differ beyond their own spread") != std::string::npos);
}
