// `boxpile compare` and its pieces: the report on a stack of five has every field, its settled
// heights agree with `boxpile run`, the plots are SVG, stacks are found through the contact graph,
// and a report directory is complete or absent.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/compare/compare.hpp"
#include "boxpile/validation/core/plots.hpp"
#include "boxpile/validation/replay/replay_data.hpp"
#include "boxpile/validation/compare/report.hpp"
#include "boxpile/validation/core/report_directory.hpp"
#include "boxpile/validation/rulers/stacks.hpp"
#include "boxpile/validation/rulers/wire_check.hpp"
#include "boxpile/tests/support/engine_scenes.hpp"
#include "boxpile/tests/support/work_dir.hpp"

using namespace boxpile;
using namespace boxpile::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Every key docs/compare.md fixes for other tools, present with the right type.
void check_report_keys(const json& r, const std::vector<std::string>& engines) {
  CHECK(r.at("scene").is_string());
  CHECK(r.at("dt").is_number());
  CHECK(r.at("duration").is_number());
  // Findings: every engine's checks at least (each scene has the default ones), each finding
  // naming an engine that ran.
  REQUIRE(r.at("findings").is_array());
  CHECK(r.at("findings").size() >= engines.size());
  for (const json& f : r.at("findings")) {
    CHECK(std::find(engines.begin(), engines.end(), f.at("engine").get<std::string>()) != engines.end());
    CHECK(f.at("kind").is_string());
    CHECK(f.at("what").is_string());
    CHECK((f.at("t").is_number() || f.at("t").is_null()));
  }
  REQUIRE(r.at("engines").size() == engines.size());
  for (const std::string& name : engines) {
    INFO("engine " << name);
    const json& e = r.at("engines").at(name);
    CHECK(e.at("final").at("t").is_number());
    REQUIRE(!e.at("final").at("bodies").empty());
    for (const json& b : e.at("final").at("bodies")) {
      CHECK(b.at("name").is_string());
      CHECK(b.at("position").size() == 3);
      CHECK(b.at("orientation").size() == 4);
      CHECK(b.at("velocity").size() == 3);
      CHECK(b.at("angular_velocity").size() == 3);
    }
    for (const json& s : e.at("stacks")) {
      CHECK(s.at("bodies").is_array());
      CHECK(s.at("height").is_number());
      CHECK(s.contains("ideal"));
      CHECK(s.contains("error"));
    }
    CHECK(e.at("us_per_step").is_number());
    CHECK(e.at("max_penetration").is_number());
    CHECK(e.at("energy").at("initial").is_number());
    CHECK(e.at("energy").at("final").is_number());
    CHECK(e.at("energy").at("max").is_number());
    CHECK(e.at("events").is_array());
  }
  CHECK(r.at("pairs").is_array());
  CHECK(r.at("contacts").is_array());
}

// A plot is its data, its script and a well-formed SVG document.
void check_plot(const fs::path& dir, const std::string& name) {
  INFO("plot " << name);
  CHECK(fs::file_size(dir / (name + ".dat")) > 0);
  CHECK(read(dir / (name + ".gp")).find(name + ".svg") != std::string::npos);
  const std::string svg = read(dir / (name + ".svg"));
  const bool starts = svg.rfind("<?xml", 0) == 0 || svg.rfind("<svg", 0) == 0;
  CHECK(starts);
  CHECK(svg.find("<svg") != std::string::npos);
  const auto end = svg.rfind("</svg>");
  REQUIRE(end != std::string::npos);
  CHECK(svg.find_first_not_of(" \t\r\n", end + 6) == std::string::npos);  // nothing after it
}

}  // namespace

TEST_CASE("compare on a stack of five gives every field of the report", "[compare]") {
  Scene scene = fixture("stack_5");
  scene.time.duration = 0.5;
  const CompareResult r = run_compare(scene, CompareSettings{});
  REQUIRE(r.runs.size() == 3);
  REQUIRE(r.baselines.size() == 3);
  REQUIRE(r.pairs.size() == 3);  // own-ode, own-bullet, ode-bullet
  CHECK_FALSE(r.contacts.empty());
  REQUIRE(r.start_stacks.size() == 1);
  CHECK(r.start_stacks[0].bodies.size() == 5);
  CHECK(r.start_stacks[0].height == Approx(5.0).margin(1e-12));

  for (const EngineRun& run : r.runs) {
    INFO("engine " << run.engine);
    CHECK(run.steps == 120);
    CHECK(run.recording.frames.t.size() == 31);  // every 4 steps at 60 frames per second, and the start
    CHECK(run.energy_initial == Approx(122.625).margin(1e-9));  // 9.81 * (0.5 + ... + 4.5)
    CHECK(run.finite);
    // A resting stack stays one stack of five, settled within a millimetre of 5 m.
    REQUIRE(run.stacks.size() == 1);
    CHECK(run.stacks[0].bodies.size() == 5);
    REQUIRE(run.stacks[0].ideal);
    CHECK(*run.stacks[0].ideal == Approx(5.0).margin(1e-12));
    REQUIRE(run.stacks[0].error);
    CHECK(std::abs(*run.stacks[0].error) < 1e-3);
    CHECK(run.deepest.depth < 1e-3);
  }
  for (const PairComparison& p : r.pairs) {
    INFO(p.difference.a << " vs " << p.difference.b);
    CHECK(p.verdict == "agree");  // nothing moves more than 1 cm
    CHECK(p.difference.t.size() == 31);
    CHECK(p.difference.bodies.size() == 5);
  }
  check_report_keys(report_json(r), {"own", "ode", "bullet"});
}

TEST_CASE("compare's settled stack heights match those of boxpile run, and its plots are SVG", "[compare][cli]") {
  const fs::path dir = scratch("compare_vs_run");
  const std::string scene = std::string(BOXPILE_FIXTURES_DIR) + "/scenes/stack_5.json";
  REQUIRE(run_boxpile("compare " + scene + " --duration 1 --report " + (dir / "report").string()) == 0);
  const json report = json::parse(read(dir / "report" / "report.json"));
  check_report_keys(report, {"own", "ode", "bullet"});
  for (const std::string name : {"energy", "penetration", "stack_height", "position_difference"}) {
    check_plot(dir / "report", name);
  }
  CHECK(read(dir / "report" / "report.md").find("![energy](energy.svg)") != std::string::npos);

  for (const std::string engine : {"own", "ode", "bullet"}) {
    INFO("engine " << engine);
    const fs::path out = dir / (engine + ".json");
    REQUIRE(run_boxpile("run " + scene + " --engine " + engine + " --duration 1 --out " + out.string()) == 0);
    const json run = json::parse(read(out));
    // The top of the stack from `run`'s final state: the top box's highest vertex, its centre's
    // height plus 0.5 (|R_zx| + |R_zy| + |R_zz|).
    const json& top = run.at("final").at("bodies").at(4);
    const json& q = top.at("orientation");
    const Quat orientation(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
    const double height =
        top.at("position")[2].get<double>() + 0.5 * orientation.toRotationMatrix().row(2).cwiseAbs().sum();
    const json& stacks = report.at("engines").at(engine).at("stacks");
    REQUIRE(stacks.size() == 1);
    CHECK(stacks[0].at("height").get<double>() == Approx(height).margin(1e-12));
    CHECK(stacks[0].at("error").get<double>() == Approx(height - 5.0).margin(1e-12));
  }
}

TEST_CASE("every engine reports the impact of a dropped box, at the speed of the fall", "[compare]") {
  // The bounce fixture: a unit box dropped flat from 1 m lands at t = sqrt(2 h / g) = 0.4515 s at
  // v = sqrt(2 g h) = 4.43 m/s. Ours reports it from its solver, ODE's and Bullet's are found from
  // their contact sets; a few steps of integration error either way (dt = 1/240 s).
  Scene scene = fixture("bounce");
  scene.time.duration = 0.6;
  const double g = 9.81, h = 1.0;
  for (const char* engine : {"own", "ode", "bullet"}) {
    DYNAMIC_SECTION(engine) {
      const EngineRun run = run_engine(scene, engine, CompareSettings{});
      REQUIRE_FALSE(run.events.empty());
      const ImpactEvent& first = run.events.front();
      CHECK(first.body_a == 0);
      CHECK(first.body_b == kGround);
      CHECK(first.t == Approx(std::sqrt(2 * h / g)).margin(3 * scene.time.dt));
      CHECK(first.approach_speed == Approx(std::sqrt(2 * g * h)).epsilon(0.03));
      CHECK(first.impulse.has_value() == (std::string(engine) == "own"));
    }
  }
}

TEST_CASE("stacks are found through the contact graph from the ground", "[compare][stacks]") {
  // Two towers of two 1 m cubes 3 m apart, a cube floating above them, and a cube on a wire
  // touching the top of the first tower.
  Scene s = fixture("stack_5");
  s.bodies.resize(2);
  s.bodies[1].frame.position = Vec3(0, 0, 1.5);
  BodyDesc b = s.bodies[0];
  b.name = "c0";
  b.frame.position = Vec3(3, 0, 0.5);
  s.bodies.push_back(b);
  b.name = "c1";
  b.frame.position = Vec3(3, 0, 1.5);
  s.bodies.push_back(b);
  b.name = "floating";
  b.frame.position = Vec3(3, 0, 4.0);
  s.bodies.push_back(b);
  b.name = "hanging";
  b.frame.position = Vec3(0, 0, 2.5);
  b.wire = Wire{Vec3(-1, 0, 3), Vec3(1, 0, 3), Vec3(0, 0, 0.5)};
  s.bodies.push_back(b);

  const std::vector<RigidBody> bodies = make_bodies(s);
  const std::vector<Stack> stacks = find_stacks(bodies, s);
  REQUIRE(stacks.size() == 2);
  CHECK(stacks[0].bodies == std::vector<int>{0, 1});
  CHECK(stacks[0].height == Approx(2.0));
  CHECK(stacks[1].bodies == std::vector<int>{2, 3});

  // A stack that is the same set of bodies as at the start gets its start height as ideal.
  std::vector<RigidBody> later = bodies;
  later[1].x.z() -= 1e-4;  // settled a little
  const std::vector<StackReport> reports = report_stacks(find_stacks(later, s), stacks, later);
  REQUIRE(reports.size() == 2);
  CHECK(reports[0].bodies == std::vector<std::string>{"b0", "b1"});
  REQUIRE(reports[0].error);
  CHECK(*reports[0].error == Approx(-1e-4).margin(1e-12));

  // The top cube knocked off: the tower of two is gone; what is left are columns of one cube, each
  // with its own height (1 m) as ideal.
  later[1].x = Vec3(0, 5, 0.5);
  const std::vector<StackReport> knocked = report_stacks(find_stacks(later, s), stacks, later);
  REQUIRE(knocked.size() == 3);
  REQUIRE(knocked[0].ideal);
  CHECK(*knocked[0].ideal == Approx(1.0).margin(1e-12));
  CHECK(*knocked[0].error == Approx(0.0).margin(1e-12));
}

TEST_CASE("A column of boxes that was no stack at the start gets the sum of its boxes' heights as ideal",
          "[compare]") {
  // stack_10: ten unit cubes, the top's centre at 9.5 m, its top at 10 m: the column height.
  const Scene ten = fixture("stack_10");
  const std::vector<RigidBody> tower = make_bodies(ten);
  const std::vector<Stack> stacks = find_stacks(tower, ten);
  REQUIRE(stacks.size() == 1);
  REQUIRE(stacks[0].column_height);
  CHECK(*stacks[0].column_height == Approx(10.0).margin(1e-12));
  CHECK(tower[9].x.z() == Approx(9.5).margin(1e-12));

  // Two boxes dropped onto each other (as docs/tutorial.md's two_drop): at the start the upper one
  // is in the air, so the stack of two at the end is no start stack; it ends turned a quarter turn
  // about x, its 0.4 m half extent along z, on the lower cube: ideal 1 + 0.8 m.
  Scene s = fixture("stack_5");
  s.bodies.resize(2);
  s.bodies[1].boxes[0].half_extents = Vec3(0.3, 0.4, 0.3);
  s.bodies[1].frame.position = Vec3(0.1, 0, 2.0);
  const std::vector<RigidBody> start = make_bodies(s);
  const std::vector<Stack> at_start = find_stacks(start, s);
  REQUIRE(at_start.size() == 1);  // the lower box alone
  std::vector<RigidBody> end = start;
  end[1].q = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
  end[1].x = Vec3(0.1, 0, 1.0 + 0.4 - 2e-5);  // its 0.4 half extent now along z, 20 um into the lower
  const std::vector<StackReport> reports = report_stacks(find_stacks(end, s), at_start, end);
  REQUIRE(reports.size() == 1);
  REQUIRE(reports[0].ideal);
  CHECK(*reports[0].ideal == Approx(1.8).margin(1e-12));
  CHECK(*reports[0].error == Approx(-2e-5).margin(1e-9));

  // Two boxes apart on the ground are two stacks of one, each its own column.
  end[1].q = Quat::Identity();
  end[1].x = Vec3(3, 0, 0.3);
  const std::vector<StackReport> apart = report_stacks(find_stacks(end, s), at_start, end);
  REQUIRE(apart.size() == 2);
  REQUIRE(apart[1].ideal);
  CHECK(*apart[1].ideal == Approx(0.6).margin(1e-12));

  // A cube across two cubes side by side is no column (two boxes on the ground): no ideal.
  Scene bridge = fixture("stack_5");
  bridge.bodies.resize(3);
  bridge.bodies[1].frame.position = Vec3(1.0, 0, 0.5);
  bridge.bodies[2].frame.position = Vec3(0.5, 0, 1.5);
  std::vector<RigidBody> pose = make_bodies(bridge);
  pose[2].x.z() += 0.5;  // in the air at the start
  const std::vector<Stack> bridge_start = find_stacks(pose, bridge);
  pose[2].x.z() -= 0.5;
  const std::vector<Stack> bridged = find_stacks(pose, bridge);
  REQUIRE(bridged.size() == 1);
  CHECK(bridged[0].bodies.size() == 3);
  CHECK_FALSE(bridged[0].column_height);
  CHECK_FALSE(report_stacks(bridged, bridge_start, pose)[0].ideal);
}

TEST_CASE("the perturbed start moves every free body by the perturbation, on its wire for the bone",
          "[compare]") {
  const Scene scene = fixture("bone_hits_pile");
  const Scene moved = perturbed_scene(scene, 1e-9);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& a = scene.bodies[i];
    const BodyDesc& b = moved.bodies[i];
    CHECK((a.frame.position - b.frame.position).norm() == Approx(1e-9).epsilon(1e-6));
    CHECK(std::abs(a.frame.position.z() - b.frame.position.z()) < (a.wire ? 1e-9 : 1e-15));
    if (a.wire) CHECK(wire_gap(*a.wire, BodyState{a.name, b.frame.position, b.frame.orientation, {}, {}}).off < 1e-15);
  }
}

TEST_CASE("a report directory is complete or absent", "[compare][report]") {
  const fs::path dir = scratch("report_directory");

  SECTION("nothing is left when the report is abandoned") {
    {
      ReportDirectory report(dir / "abandoned");
      std::ofstream(report.staging() / "report.json") << "{}";
    }
    CHECK_FALSE(fs::exists(dir / "abandoned"));
    CHECK(fs::is_empty(dir));
  }
  SECTION("a committed report replaces the previous one whole") {
    for (const char* content : {"first", "second"}) {
      ReportDirectory report(dir / "r");
      std::ofstream(report.staging() / "report.json") << content;
      report.commit();
    }
    CHECK(read(dir / "r" / "report.json") == "second");
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);  // no leftovers
  }
  SECTION("a path under a file cannot be a report directory") {
    std::ofstream(dir / "file") << "x";
    CHECK_THROWS_AS(ReportDirectory(dir / "file" / "r"), ReportDirectoryError);
    CHECK_THROWS_AS(ReportDirectory(dir / "file"), ReportDirectoryError);
  }
  SECTION("a directory that holds something else is left alone") {
    fs::create_directories(dir / "mine");
    std::ofstream(dir / "mine" / "notes.txt") << "keep me";
    CHECK_THROWS_WITH(ReportDirectory(dir / "mine"), Catch::Contains("not a boxpile report"));
    CHECK(read(dir / "mine" / "notes.txt") == "keep me");
  }
}

TEST_CASE("bad input to boxpile compare exits with 2 and writes no report", "[compare][cli]") {
  const fs::path dir = scratch("compare_bad_input");
  const std::string scene = std::string(BOXPILE_FIXTURES_DIR) + "/scenes/stack_5.json";
  const std::string report = (dir / "report").string();
  CHECK(run_boxpile("compare " + scene + " --engines own,physx --duration 0.1 --report " + report) == 2);
  CHECK(run_boxpile("compare " + (dir / "missing.json").string() + " --duration 0.1 --report " + report) == 2);
  std::ofstream(dir / "file") << "x";
  CHECK(run_boxpile("compare " + scene + " --duration 0.1 --report " + (dir / "file" / "report").string()) == 2);
  CHECK(run_boxpile("compare " + scene + " --dt -1 --report " + report) == 2);
  // Nothing but the file made above: no report, no staging directory.
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("an engine has one colour in a 2-engine and a 4-engine compare's plots and replay data", "[compare]") {
  Scene scene = fixture("stack_5");
  scene.time.duration = 0.05;
  // The colour of every series titled `engine` in the plots, and of its replay data.
  const auto colours_of = [&scene](const CompareResult& r, const std::string& engine) {
    std::set<std::string> colours;
    for (const PlotSpec& p : report_plots(r))
      for (const PlotSeries& s : p.series)
        if (s.title == engine) colours.insert(s.colour);
    std::vector<const Recording*> runs;
    for (const EngineRun& run : r.runs) runs.push_back(&run.recording);
    const json data = replay_data(scene.name, runs, {});  // a range over a temporary's member would dangle
    for (const json& e : data.at("engines"))
      if (e.at("name") == engine) colours.insert(e.at("colour").get<std::string>());
    return colours;
  };
  CompareSettings two, four;
  two.engines = {"own", "ode"};
  four.engines = {"bullet", "mujoco", "own-impulse", "ode"};
  const CompareResult a = run_compare(scene, two), b = run_compare(scene, four);
  // The start frame holds the first step's contact set (the stack rests on its contacts), so a
  // replay opens on them.
  for (const EngineRun& run : b.runs) {
    INFO(run.engine);
    CHECK(run.recording.frames.contacts.at(0).size() >= 4);
  }
  const std::set<std::string> expected = {engine_colour("ode")};
  CHECK(colours_of(a, "ode") == expected);
  CHECK(colours_of(b, "ode") == expected);
  // Four engines, four colours, none of them a pair's line.
  std::set<std::string> all;
  for (const std::string& e : four.engines) {
    const std::set<std::string> c = colours_of(b, e);
    REQUIRE(c.size() == 1);
    all.insert(*c.begin());
  }
  CHECK(all.size() == 4);
  for (const PlotSpec& p : report_plots(b))
    for (const PlotSeries& s : p.series)
      if (s.title.find(" vs ") != std::string::npos) CHECK(all.count(s.colour) == 0);
  // A name without a row gets the same colour each time it is asked.
  CHECK(engine_colour("someone-elses") == engine_colour("someone-elses"));
  CHECK(engine_colour("someone-elses").size() == 7);
}

TEST_CASE("compare's penetration plot holds each interval's deepest, its energy plot the parts", "[compare]") {
  // The bounce: a box dropped on the ground, its deepest penetration at an impact between frames.
  Scene scene = fixture("bounce");
  scene.time.duration = std::min(scene.time.duration, 1.0);
  CompareSettings settings;
  settings.engines = {"own", "ode"};
  const CompareResult r = run_compare(scene, settings);
  const std::vector<PlotSpec> plots = report_plots(r);
  const PlotSpec& energy = plots.at(0);
  const PlotSpec& penetration = plots.at(1);
  REQUIRE(penetration.name == "penetration");
  for (const EngineRun& run : r.runs) {
    INFO(run.engine);
    const FrameSeries& f = run.recording.frames;
    REQUIRE(run.interval_penetration.size() == f.t.size());
    // The largest of the intervals is the deepest of every step, which the table reports.
    CHECK(*std::max_element(run.interval_penetration.begin(), run.interval_penetration.end()) == run.deepest.depth);
    for (std::size_t k = 0; k < f.t.size(); ++k) CHECK(run.interval_penetration[k] >= f.penetration[k] - 1e-12);
    const auto series = [&](const PlotSpec& p, const std::string& title) -> const PlotSeries& {
      for (const PlotSeries& s : p.series)
        if (s.title == title) return s;
      FAIL("no series " << title << " in " << p.name);
      return p.series.front();
    };
    CHECK(series(penetration, run.engine).y == run.interval_penetration);
    const PlotSeries& total = series(energy, run.engine);
    const PlotSeries& translational = series(energy, run.engine + " translational");
    const PlotSeries& rotational = series(energy, run.engine + " rotational");
    const PlotSeries& potential = series(energy, run.engine + " potential");
    REQUIRE(translational.y.size() == total.y.size());
    for (std::size_t k = 0; k < total.y.size(); ++k) {
      CHECK(translational.y[k] + rotational.y[k] + potential.y[k] == Approx(total.y[k]).margin(1e-9));
    }
  }
}

TEST_CASE("compare's energy plot marks impacts by kind, and its plots keep their key below", "[compare]") {
  // A cube dropped onto a cube at rest (an impact between bodies), and a cube dropped onto the
  // ground beside them (an impact with the ground).
  Scene scene = empty_scene(Effects{}, true);
  scene.bodies = {unit_box("low", Vec3(0, 0, 0.5)), unit_box("high", Vec3(0, 0, 2.0)),
                  unit_box("side", Vec3(3, 0, 1.5))};
  scene.time.duration = 0.6;
  CompareSettings settings;
  settings.engines = {"own", "ode"};
  const CompareResult r = run_compare(scene, settings);
  const std::vector<PlotSpec> plots = report_plots(r);
  const PlotSpec& energy = plots.at(0);
  REQUIRE(energy.name == "energy");
  const json report = report_json(r);
  for (const EngineRun& run : r.runs) {
    INFO(run.engine);
    std::map<std::string, std::vector<double>> times;  // kind: impact times
    for (const ImpactEvent& e : run.events) times[impact_kind_name(impact_kind(e))].push_back(e.t);
    REQUIRE(times["ground"].size() >= 1);
    REQUIRE(times["bodies"].size() >= 1);
    for (const char* kind : {"ground", "bodies"}) {
      std::string title = run.engine;
      title += std::string(kind) == "ground" ? " impact with the ground" : " impact between bodies";
      const auto s = std::find_if(energy.series.begin(), energy.series.end(),
                                  [&](const PlotSeries& p) { return p.title == title; });
      REQUIRE(s != energy.series.end());
      CHECK(s->x == times[kind]);
      CHECK_FALSE(s->in_key);
      CHECK(s->style == (std::string(kind) == "ground" ? PlotSeries::Style::Triangles : PlotSeries::Style::Points));
      CHECK(s->colour == engine_colour(run.engine));
    }
    // report.json names each event's kind alike.
    const json& events = report.at("engines").at(run.engine).at("events");
    REQUIRE(events.size() == run.events.size());
    for (std::size_t k = 0; k < events.size(); ++k)
      CHECK(events[k].at("kind") == impact_kind_name(impact_kind(run.events[k])));
  }
  // The key: each engine's total once, each style once (in grey), nothing else of the energy.
  std::vector<std::string> keyed;
  for (const PlotSeries& s : energy.series)
    if (s.in_key) keyed.push_back(s.title);
  CHECK(keyed == std::vector<std::string>{"own", "ode"});
  std::vector<std::string> styles;
  for (const PlotSeries& k : energy.key) styles.push_back(k.title);
  CHECK(styles == std::vector<std::string>{"translational", "rotational", "potential", "impact with the ground",
                                           "impact between bodies"});

  // The scripts put the key below the plot, at most kKeyColumns entries a row, the picture taller
  // by a row's height per row: position_difference's 1 pair + 2 baselines + threshold = 4 entries,
  // one row; energy's 2 totals + 5 styles = 7, two rows; series out of the key are untitled.
  const fs::path dir = scratch("plot_layout");
  for (const PlotSpec& p : plots) write_plot_files(dir, p);
  const std::string difference = read(dir / "position_difference.gp");
  CHECK_THAT(difference, Catch::Contains("set key outside below center horizontal maxcols 4"));
  CHECK_THAT(difference, !Catch::Contains("right top"));
  CHECK_THAT(difference, Catch::Contains("set terminal svg size 900,440 "));
  const std::string energy_gp = read(dir / "energy.gp");
  CHECK_THAT(energy_gp, Catch::Contains("set terminal svg size 900,460 "));
  CHECK_THAT(energy_gp, Catch::Contains("NaN with points pt 9 ps 0.8 lc rgb '#555555' title 'impact with the ground'"));
  CHECK_THAT(energy_gp, Catch::Contains("NaN with lines lw 1.2 dt 2 lc rgb '#555555' title 'translational'"));
  std::size_t untitled = 0;
  for (std::size_t at = energy_gp.find(" notitle"); at != std::string::npos; at = energy_gp.find(" notitle", at + 1)) ++untitled;
  CHECK(untitled == 2 * 5);  // per engine: its two kinds of impact and its three parts
  if (gnuplot_available()) {
    render_plot(dir, "position_difference");
    check_plot(dir, "position_difference");
  }
}
