// The engine registry (reference/registry.hpp) and `--set` (validation/core/engine_settings.hpp), tag
// [registry]: every list of engines and settings is derived from the rows, a row added at run
// time joins every list and can be built, `--set ENGINE.KEY=VALUE` reaches compare and stability
// with and without its prefix, bad words are exit 2 with nothing written, and report.json and
// stability.json record every setting each engine ran with.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/sim/world.hpp"
#include "boxpile/tests/support/work_dir.hpp"
#include "boxpile/validation/compare/compare.hpp"
#include "boxpile/validation/contacts/detectors.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/core/process_engines.hpp"
#include "boxpile/validation/stability/stability.hpp"
#include "boxpile/validation/stability/stability_report.hpp"
#include "boxpile/validation/stability/tune_moves.hpp"

using namespace boxpile;
using namespace boxpile::test;
using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using Names = std::vector<std::string>;

bool lists(const Names& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// An engine known only at run time, as `--engine-cmd` adds one: our World under another name,
// with one setting announced at run time (its contact passes).
EngineRow run_time_row(const std::string& name) {
  EngineRow row;
  row.name = name;
  row.title = "a run-time engine of the tests";
  row.settings = [] {
    return std::vector<SettingInfo>{{"passes", SettingInfo::Kind::Integer, "", "contact passes", 1, 64, {}, 7}};
  };
  row.make = [name](const Scene& scene, const json& settings) -> std::unique_ptr<Engine> {
    Scene s = scene;
    s.solver.contact_passes = settings.value("passes", 7);
    return std::make_unique<World>(s, name);
  };
  row.in = {.compare = true};
  return row;
}

std::string scene_path(const std::string& name) { return std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + name + ".json"; }

}  // namespace

TEST_CASE("The registry's lists are its rows'", "[registry]") {
  const Names all = engine_names();
  CHECK(all == Names{"own", "own-impulse", "own-penalty", "ode", "bullet", "mujoco", "dart"});
  CHECK(available_engine_names() == all);
  CHECK(available_engines_text() == "own, own-impulse, own-penalty, ode, bullet, mujoco, dart");
  CHECK(default_engines(&DefaultLists::compare) == Names{"own", "ode", "bullet"});
  CHECK(default_engines(&DefaultLists::stability) == Names{"own", "ode", "bullet"});
  CHECK(default_engines(&DefaultLists::main_job) == Names{"own-impulse", "own-penalty", "ode", "bullet"});
  CHECK(CompareSettings{}.engines == default_engines(&DefaultLists::compare));
  CHECK(StabilitySettings{}.engines == default_engines(&DefaultLists::stability));
  Names detector_names;
  for (const DetectorInfo& d : detectors()) detector_names.push_back(d.name);
  CHECK(detector_names == Names{"own", "ode", "bullet", "bullet-multipoint", "mujoco", "dart", "fcl"});
  // Every row has a title, and every available row a factory that builds it under its name
  // (own-impulse and own-penalty are World under their row's name).
  const Scene scene = fixture("stack_5");
  for (const std::string& name : all) {
    INFO(name);
    CHECK(!engine_row(name).title.empty());
    CHECK(make_engine(name, scene)->name() == name);
  }
  CHECK_THAT(error_of([] { check_engine_name("odee"); }),
             Contains("unknown engine \"odee\"; available: own, own-impulse, own-penalty, ode, bullet, mujoco, dart"));
  // A name is registered once.
  EngineRow twice;
  twice.name = "ode";
  twice.make = [](const Scene& s, const json&) -> std::unique_ptr<Engine> { return std::make_unique<World>(s); };
  CHECK_THROWS_AS(add_engine(twice), std::invalid_argument);
}

// The pages that list settings hold `boxpile settings`' own tables (scripts/update-settings-docs
// copies them): docs/sweeps.md all of them, docs/reference-engines.md ODE's, Bullet's and DART's.
TEST_CASE("The docs' settings tables are the registry's", "[registry]") {
  const std::string all = settings_markdown();
  const std::string docs = std::string(BOXPILE_FIXTURES_DIR) + "/../docs/";
  CHECK(read(docs + "sweeps.md").find(all) != std::string::npos);
  const std::string reference = read(docs + "reference-engines.md");
  for (const std::string engine : {"ode", "bullet", "dart"}) {
    INFO(engine);
    const std::size_t start = all.find("### " + engine + "\n");
    REQUIRE(start != std::string::npos);
    const std::size_t end = all.find("### ", start + 4);
    std::string block = all.substr(start, end == std::string::npos ? std::string::npos : end - start);
    // The page holds the block up to its last table row (scripts/update-settings-docs strips the
    // blank lines that part it from the next engine's).
    block.erase(block.find_last_not_of('\n') + 1);
    CHECK(reference.find(block + "\n<!-- end " + engine + " -->") != std::string::npos);
  }
}

TEST_CASE("A row added at run time joins every list, and builds with its announced settings", "[registry]") {
  const std::string name = "run-time-engine";
  if (!find_engine_row(name)) add_engine(run_time_row(name));
  CHECK(engine_names().back() == name);
  CHECK(lists(available_engine_names(), name));
  CHECK_THAT(available_engines_text(), Contains(", " + name));
  CHECK(lists(default_engines(&DefaultLists::compare), name));
  CHECK(!lists(default_engines(&DefaultLists::stability), name));
  CHECK(lists(CompareSettings{}.engines, name));
  CHECK_THAT(error_of([] { check_engine_name("nope"); }), Contains(name));
  CHECK_THAT(settings_markdown(), Contains("### " + name));

  // Its settings are the ones it announced: checked, defaulted and recorded like any table's.
  REQUIRE(engine_settings(name).size() == 2);  // the time step, every engine's, and its own
  const double dt = fixture("stack_5").time.dt;
  CHECK(resolved_settings(name, fixture("stack_5")) == json({{"dt", dt}, {"passes", 7}}));
  const auto set = parse_set_options({name + ".passes=3"}, {name, "ode"});
  CHECK(set.at(name) == json({{"passes", 3}}));
  CHECK(resolved_settings(name, fixture("stack_5"), set.at(name)) == json({{"dt", dt}, {"passes", 3}}));
  CHECK_THROWS_AS(parse_set_options({name + ".passes=65"}, {name}), InputError);
  const std::unique_ptr<Engine> engine = make_engine(name, fixture("stack_5"), set.at(name));
  CHECK(engine->name() == name);
  engine->step();

  // A row that cannot be built here is listed with its reason, and refused with it.
  if (!find_engine_row("absent-engine")) {
    EngineRow absent;
    absent.name = "absent-engine";
    absent.unavailable = "needs a library this build lacks";
    add_engine(absent);
  }
  CHECK(lists(engine_names(), "absent-engine"));
  CHECK(!lists(available_engine_names(), "absent-engine"));
  CHECK_THAT(error_of([] { check_engine_name("absent-engine"); }), Contains("needs a library this build lacks"));
}

TEST_CASE("Setting words of --set: the engine prefix, keys given twice, unknown engines, keys and values", "[registry]") {
  CHECK(parse_set_options({"erp=0.5"}, {"ode"}) == std::map<std::string, json>{{"ode", {{"erp", 0.5}}}});
  CHECK(parse_set_options({"ode.erp=0.5", "bullet.iterations=20", "ode.stepper=world"}, {"own", "ode", "bullet"}) ==
        std::map<std::string, json>{{"ode", {{"erp", 0.5}, {"stepper", "world"}}}, {"bullet", {{"iterations", 20}}}});
  // An integer written 5.0 reads as 5, as the loader reads it.
  CHECK(parse_set_options({"own.contact_passes=5.0"}, {"own"}).at("own") == json({{"contact_passes", 5}}));
  CHECK_THAT(error_of([] { parse_set_options({"erp=0.5"}, {"ode", "bullet"}); }), Contains("names no engine"));
  CHECK_THAT(error_of([] { parse_set_options({"erp=0.2", "erp=0.8"}, {"ode"}); }), Contains("\"erp\" is given twice"));
  CHECK_THAT(error_of([] { parse_set_options({"erp=0.2", "ode.erp=0.8"}, {"ode"}); }), Contains("given twice"));
  CHECK_THROWS_AS(parse_set_options({"nope.erp=0.2"}, {"ode"}), UnknownEngine);
  CHECK_THAT(error_of([] { parse_set_options({"bullet.erp=0.2"}, {"ode"}); }),
             Contains("engine \"bullet\" is not running"));
  CHECK_THAT(error_of([] { parse_set_options({"ode.erq=0.2"}, {"ode"}); }), Contains("did you mean \"erp\"?"));
  CHECK_THAT(error_of([] { parse_set_options({"ode.erp=2"}, {"ode"}); }), Contains("must be in [0, 1]"));
  CHECK_THAT(error_of([] { parse_set_options({"ode.stepper=step"}, {"ode"}); }), Contains("stepper"));
  CHECK_THAT(error_of([] { parse_set_options({"ode.erp"}, {"ode"}); }), Contains("expected [ENGINE.]KEY=VALUE"));
  // A setting of the penalty method is not offered by the engine that forces the impulse method.
  CHECK_THROWS_AS(parse_set_options({"own-impulse.stiffness=1e4"}, {"own-impulse"}), InputError);
  CHECK_NOTHROW(parse_set_options({"own-penalty.stiffness=1e4"}, {"own-penalty"}));
}

TEST_CASE("compare and stability take --set, record every setting, and refuse bad words with nothing written",
          "[registry]") {
  const fs::path dir = scratch("registry_set");
  const std::string scene = scene_path("stack_5");
  const std::string compare = "compare " + scene + " --duration 0.05 ";

  // With prefixes, two engines: each runs with its own, and records every setting's value.
  REQUIRE(run_boxpile(compare + "--engines ode,bullet --set ode.erp=0.5 --set bullet.iterations=20 --report " +
                      (dir / "both").string()) == 0);
  const json report = json::parse(read(dir / "both" / "report.json"));
  const json& ode = report.at("engines").at("ode").at("settings");
  const json& bullet = report.at("engines").at("bullet").at("settings");
  CHECK(ode.at("erp") == 0.5);
  CHECK(ode.at("iterations") == 20);   // ODE's default, recorded
  CHECK(ode.at("stepper") == "quickstep");
  CHECK(bullet.at("iterations") == 20);
  CHECK(bullet.at("erp") == 0.2);      // Bullet's default, recorded
  CHECK(ode.size() == engine_settings("ode").size());
  CHECK(bullet.size() == engine_settings("bullet").size());

  // Without a prefix where one engine runs; our engine records the scene's values.
  REQUIRE(run_boxpile(compare + "--engines own --set contact_passes=3 --report " + (dir / "own").string()) == 0);
  const json own = json::parse(read(dir / "own" / "report.json")).at("engines").at("own").at("settings");
  CHECK(own.at("contact_passes") == 3);
  CHECK(own.at("collision_passes") == fixture("stack_5").solver.collision_passes);
  CHECK(!own.contains("stiffness"));  // the penalty method's: the scene runs the impulse method

  // Refused, exit 2, nothing written.
  const std::vector<std::string> bad = {
      "--engines ode,bullet --set erp=0.5",                // no engine named while two run
      "--engines ode --set ode.erp=0.2 --set ode.erp=0.8",  // a key given twice
      "--engines ode --set erp=0.2 --set ode.erp=0.8",      // the same key, with and without prefix
      "--engines ode --set nope.erp=0.2",                  // an unknown engine
      "--engines ode --set bullet.erp=0.2",                // an engine that is not running
      "--engines ode --set ode.erq=0.2",                   // an unknown key
      "--engines ode --set ode.erp=7",                     // a value out of range
  };
  for (std::size_t i = 0; i < bad.size(); ++i) {
    INFO(bad[i]);
    const fs::path out = dir / ("bad_" + std::to_string(i));
    CHECK(run_boxpile(compare + bad[i] + " --report " + out.string()) == 2);
    CHECK(!fs::exists(out));
  }

  // stability: the same words, the settings recorded in every cell.
  const std::string hard = std::string(BOXPILE_FIXTURES_DIR) + "/hard/edge_drop.json";
  REQUIRE(run_boxpile("stability --engines ode --scenes " + hard + " --set erp=0.5 --report " +
                      (dir / "stability").string()) == 0);
  const json cells = json::parse(read(dir / "stability" / "stability.json")).at("cells");
  REQUIRE(cells.size() == 1);
  CHECK(cells[0].at("settings").at("erp") == 0.5);
  CHECK(cells[0].at("settings").at("iterations") == 20);
  CHECK(run_boxpile("stability --engines ode --scenes " + hard + " --set ode.erp=0.2 --set ode.erp=0.8 --report " +
                    (dir / "stability_twice").string()) == 2);
  CHECK(!fs::exists(dir / "stability_twice"));
  CHECK(run_boxpile("stability --engines ode --scenes " + hard + " --set bullet.erp=0.2 --report " +
                    (dir / "stability_absent").string()) == 2);
  CHECK(!fs::exists(dir / "stability_absent"));

  // run: with and without the prefix; --iterations is a spelling of --set iterations.
  CHECK(run_boxpile("run " + scene + " --engine own --duration 0.05 --set own.contact_passes=3") == 0);
  CHECK(run_boxpile("run " + scene + " --engine ode --duration 0.05 --set stepper=world") == 0);
  CHECK(run_boxpile("run " + scene + " --engine ode --duration 0.05 --iterations 5 --set iterations=6") == 2);
  CHECK(run_boxpile("run " + scene + " --engine ode --duration 0.05 --set bullet.erp=0.1") == 2);
}

// The scene loader and `--set` read one declaration: for every key of our settings table that a
// scene file gives, a value just past either bound is refused by both with the same range, and a
// value at the bound is read by both (penalty keys are refused or read under the penalty method).
TEST_CASE("A loader bound and the --set bound are one declaration", "[registry]") {
  const std::string file = scene_path("stack_5");
  const json base = json::parse(read(file));
  int checked = 0;
  for (const SettingInfo& s : engine_settings("own")) {
    if (s.scene_key.empty() || (s.kind != SettingInfo::Kind::Integer && s.kind != SettingInfo::Kind::Number)) continue;
    INFO(s.scene_key);
    const std::size_t dot = s.scene_key.find('.');
    const std::string section = s.scene_key.substr(0, dot), key = s.scene_key.substr(dot + 1);
    const bool integer = s.kind == SettingInfo::Kind::Integer;
    const double above = integer ? s.max + 1 : 2 * s.max;
    const double below = integer ? s.min - 1 : (s.min > 0 ? s.min / 2 : -1);
    const std::string range = "must be in [" + (integer ? std::to_string(static_cast<long>(s.min)) : json_input::format_number(s.min)) +
                              ", " + (integer ? std::to_string(static_cast<long>(s.max)) : json_input::format_number(s.max)) + "]";
    for (const double value : {above, below}) {
      json doc = base;
      if (!s.group.empty()) doc["solver"]["method"] = s.group;
      doc[section][key] = integer ? json(static_cast<long>(value)) : json(value);
      const std::string loader = error_of([&] { parse_scene(doc.dump(), "bound.json"); });
      const std::string word = error_of([&] {
        parse_set_options({"own." + s.key + "=" + (integer ? std::to_string(static_cast<long>(value)) : json(value).dump())}, {"own"});
      });
      CHECK_THAT(loader, Contains("bound.json") && Contains(s.scene_key) && Contains(range));
      CHECK_THAT(word, Contains(s.key) && Contains(range));
    }
    // At the bound both read the value (the penalty method's are checked by --set alone: a
    // scene at the stiffest spring is refused by the penalty method's own stability bound).
    const json at = integer ? json(static_cast<long>(s.max)) : json(s.max);
    CHECK(parse_set_options({"own." + s.key + "=" + at.dump()}, {"own"}).at("own").at(s.key) == at);
    if (s.group != "penalty") {
      json doc = base;
      doc[section][key] = at;
      const Scene loaded = parse_scene(doc.dump(), "bound.json");
      CHECK(resolved_settings("own", loaded).at(s.key) == at);
    }
    ++checked;
  }
  CHECK(checked == 13);  // every numeric key of `solver` and `collision`, `solver.threads` among them
}

// docs/scene-format.md's `solver` and `collision` tables state each key's default, unit and
// range as our settings table declares them.
TEST_CASE("docs/scene-format.md's solver and collision keys are the settings table's", "[registry]") {
  const std::string doc = read(std::string(BOXPILE_FIXTURES_DIR) + "/../docs/scene-format.md");
  auto cells_of = [](const std::string& line) {
    std::vector<std::string> cells;
    std::size_t at = 1;
    for (std::size_t bar; (bar = line.find(" |", at)) != std::string::npos; at = bar + 2) {
      std::string cell = line.substr(at, bar - at);
      cell.erase(0, cell.find_first_not_of(' '));
      cells.push_back(cell);
    }
    return cells;
  };
  auto unquoted = [](std::string s) {
    s.erase(std::remove(s.begin(), s.end(), '`'), s.end());
    return s;
  };
  for (const SettingInfo& s : engine_settings("own")) {
    if (s.scene_key.empty()) continue;
    INFO(s.scene_key);
    const std::size_t dot = s.scene_key.find('.');
    const std::size_t section = doc.find("### `" + s.scene_key.substr(0, dot) + "`");
    REQUIRE(section != std::string::npos);
    const std::size_t row = doc.find("| `" + s.scene_key.substr(dot + 1) + "` |", section);
    REQUIRE(row != std::string::npos);
    const std::vector<std::string> cells = cells_of(doc.substr(row, doc.find('\n', row) - row));
    REQUIRE(cells.size() == 5);  // key, type, default, unit, constraint
    const json doc_default = json::parse(unquoted(cells[2]), nullptr, false);
    if (s.default_value.is_null()) {
      CHECK((doc_default.is_discarded() || doc_default.is_string()));  // "derived", `stiffness`
    } else if (s.default_value.is_number()) {
      REQUIRE(doc_default.is_number());
      CHECK(doc_default.get<double>() == s.default_value.get<double>());
    } else {
      CHECK(doc_default == s.default_value);
    }
    std::string unit = cells[3];
    for (std::size_t dot_at; (dot_at = unit.find("·")) != std::string::npos;) unit.replace(dot_at, std::string("·").size(), " ");
    CHECK(unit == s.unit);
    if (s.kind == SettingInfo::Kind::Integer || s.kind == SettingInfo::Kind::Number) {
      const std::string values = setting_values_text(s);  // "integer in [1, 64]"
      CHECK_THAT(cells[4], Contains(values.substr(values.find('['))));
    }
    if (s.kind == SettingInfo::Kind::Choice)
      for (const std::string& c : s.choices) CHECK_THAT(cells[4], Contains("\"" + c + "\""));
  }
}

// Each reference engine names what it needs installed in its folder (reference/NAME/packages);
// scripts/install-deps installs those, and the engine's title, which help texts and reports show,
// names the same packages. package.json, which npm ci installs from its lockfile, holds exactly the
// npm packages the folders name, at their versions.
TEST_CASE("Each engine's folder names its packages, and install-deps and its title follow them", "[registry]") {
  add_node_engines();
  const fs::path root = fs::path(BOXPILE_FIXTURES_DIR).parent_path();
  struct Package {
    std::string kind, name, version;
  };
  const auto packages_of = [&](const std::string& folder) {
    std::ifstream in(root / "reference" / folder / "packages");
    REQUIRE(in);
    std::vector<Package> out;
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream words(line);
      Package p;
      words >> p.kind >> p.name;
      if (p.kind == "npm") words >> p.version;
      INFO(line);
      CHECK((p.kind == "debian" || p.kind == "npm"));
      CHECK(!p.name.empty());
      out.push_back(p);
    }
    return out;
  };
  // install-deps --list: the Debian packages it would install.
  Names listed;
  {
    const std::string command = "bash '" + (root / "scripts" / "install-deps").string() + "' --list";
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    char line[256];
    while (std::fgets(line, sizeof line, pipe)) listed.emplace_back(std::string(line).substr(0, std::strcspn(line, "\n")));
    CHECK(pclose(pipe) == 0);
  }
  json npm_dependencies;
  std::ifstream(root / "reference" / "package.json") >> npm_dependencies;
  npm_dependencies = npm_dependencies.at("dependencies");
  std::size_t npm_named = 0;
  std::size_t engines_checked = 0;
  for (const std::string& engine : engine_names()) {
    INFO(engine);
    const std::string& title = find_engine_row(engine)->title;
    // Ours is built in; other tests add rows of their own at run time. Every engine that is
    // installed from a package has its folder.
    std::string folder = engine;
    std::replace(folder.begin(), folder.end(), '-', '_');
    if (!fs::exists(root / "reference" / folder / "packages")) {
      CHECK(title.find("Debian") == std::string::npos);
      CHECK(title.find("npm") == std::string::npos);
      continue;
    }
    const std::vector<Package> packages = packages_of(folder);
    CHECK(!packages.empty());
    for (const Package& p : packages) {
      INFO(p.name);
      CHECK_THAT(title, Contains(p.version.empty() ? p.name : p.name + " " + p.version));
      if (p.kind == "debian") CHECK(std::count(listed.begin(), listed.end(), p.name) == 1);
      if (p.kind == "npm") {
        ++npm_named;
        REQUIRE(npm_dependencies.contains(p.name));
        CHECK(npm_dependencies[p.name] == p.version);
      }
    }
    ++engines_checked;
  }
  CHECK(engines_checked == 7);  // ode, bullet, mujoco, dart, jolt, rapier, mujoco-wasm
  CHECK(npm_named == npm_dependencies.size());
}

// The time step is every engine's setting, declared once: listed first, recorded at the scene's
// value, and when given it is the step the engine takes (its clock after three steps).
TEST_CASE("dt is a setting of every engine, the scene's by default", "[registry]") {
  const Scene scene = fixture("stack_5");
  for (const std::string& name : available_engine_names()) {
    INFO(name);
    const std::vector<SettingInfo> settings = engine_settings(name);
    REQUIRE(!settings.empty());
    CHECK(settings.front().key == "dt");
    CHECK(settings.front().unit == "s");
    CHECK(std::count_if(settings.begin(), settings.end(), [](const SettingInfo& s) { return s.key == "dt"; }) == 1);
    CHECK(resolved_settings(name, scene).at("dt") == scene.time.dt);
    const json set = parse_set_options({"dt=0.002"}, {name}).at(name);
    CHECK(resolved_settings(name, scene, set).at("dt") == 0.002);
    CHECK(scene_with_settings(name, scene, set).time.dt == 0.002);
    const std::unique_ptr<Engine> engine = make_engine(name, scene, set);
    for (int k = 0; k < 3; ++k) engine->step();
    CHECK(engine->time() == Approx(0.006).margin(1e-15));
  }
  CHECK_THAT(error_of([] { parse_set_options({"ode.dt=0"}, {"ode"}); }), Contains("must be in (0, 1] s"));
  CHECK_THAT(error_of([] { parse_set_options({"ode.dt=2"}, {"ode"}); }), Contains("must be in (0, 1] s"));
  CHECK_THAT(settings_markdown(), Contains("| `dt` | number in (0, 1] | the scene's time.dt | s |"));
}

TEST_CASE("An engine given its own dt by --set runs at it in run, compare and stability", "[registry]") {
  const fs::path dir = scratch("registry_dt");
  const std::string scene = scene_path("stack_5");
  // compare: ODE at 2 ms beside Bullet at the scene's step, each recorded.
  REQUIRE(run_boxpile("compare " + scene + " --duration 0.1 --engines ode,bullet --set ode.dt=0.002 --report " +
                      (dir / "compare").string()) == 0);
  const json engines = json::parse(read(dir / "compare" / "report.json")).at("engines");
  CHECK(engines.at("ode").at("settings").at("dt") == 0.002);
  CHECK(engines.at("bullet").at("settings").at("dt") == fixture("stack_5").time.dt);
  // stability: the steps run are the duration over the engine's own dt.
  const std::string hard = std::string(BOXPILE_FIXTURES_DIR) + "/hard/edge_drop.json";
  REQUIRE(run_boxpile("stability --engines ode --scenes " + hard + " --set dt=0.01 --report " +
                      (dir / "stability").string()) == 0);
  const json cell = json::parse(read(dir / "stability" / "stability.json")).at("cells").at(0);
  CHECK(cell.at("settings").at("dt") == 0.01);
  CHECK(cell.at("steps") == 150);  // 1.5 s
  // Refused, nothing written: beside --dt, past the step cap, out of range.
  CHECK(run_boxpile("run " + scene + " --engine ode --dt 0.01 --set dt=0.02") == 2);
  CHECK(run_boxpile("stability --engines ode --scenes " + hard + " --set dt=1e-7 --max-steps 1000 --report " +
                    (dir / "capped").string()) == 2);
  CHECK(!fs::exists(dir / "capped"));
  CHECK(run_boxpile("compare " + scene + " --engines ode --set dt=-1 --report " + (dir / "negative").string()) == 2);
  CHECK(!fs::exists(dir / "negative"));
  CHECK(run_boxpile("run " + scene + " --engine own --duration 0.05 --set dt=0.01") == 0);
}

namespace {

// A box sliding on frictionless ground at `speed` (m/s) along x for `steps` steps of 0.01 s in
// `engine` with `words`: how far it went (m). On the ground, because ODE never puts a body to
// sleep in mid-air (one without joints).
double slide(const std::string& engine, double speed, int steps, const std::vector<std::string>& words) {
  Scene s;
  s.ground = HalfSpace{};
  s.material.friction = 0.0;
  s.time.dt = 0.01;
  BodyDesc box;
  box.name = "box";
  box.mass = 1.0;
  box.boxes = {BoxShape{}};
  box.frame.position = Vec3(0.0, 0.0, 0.5);
  box.velocity = Vec3(speed, 0.0, 0.0);
  s.bodies.push_back(box);
  const std::unique_ptr<Engine> e = make_engine(engine, s, parse_setting_words(engine, words, "test"));
  for (int k = 0; k < steps; ++k) e->step();
  std::vector<BodyState> states;
  e->body_states(states);
  return states.at(0).position.x();
}

}  // namespace

// Sleeping is a setting, off by default: on, a body slower than the threshold stops after the
// engine's wait (ODE: auto_disable_steps steps; Bullet: 2 s), off, it keeps its speed.
TEST_CASE("ODE's auto-disable and Bullet's sleeping are settings that take effect", "[registry]") {
  // ODE: 0.005 m/s, under the 0.01 m/s threshold, for 100 steps of 0.01 s: 5 mm awake; asleep
  // after auto_disable_steps calm steps, which begin once ERP's push out of the first step's
  // overlap (0.2 x 1 mm per 0.01 s, 0.02 m/s at first) has died down: up to 15 steps later.
  const double mm_per_step = 0.005 * 0.01;
  CHECK(slide("ode", 0.005, 100, {}) == Approx(0.005).epsilon(1e-9));
  const double ten = slide("ode", 0.005, 100, {"auto_disable=true"});
  CHECK(ten >= 10 * mm_per_step);
  CHECK(ten <= 25 * mm_per_step);
  const double fifty = slide("ode", 0.005, 100, {"auto_disable=true", "auto_disable_steps=50"});
  CHECK(fifty - ten == Approx(40 * mm_per_step).margin(1e-9));
  CHECK(slide("ode", 0.005, 100, {"auto_disable=true", "auto_disable_linear_threshold=0.001"}) ==
        Approx(0.005).epsilon(1e-9));
  // Bullet: 0.5 m/s, under its 0.8 m/s threshold, for 3 s: 1.5 m awake, asleep after 2 s (1 m).
  CHECK(slide("bullet", 0.5, 300, {}) == Approx(1.5).epsilon(1e-9));
  CHECK(slide("bullet", 0.5, 300, {"sleeping=true"}) == Approx(1.0).margin(0.011));
  CHECK(slide("bullet", 0.5, 300, {"sleeping=true", "linear_sleeping_threshold=0.1"}) == Approx(1.5).epsilon(1e-9));
}

// Bullet's continuous collision detection is a setting, off by default: the catalogue's shot at
// 100 m/s (0.42 m a step) passes through the 2 cm plate without it and stays in front of it with
// it (Bullet's contact then still lets it 4 cm deep: the penetration check fails either way).
TEST_CASE("Bullet's CCD is a setting that changes the tunnelling verdict", "[registry]") {
  const Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/hard/tunnelling.json");
  auto stays_behind = [](const StabilityCell& cell) {
    for (const SceneCheckResult& c : cell.checks)
      if (c.name == "stays_behind shot") return c.passed;
    FAIL("no stays_behind check");
    return false;
  };
  StabilitySettings settings;
  settings.engines = {"bullet"};
  CHECK(!stays_behind(run_stability_cell(scene, "bullet", settings)));
  settings.engine_settings["bullet"] =
      parse_set_options({"ccd_motion_threshold=0.05", "ccd_swept_sphere_radius=0.1"}, {"bullet"}).at("bullet");
  const StabilityCell ccd = run_stability_cell(scene, "bullet", settings);
  CHECK(stays_behind(ccd));
  CHECK(ccd.settings.at("ccd_motion_threshold") == 0.05);
}

// Runs at different time steps (`--set ode.dt=...` beside another engine at the scene's) are
// compared frame against the nearest frame in time, not frame index against frame index.
TEST_CASE("diff_runs pairs frames by time when the runs' steps differ", "[registry]") {
  // A body at x = t in both runs: one recorded every 0.1 s, the other every 0.05 s.
  auto series = [](double spacing, int frames) {
    FrameSeries f;
    for (int k = 0; k < frames; ++k) {
      f.t.push_back(spacing * k);
      BodyState s;
      s.name = "box";
      s.position = Vec3(spacing * k, 0.0, 0.0);
      f.states.push_back({s});
    }
    return f;
  };
  const FrameSeries coarse = series(0.1, 11), fine = series(0.05, 21);
  const RunDifference d = diff_runs("a", coarse, "b", fine, 1e-3, 1e-3);
  REQUIRE(d.t.size() == 11u);
  CHECK(d.largest_position < 1e-12);  // the same motion, frame for frame in time
  CHECK(!d.position_passes);
  // A run stopped at 0.5 s: the frames after it are left out.
  const RunDifference stopped = diff_runs("a", coarse, "b", series(0.05, 11), 1e-3, 1e-3);
  CHECK(stopped.t.size() == 6u);
  CHECK(stopped.largest_position < 1e-12);
}

// `stability --tune` on a cell that fails as run: ODE's QuickStep lets the flat drop turn
// (no_turning 0.07 rad/s at 1/240 s and 20 iterations). The first of ODE's knobs, dWorldStep's
// exact LCP, keeps it from turning at the scene's step; the search records it, and the recorded
// settings given back through --set pass again.
TEST_CASE("stability --tune finds a passing setting that --set reproduces", "[registry]") {
  const fs::path dir = scratch("registry_tune");
  const std::string hard = std::string(BOXPILE_FIXTURES_DIR) + "/hard/flat_drop.json";
  REQUIRE(run_boxpile("stability --engines ode --scenes " + hard + " --tune --tune-budget 60 --report " +
                      (dir / "tuned").string()) == 0);
  const json cell = json::parse(read(dir / "tuned" / "stability.json")).at("cells").at(0);
  CHECK(!cell.at("passed").get<bool>());
  const json& tuned = cell.at("tuned");
  REQUIRE(tuned.at("passed").get<bool>());
  const json& settings = tuned.at("settings");
  CHECK(settings == json{{"stepper", "world"}});
  CHECK(tuned.at("attempts") == 2);  // as given, then the first knob
  CHECK(tuned.at("us_per_sim_s").get<double>() > 0.0);
  for (const json& check : tuned.at("checks")) CHECK(check.at("passed").get<bool>());
  CHECK_THAT(read(dir / "tuned" / "stability.md"), Contains("## The cheapest passing settings (--tune)"));
  CHECK_THAT(read(dir / "tuned" / "stability.md"), Contains("| flat_drop | stepper=\"world\" |"));

  std::string set;
  for (const auto& [key, value] : settings.items()) set += " --set " + key + "=" + value.dump();
  REQUIRE(run_boxpile("stability --engines ode --scenes " + hard + set + " --report " + (dir / "again").string()) == 0);
  const json again = json::parse(read(dir / "again" / "stability.json")).at("cells").at(0);
  CHECK(again.at("passed").get<bool>());
  CHECK(again.at("settings").at("stepper") == "world");
  // A budget of 0 s stops at the run as given: the closest attempt is it, and says so.
  REQUIRE(run_boxpile("stability --engines ode --scenes " + hard + " --tune --tune-budget 0 --report " +
                      (dir / "no_budget").string()) == 0);
  const json spent = json::parse(read(dir / "no_budget" / "stability.json")).at("cells").at(0).at("tuned");
  CHECK(!spent.at("passed").get<bool>());
  CHECK(spent.at("out_of_budget").get<bool>());
  CHECK(spent.at("attempts") == 1);
}

// The order of --tune's search on a cell no setting can pass: a unit cube dropped 1 m, held to
// rest (it must not move 1 mm), moves 1 m in every engine at every step. ODE's knobs come first,
// one at a time at the scene's step; then the ladder, dt halved and the iterations doubled
// together, which stops after two rungs that do not shrink the miss; then ODE's sleeping switch
// on the closest attempt, here the given settings. Each attempt costs more than the last.
TEST_CASE("stability --tune tries the knobs, then the ladder's rungs, then sleeping, in that order", "[registry]") {
  const Scene scene = parse_scene(R"({"name": "drop", "time": {"dt": 0.004166666666666667, "duration": 1},
    "ground": {}, "bodies": [{"name": "box", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 1.5]}],
    "checks": {"rest": {"speed": 0.001, "max_move": 0.001}}})", "drop.json");
  StabilitySettings settings;
  settings.engines = {"ode"};
  const StabilityCell given = run_stability_cell(scene, "ode", settings);
  REQUIRE_FALSE(given.passed);
  REQUIRE(given.settings.at("iterations") == 20);
  std::vector<std::string> attempts;
  const TunedCell tuned =
      tune_cell(scene, "ode", settings, given, [&](std::string_view label) { attempts.emplace_back(label); });
  CHECK(attempts == std::vector<std::string>{"stepper world", "surface_layer", "dt/2, iterations 40",
                                             "dt/4, iterations 80", "the given settings, auto_disable"});
  CHECK_FALSE(tuned.passed);
  CHECK_FALSE(tuned.out_of_budget);
  CHECK(tuned.attempts == 6);  // the cell as given and the five above
  // None shrank the miss by 1%: the closest attempt is the cell as given (the box moved 1 m, less
  // what it sinks into the ground).
  CHECK(tuned.settings == json::object());
  for (const SceneCheckResult& c : tuned.checks)
    if (c.name == "rest_move") CHECK(c.value == Approx(1.0).margin(0.01));
}

// Every knob --tune tries is one of its engine's settings, with a value the engine's table takes,
// and the moves scaled with the scene are: a slop a tenth of the allowed depth, a time constant
// twice the step.
TEST_CASE("every tune move is a valid setting of its engine, scaled with the scene", "[registry]") {
  add_node_engines();
  const Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/hard/thin_plates.json");
  for (const std::string& engine : engines_with_tune_moves()) {
    INFO(engine);
    const std::vector<TuneMove> moves = tune_moves(engine, scene, 0.004);
    CHECK(!moves.empty());
    const std::vector<SettingInfo> table = engine_settings(engine);
    for (const TuneMove& m : moves) {
      INFO(m.label);
      CHECK(!m.why.empty());
      for (const auto& [key, value] : m.settings.items()) {
        INFO(key);
        const auto row = std::find_if(table.begin(), table.end(), [&](const SettingInfo& s) { return s.key == key; });
        REQUIRE(row != table.end());
        const json doc = {{"v", value}};
        CHECK_NOTHROW(check_setting_value(*row, json_input::JsonNode(doc, "move").at("v")));
      }
    }
  }
  // thin_plates: 1 cm plates, a 0.1 mm penetration limit: ODE's surface layer 10 µm.
  const std::vector<TuneMove> ode = tune_moves("ode", scene, 0.004);
  CHECK(ode.at(1).settings.at("surface_layer").get<double>() == Approx(1e-5));
  CHECK(tune_moves("mujoco", scene, 0.004).at(0).settings.at("solref_timeconst").get<double>() == Approx(0.008));
  CHECK(tune_moves("own", scene, 0.004).empty());
}

// `--shard I/N` runs every N-th cell; stability-merge joins the shards into the report one run
// gives, cell for cell (timings aside), and refuses a shard given twice or a run left incomplete.
TEST_CASE("stability shards merge into the unsharded run's report", "[registry]") {
  const fs::path dir = scratch("registry_shards");
  const std::string scenes = std::string(BOXPILE_FIXTURES_DIR) + "/hard/flat_drop.json " + BOXPILE_FIXTURES_DIR +
                             "/hard/edge_drop.json";
  const std::string run = "stability --engines own,ode --scenes " + scenes;
  REQUIRE(run_boxpile(run + " --report " + (dir / "whole").string()) == 0);
  REQUIRE(run_boxpile(run + " --shard 1/3 --report " + (dir / "s1").string()) == 0);
  REQUIRE(run_boxpile(run + " --shard 2/3 --report " + (dir / "s2").string()) == 0);
  REQUIRE(run_boxpile(run + " --shard 3/3 --report " + (dir / "s3").string()) == 0);
  const json s1 = json::parse(read(dir / "s1" / "stability.json"));
  CHECK(s1.at("cells").size() == 2u);  // positions 0 and 3 of 4
  CHECK(s1.at("shards") == json{"1/3"});
  CHECK(s1.at("cells_total") == 4);
  REQUIRE(run_boxpile("stability-merge " + (dir / "s3").string() + " " + (dir / "s1").string() + " " +
                      (dir / "s2").string() + " --report " + (dir / "merged").string()) == 0);
  const json whole = json::parse(read(dir / "whole" / "stability.json"));
  const json merged = json::parse(read(dir / "merged" / "stability.json"));
  REQUIRE(merged.at("cells").size() == whole.at("cells").size());
  for (std::size_t k = 0; k < whole.at("cells").size(); ++k) {
    json a = whole.at("cells")[k], b = merged.at("cells")[k];
    for (json* c : {&a, &b})
      for (const char* timing : {"us_per_step", "us_per_sim_s", "wall_seconds"}) c->erase(timing);
    CHECK(a == b);
  }
  CHECK(merged.at("shards") == json({"1/3", "2/3", "3/3"}));
  CHECK_THAT(read(dir / "merged" / "stability.md"), Contains("in 3 shards"));
  // A shard given twice, and a run left incomplete: exit 2, nothing written.
  CHECK(run_boxpile("stability-merge " + (dir / "s1").string() + " " + (dir / "s1").string() + " " +
                    (dir / "s2").string() + " " + (dir / "s3").string() + " --report " + (dir / "twice").string()) == 2);
  CHECK(!fs::exists(dir / "twice"));
  CHECK(run_boxpile("stability-merge " + (dir / "s1").string() + " " + (dir / "s2").string() + " --report " +
                    (dir / "part").string()) == 2);
  CHECK(!fs::exists(dir / "part"));
  CHECK(run_boxpile("stability-merge " + (dir / "whole").string() + " --report " + (dir / "unsharded").string()) == 2);
  CHECK(run_boxpile(run + " --shard 4/3 --report " + (dir / "bad").string()) == 2);
  CHECK(!fs::exists(dir / "bad"));
}

// The half extents' range in docs/scene-format.md is the loader's (sim/limits.hpp), and the
// integrator's default is said alike on every page that names it.
// A cell's wall-time limit stops the run after the step that passed it and fails the cell by a
// check of its own ("finished": steps run against the scene's), while a cell within its limit
// runs and is judged exactly as without one.
TEST_CASE("stability's cell time limit stops a cell and fails its finished check", "[registry]") {
  const Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/hard/edge_drop.json");
  StabilitySettings settings;
  settings.engines = {"own"};
  const StabilityCell whole = run_stability_cell(scene, "own", settings);
  REQUIRE(whole.passed);
  CHECK(!whole.out_of_time);
  CHECK(whole.steps == step_count(scene.time));

  settings.cell_time_limit = 3600.0;
  const StabilityCell within = run_stability_cell(scene, "own", settings);
  CHECK(!within.out_of_time);
  CHECK(within.steps == whole.steps);
  REQUIRE(within.checks.size() == whole.checks.size());
  for (std::size_t i = 0; i < whole.checks.size(); ++i) CHECK(within.checks[i].value == whole.checks[i].value);

  settings.cell_time_limit = 1e-9;  // passed by the first step: the run stops after it
  const StabilityCell cut = run_stability_cell(scene, "own", settings);
  CHECK(cut.out_of_time);
  CHECK(cut.steps == 1);
  CHECK(!cut.passed);
  REQUIRE(!cut.checks.empty());
  CHECK(cut.checks.front().name == "finished");
  CHECK(!cut.checks.front().passed);
  CHECK(cut.checks.front().value == 1.0);
  CHECK(cut.checks.front().limit == static_cast<double>(whole.steps));
  CHECK(describe(cut.checks.front()) == "finished 1 steps < " + std::to_string(whole.steps));
}

// An engine that refuses a scene (EngineRefused: MuJoCo 2.2 cannot allocate the 385-box pyramid's
// constraint arrays) fails that cell by its "finished" check, with its message in the cell and in
// stability.json, and the matrix goes on with the next cell.
TEST_CASE("stability records an engine's refusal of a scene as the cell's failure", "[registry]") {
  if (!find_engine_row("mujoco") || !find_engine_row("mujoco")->make) return;  // built without MuJoCo
  const Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/hard/pyramid_10.json");
  StabilitySettings settings;
  settings.engines = {"mujoco"};
  const StabilityCell cell = run_stability_cell(scene, "mujoco", settings);
  CHECK(!cell.passed);
  CHECK(cell.steps < step_count(scene.time));
  CHECK_THAT(cell.refused, Contains("mujoco"));
  REQUIRE(!cell.checks.empty());
  CHECK(cell.checks.front().name == "finished");
  CHECK(!cell.checks.front().passed);
  CHECK(cell.checks.front().limit == static_cast<double>(step_count(scene.time)));
  StabilityResult result;
  result.engines = {"mujoco"};
  result.scenes = {scene};
  result.cells = {cell};
  const json doc = stability_json(result);
  CHECK(doc["cells"][0]["refused"] == cell.refused);
  CHECK_THAT(cell_text(cell), Contains("refused: mujoco"));
}

TEST_CASE("docs state the loader's half-extent range and the integrator's default", "[registry]") {
  const std::string docs = std::string(BOXPILE_FIXTURES_DIR) + "/../docs/";
  const std::string format = read(docs + "scene-format.md");
  // The doc writes the loader's numbers as 5e-4 and 1e3.
  CHECK(limits::kMinHalfExtent == 5e-4);
  CHECK(limits::kMaxHalfExtent == 1e3);
  const std::string range = "each 5e-4 to 1e3";
  std::size_t rows = 0;
  for (std::size_t at = format.find("| `half_extents` |"); at != std::string::npos;
       at = format.find("| `half_extents` |", at + 1)) {
    ++rows;
    const std::string row = format.substr(at, format.find('\n', at) - at);
    CHECK_THAT(row, Contains(range));
  }
  CHECK(rows == 2);
  CHECK(SolverSettings{}.integrator == PositionIntegrator::SemiImplicitEuler);
  CHECK_THAT(format, Contains("| `integrator` | string | `\"semi_implicit_euler\"` |"));
  CHECK_THAT(read(docs + "reference-engines.md"), Contains("`solver.integrator` (semi-implicit Euler by default"));
}
