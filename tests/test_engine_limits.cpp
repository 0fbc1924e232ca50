// What the engines survive: at the ends of the documented input ranges (sim/limits.hpp) every
// engine stays finite and keeps resting boxes on the ground; beyond them ODE's internal
// assertions become an OdeError instead of an abort; a run that turns non-finite stops at that
// step with the step, body and quantity named; output locations are checked before any work.
#include <string_view>
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "boxpile/reference/ode/ode_engine.hpp"
#include "boxpile/sim/finite.hpp"
#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/validation/compare/compare.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/output_safety.hpp"
#include "boxpile/validation/core/report_directory.hpp"

using namespace boxpile;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// Two cubes of half extent h and mass m: one on the ground, one dropped onto it from h above,
// thrown down at `speed` and spun at `spin` (the measurement behind sim/limits.hpp).
Scene two_cubes(double mass, double h, double speed, double spin) {
  Scene s;
  s.name = "two_cubes";
  s.ground = HalfSpace{};
  BodyDesc a;
  a.name = "bottom";
  a.mass = mass;
  a.boxes = {BoxShape{Vec3::Constant(h)}};
  a.frame.position = Vec3(0, 0, h);
  BodyDesc b = a;
  b.name = "top";
  b.frame.position = Vec3(0.1 * h, 0, 3.5 * h);
  b.velocity = Vec3(0.3 * speed, 0, -speed);
  b.angular_velocity = Vec3(spin, 0.5 * spin, 0);
  s.bodies = {a, b};
  s.time.dt = 1.0 / 240.0;
  s.time.duration = 1.0;
  return s;
}

// Steps the scene for its duration; returns the final states, or fails at a non-finite step.
std::vector<BodyState> run_checked(const Scene& scene, const std::string& engine_name) {
  const std::unique_ptr<Engine> engine = make_engine(engine_name, scene);
  std::vector<BodyState> states;
  const long steps = step_count(scene.time);
  for (long k = 1; k <= steps; ++k) {
    engine->step();
    engine->body_states(states);
    const auto bad = find_non_finite(states);
    INFO(engine_name << ": " << (bad ? describe_non_finite(k, engine->time(), states, *bad) : ""));
    REQUIRE_FALSE(bad);
  }
  return states;
}

// A resting cube counts as on the ground when its centre is within this fraction of its half
// extent of where it started: ODE's cube at 1e9 kg sinks 2%, at 1e12 kg it falls through.
constexpr double kRestingFraction = 0.05;
// Bullet's smallest cube runs at this step instead of the scenes' 1/240 s. At 1/240 s one step's
// fall under gravity, g dt^2 = 0.17 mm, is a third of its 0.5 mm half extent and it never settles:
// its centre wanders between -0.59 h and 0.75 h from t = 1 s to 2 s (under the ground at
// times). At 1/960 s (g dt^2 = 0.02 h) it rests within 2e-4 h, like the 1 cm cube at 1/240 s.
constexpr double kBulletSmallestDt = 1.0 / 960.0;

}  // namespace

TEST_CASE("at the ends of the documented ranges every engine keeps a resting cube on the ground",
          "[reliability][limits]") {
  struct End {
    const char* what;
    double mass, h;
  };
  const End ends[] = {{"lightest", limits::kMinMass, 0.5},
                      {"heaviest", limits::kMaxMass, 0.5},
                      {"smallest", 1.0, limits::kMinHalfExtent},
                      {"largest", 1.0, limits::kMaxHalfExtent}};
  for (const End& e : ends) {
    for (const char* engine : {"own", "ode", "bullet"}) {
      DYNAMIC_SECTION(e.what << " in " << engine) {
        Scene scene = two_cubes(e.mass, e.h, 0.0, 0.0);
        if (std::string_view(engine) == "bullet" && e.h == limits::kMinHalfExtent) scene.time.dt = kBulletSmallestDt;
        const std::vector<BodyState> s = run_checked(scene, engine);
        CHECK(std::abs(s[0].position.z() - e.h) < kRestingFraction * e.h);
      }
    }
  }
}

TEST_CASE("at the fastest and most spinning corners every engine stays finite", "[reliability][limits]") {
  for (const double mass : {limits::kMinMass, limits::kMaxMass}) {
    for (const double h : {limits::kMinHalfExtent, limits::kMaxHalfExtent}) {
      for (const char* engine : {"own", "ode", "bullet"}) {
        DYNAMIC_SECTION(engine << " m " << mass << " h " << h) {
          run_checked(two_cubes(mass, h, limits::kMaxSpeed, limits::kMaxAngularSpeed), engine);
        }
      }
    }
  }
}

TEST_CASE("an ODE internal assertion becomes an OdeError, not an abort", "[reliability][ode]") {
  // A mass of 1e-300 kg (far below the loader's range) used to end the process with SIGABRT.
  const Scene scene = two_cubes(1e-300, 0.5, 1.0, 0.0);
  auto build_and_step = [&] {
    OdeEngine engine(scene);
    for (int k = 0; k < 3; ++k) engine.step();
  };
  CHECK_THROWS_AS(build_and_step(), OdeError);
  // ODE still works for the next world.
  const std::vector<BodyState> s = run_checked(two_cubes(1.0, 0.5, 0.0, 0.0), "ode");
  CHECK(s[0].position.z() == Approx(0.5).margin(0.01));
}

TEST_CASE("a run that turns non-finite stops there and compare marks the engine failed", "[reliability][compare]") {
  // A lone cube spun at 1e150 rad/s (refused by the loader, built here directly): finite at the
  // start, its squared speed overflows within a few of our steps.
  Scene scene = two_cubes(1.0, 0.5, 0.0, 1e150);
  scene.bodies.erase(scene.bodies.begin());
  const EngineRun run = run_engine(scene, "own", CompareSettings{});
  REQUIRE(run.failure);
  CHECK(run.steps < 240);
  CHECK_THAT(*run.failure, Contains("step " + std::to_string(run.steps + 1) + " (t = ") &&
                               Contains("body \"top\" has a non-finite"));
  CHECK_FALSE(run.finite);
  // What the report keeps is the last finite state, never NaN.
  CHECK_FALSE(find_non_finite(run.final_states));
  CHECK(run.recording.frames.t.back() == Approx(static_cast<double>(run.steps) * scene.time.dt));
}

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(BOXPILE_TEST_WORK) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void check_output_refused(const fs::path& target, OutputKind kind, const std::vector<fs::path>& inputs,
                          const std::string& word) {
  try {
    check_output_path(target, kind, inputs);
    FAIL("accepted " << target);
  } catch (const OutputError& e) {
    CHECK_THAT(std::string(e.what()), Contains(target.string()) && Contains(word));
  }
}

}  // namespace

TEST_CASE("output paths: only absent or ordinary targets, never the inputs", "[reliability][output]") {
  const fs::path dir = scratch("output_paths");
  check_output_refused("", OutputKind::File, {}, "no path given");
  check_output_refused("/dev/null", OutputKind::File, {}, "device node");
  REQUIRE(mkfifo((dir / "fifo").c_str(), 0600) == 0);
  check_output_refused(dir / "fifo", OutputKind::File, {}, "FIFO");
  fs::create_symlink(dir / "elsewhere.json", dir / "link.json");
  check_output_refused(dir / "link.json", OutputKind::File, {}, "symbolic link");
  check_output_refused(dir, OutputKind::File, {}, "is a directory");
  std::ofstream(dir / "scene.json") << "{}";
  check_output_refused(dir / "scene.json", OutputKind::File, {dir / "scene.json"}, "is the input file");
  // The same file by another name.
  check_output_refused(dir / "." / "scene.json", OutputKind::File, {dir / "scene.json"}, "is the input file");
  // A report directory that holds the input would delete it when replaced.
  check_output_refused(dir, OutputKind::Directory, {dir / "scene.json"}, "holds the input file");
  check_output_refused(dir / "scene.json", OutputKind::Directory, {}, "not a directory");
  CHECK_NOTHROW(check_output_path(dir / "new.json", OutputKind::File, {dir / "scene.json"}));
  CHECK_NOTHROW(check_output_path(dir / "scene.json", OutputKind::File, {dir / "other.json"}));
}

TEST_CASE("an output file appears whole on commit and not at all without one", "[reliability][output]") {
  const fs::path dir = scratch("output_file");
  const auto staging_files = [&] {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".tmp-") != std::string::npos;
    return n;
  };
  {
    OutputFile out(dir / "sub" / "a.json", {});
    CHECK(fs::exists(dir / "sub"));  // missing parents are created
    CHECK_FALSE(fs::exists(dir / "sub" / "a.json"));
  }  // no commit: nothing left, not even the staging file or the folder it made
  CHECK_FALSE(fs::exists(dir / "sub"));
  {
    std::ofstream(dir / "b.json") << "old";
    OutputFile out(dir / "b.json", {});
    CHECK(staging_files() == 1);
    out.commit("new\n");
  }
  std::ifstream in(dir / "b.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text == "new\n");
  CHECK(staging_files() == 0);
  // An unwritable place is found when the output is set up, before any run.
  CHECK_THROWS_AS(OutputFile("/proc/boxpile-test.json", {}), OutputError);
}

TEST_CASE("SIGTERM outside an InterruptScope removes a staged report directory and all it holds",
          "[reliability][output]") {
  // In a child process, which dies of the signal. Enough files that the handler reads the
  // directory in several batches, and a folder two levels down.
  const fs::path dir = scratch("terminated");
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ReportDirectory report(dir / "report");
    fs::create_directories(report.staging() / "cells" / "plots");
    for (int k = 0; k < 200; ++k) std::ofstream(report.staging() / "cells" / ("cell_" + std::to_string(k) + ".json")) << "{}";
    std::ofstream(report.staging() / "cells" / "plots" / "energy.svg") << "<svg/>";
    { const InterruptScope scope; }  // puts boxpile's SIGTERM handler back (Catch2 replaces it per test)
    std::raise(SIGTERM);
    std::_Exit(0);  // not reached: the handler ends the process
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  // The documented code of an interrupt, whichever stop signal it was (never 143, 128 + SIGTERM).
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(fs::is_empty(dir));
}

TEST_CASE("SIGINT inside an InterruptScope is polled, unwinds, and leaves no staging", "[reliability][output]") {
  const fs::path dir = scratch("interrupt");
  const auto entries = [&] {
    return std::distance(fs::directory_iterator(dir), fs::directory_iterator{});
  };
  bool unwound = false;
  try {
    OutputFile out(dir / "run.json", {});
    REQUIRE(entries() == 1);  // the staging file
    const InterruptScope scope;
    CHECK_FALSE(interrupted());
    REQUIRE(std::raise(SIGINT) == 0);  // handled: only a flag is set, the process goes on
    CHECK(interrupted());
    throw_if_interrupted();
  } catch (const Interrupted&) {
    unwound = true;
  }
  CHECK(unwound);
  CHECK(entries() == 0);  // the staging file went with the unwinding, nothing was written
  // Past the scope the interrupt is spent: runs outside any scope (and a new scope) go on.
  CHECK_FALSE(interrupted());
  CHECK_NOTHROW(throw_if_interrupted());
}
