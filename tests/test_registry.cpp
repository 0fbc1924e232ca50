// The engine registry (reference/registry.hpp) and `--set` (validation/engine_settings.hpp), tag
// [registry]: every list of engines and settings is derived from the rows, a row added at run
// time joins every list and can be built, `--set ENGINE.KEY=VALUE` reaches compare and stability
// with and without its prefix, bad words are exit 2 with nothing written, and report.json and
// stability.json record every setting each engine ran with.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/world.hpp"
#include "boxpile/tests/support/work_dir.hpp"
#include "boxpile/validation/compare.hpp"
#include "boxpile/validation/detectors.hpp"
#include "boxpile/validation/engine_settings.hpp"
#include "boxpile/validation/stability.hpp"

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
  REQUIRE(engine_settings(name).size() == 1);
  CHECK(resolved_settings(name, fixture("stack_5")) == json({{"passes", 7}}));
  const auto set = parse_set_options({name + ".passes=3"}, {name, "ode"});
  CHECK(set.at(name) == json({{"passes", 3}}));
  CHECK(resolved_settings(name, fixture("stack_5"), set.at(name)) == json({{"passes", 3}}));
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
  CHECK(checked == 12);  // every numeric key of `solver` and `collision`
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

// The half extents' range in docs/scene-format.md is the loader's (sim/limits.hpp), and the
// integrator's default is said alike on every page that names it.
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
