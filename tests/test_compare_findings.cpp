// compare's findings (validation/compare_findings.hpp): each rule on runs built by hand, where the
// answer is known, and on the runs where a reader needed it named: the tutorial's two boxes at
// dt 0.1 s (Bullet leaves first and goes 1.62 m into the ground) and the bone scene (our impulse
// method loses more in the first impact than the others).
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/compare.hpp"
#include "boxpile/validation/compare_findings.hpp"
#include "boxpile/tests/support/work_dir.hpp"

using namespace boxpile;
using namespace boxpile::test;

namespace {

std::vector<CompareFinding> of_kind(const std::vector<CompareFinding>& all, const std::string& kind) {
  std::vector<CompareFinding> out;
  std::copy_if(all.begin(), all.end(), std::back_inserter(out), [&](const CompareFinding& f) { return f.kind == kind; });
  return out;
}

// A run named `engine` with the energy series e(t) at 100 frames over 1 s and its deepest
// penetration.
EngineRun run_of(const std::string& engine, double (*energy)(double), double deepest) {
  EngineRun run;
  run.engine = engine;
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.01 * k;
    run.recording.frames.t.push_back(t);
    run.recording.frames.energy.push_back(energy(t));
    run.recording.frames.kinetic.push_back(10.0);  // 10 J in motion throughout
  }
  run.energy_initial = energy(0.0);
  run.deepest.depth = deepest;
  run.measures.smallest_edge = 1.0;  // unit cubes, as the checks measure the scene
  run.deepest_t = 0.5;
  return run;
}

PairComparison pair_of(const std::string& a, const std::string& b, std::optional<double> passes) {
  PairComparison p;
  p.difference.a = a;
  p.difference.b = b;
  p.difference.position_passes = passes;
  return p;
}

CompareResult three_engines() {
  CompareResult r;
  r.runs = {run_of("a", [](double) { return 100.0; }, 1e-3), run_of("b", [](double) { return 100.0; }, 1.2e-3),
            run_of("c", [](double t) { return t < 0.3 ? 100.0 : 97.0; }, 5e-3)};
  r.baselines.resize(3);
  return r;
}

}  // namespace

TEST_CASE("findings: the engine whose energy leaves the median by a tenth of the energy in motion", "[compare][findings]") {
  // c loses 3 J at 0.3 s and stays there: 0.3 of the 10 J in motion, over the 0.1 limit (1 J), and
  // over the floor (1e-3 of 100 J). a and b sit on the median.
  CompareResult r = three_engines();
  const auto energy = of_kind(compare_findings(r), "energy");
  REQUIRE(energy.size() == 1);
  CHECK(energy[0].engine == "c");
  CHECK(*energy[0].t == Approx(0.3));
  CHECK_THAT(energy[0].what, Catch::Contains("3 J lower"));
  // A loss of 0.9 J is under the limit; a gap that closes again within 0.2 s is an impact's timing.
  r.runs[2] = run_of("c", [](double t) { return t < 0.3 ? 100.0 : 99.1; }, 5e-3);
  CHECK(of_kind(compare_findings(r), "energy").empty());
  r.runs[2] = run_of("c", [](double t) { return t >= 0.3 && t < 0.45 ? 97.0 : 100.0; }, 5e-3);
  CHECK(of_kind(compare_findings(r), "energy").empty());
  // Past the first self-divergence (chaos), a parting counts only if the gap is still open at the end.
  r.runs[2] = run_of("c", [](double t) { return t < 0.3 ? 100.0 : 97.0; }, 5e-3);
  r.baselines[0].divergence.position_passes = 0.2;
  const auto late = of_kind(compare_findings(r), "energy");
  REQUIRE(late.size() == 1);
  CHECK_THAT(late[0].what, Catch::StartsWith("total energy ends apart"));
}

TEST_CASE("findings: a penetration past 1% of the smallest edge and 3 times the median", "[compare][findings]") {
  CompareResult r = three_engines();
  // c: 5 mm, 4.2 times the median 1.2 mm, but under 1% of the 1 m edge (10 mm): nothing.
  CHECK(of_kind(compare_findings(r), "penetration").empty());
  r.runs[2].deepest.depth = 0.05;  // 50 mm: 42 times the median, past 10 mm
  const auto deep = of_kind(compare_findings(r), "penetration");
  REQUIRE(deep.size() == 1);
  CHECK(deep[0].engine == "c");
  r.runs[2].deepest.depth = 3.5e-3;  // 2.9 times the median: not far past it
  r.runs[0].deepest.depth = r.runs[1].deepest.depth = 1.2e-3;
  CHECK(of_kind(compare_findings(r), "penetration").empty());
}

TEST_CASE("findings: the odd one out leaves every other engine before any two others part", "[compare][findings]") {
  CompareResult r = three_engines();
  r.pairs = {pair_of("a", "b", 0.9), pair_of("a", "c", 0.2), pair_of("b", "c", 0.3)};
  auto odd = of_kind(compare_findings(r), "odd_one_out");
  REQUIRE(odd.size() == 1);
  CHECK(odd[0].engine == "c");
  CHECK(*odd[0].t == Approx(0.3));  // when it had left both
  // a and b part at 0.25 s, before c has left b (0.3 s): then a, which left both by 0.25 s while
  // b and c agreed until 0.3 s, is the one.
  r.pairs[0].difference.position_passes = 0.25;
  odd = of_kind(compare_findings(r), "odd_one_out");
  REQUIRE(odd.size() == 1);
  CHECK(odd[0].engine == "a");
  // All part at once: nobody is the odd one out.
  for (PairComparison& p : r.pairs) p.difference.position_passes = 0.2;
  CHECK(of_kind(compare_findings(r), "odd_one_out").empty());
  // c never leaves b: not the odd one out either.
  r.pairs = {pair_of("a", "b", std::nullopt), pair_of("a", "c", 0.2), pair_of("b", "c", std::nullopt)};
  CHECK(of_kind(compare_findings(r), "odd_one_out").empty());
}

TEST_CASE("findings: an engine that alone fails a check the others pass", "[compare][findings]") {
  CompareResult r = three_engines();
  const SceneCheckResult pass{"rest_move", 1e-5, 1e-3, false, true, "m", "rest", ""};
  const SceneCheckResult fail{"rest_move", 2e-3, 1e-3, false, false, "m", "rest", ""};
  r.runs[0].checks = {pass};
  r.runs[1].checks = {pass};
  r.runs[2].checks = {fail};
  const std::vector<CompareFinding> all = compare_findings(r);
  CHECK(of_kind(all, "check").size() == 3);
  const auto odd = of_kind(all, "odd_check");
  REQUIRE(odd.size() == 1);
  CHECK(odd[0].engine == "c");
  CHECK_THAT(odd[0].what, Catch::Contains("rest_move 0.002 m > 0.001"));
  r.runs[1].checks = {fail};  // two fail it: no odd one
  CHECK(of_kind(compare_findings(r), "odd_check").empty());
}

TEST_CASE("findings name Bullet on the tutorial's two boxes at dt 0.1 s", "[compare][findings]") {
  const Scene scene = parse_scene(R"({"name": "two_drop", "ground": {"normal": [0, 0, 1], "offset": 0},
    "effects": ["gravity", "friction"],
    "bodies": [
      {"name": "low", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5]},
      {"name": "high", "mass": 1, "half_extents": [0.3, 0.3, 0.3], "position": [0.1, 0, 1.5],
       "orientation": [0.96, 0.2, 0.2, 0]}],
    "time": {"dt": 0.1, "duration": 2}})",
                                  "two_drop.json");
  CompareSettings settings;
  settings.engines = {"own", "ode", "bullet"};
  const CompareResult r = run_compare(scene, settings);
  for (const char* kind : {"odd_one_out", "energy", "penetration"}) {
    INFO(kind);
    const auto found = of_kind(r.findings, kind);
    REQUIRE(found.size() == 1);
    CHECK(found[0].engine == "bullet");
  }
  // Bullet's box ends 1.62 m deep at this step (measured; dt 0.1 s is 24 times the usual).
  const auto bullet = std::find_if(r.runs.begin(), r.runs.end(), [](const EngineRun& e) { return e.engine == "bullet"; });
  CHECK(bullet->deepest.depth == Approx(1.62).margin(0.02));
}

TEST_CASE("findings name our impulse method's larger loss in the bone's first impact", "[compare][findings]") {
  Scene scene = fixture("bone_hits_pile");
  scene.time.duration = 2.0;
  CompareSettings settings;
  settings.engines = {"own-impulse", "own-penalty", "ode", "bullet"};
  const CompareResult r = run_compare(scene, settings);
  const auto energy = of_kind(r.findings, "energy");
  REQUIRE(energy.size() == 1);
  CHECK(energy[0].engine == "own-impulse");
  CHECK(*energy[0].t == Approx(1.833).margin(0.02));  // the bone meets the pile
  CHECK_THAT(energy[0].what, Catch::Contains("J lower"));
}
