#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/sim/solver/contact_method.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/core/json_output.hpp"
#include "boxpile/validation/contacts/contact_diff.hpp"
#include "boxpile/validation/contacts/detectors.hpp"

namespace boxpile::cli {
namespace {

constexpr std::string_view kOwn = kOwnDetector;
// own-NAME names our engine with a forced contact method (one per row of the registry,
// sim/solver/contact_method.hpp); the contact set is the same for each, so they are "own" here.
std::vector<std::string> own_aliases() {
  std::vector<std::string> names;
  for (const ContactMethodRow& m : contact_methods()) names.push_back("own-" + m.name);
  return names;
}

std::string detector_of(const std::string& name) {
  const std::vector<std::string> aliases = own_aliases();
  const bool alias = std::find(aliases.begin(), aliases.end(), name) != aliases.end();
  return alias ? std::string(kOwn) : name;
}
constexpr const char* kTable = "table";
constexpr const char* kJson = "json";

DetectOptions detect_options(const ContactsOptions& options) {
  DetectOptions d;
  d.own.reduce_to_four = options.reduce;
  return d;
}

std::vector<std::string> detector_names() {
  std::vector<std::string> names;
  for (const DetectorInfo& d : detectors()) names.emplace_back(d.name);
  const std::vector<std::string> aliases = own_aliases();
  names.insert(names.begin() + 1, aliases.begin(), aliases.end());
  return names;
}

// A detector name of detector_names(); an old spelling (bullet_multipoint) is refused with the
// name it now has.
CLI::Validator detector_name() {
  std::string names;
  for (const std::string& n : detector_names()) names += (names.empty() ? "" : ",") + n;
  return CLI::Validator(
      [](const std::string& name) -> std::string {
        const std::vector<std::string> known = detector_names();
        if (std::find(known.begin(), known.end(), name) != known.end()) return "";
        try {
          find_detector(name);
        } catch (const UnknownDetector& e) {
          return e.what();
        }
        return "";
      },
      "{" + names + "}");
}

// The detectors shown when none are named: every one, those that differ on box-plane queries
// only when the query is box-plane.
std::vector<std::string> default_detectors(const ContactQuery& query) {
  std::vector<std::string> names;
  for (const DetectorInfo& d : detectors()) {
    if (!d.box_plane_only || query.plane) names.emplace_back(d.name);
  }
  return names;
}

// One contact set per detector, then the answers saved in the query file.
std::vector<std::pair<std::string, Manifold>> contact_sets(const ContactsOptions& options, const ContactQuery& query) {
  std::vector<std::string> names = options.engines.empty() ? default_detectors(query) : options.engines;
  std::vector<std::pair<std::string, Manifold>> sets;
  for (const std::string& listed : names) {
    const std::string name = detector_of(listed);
    const bool listed_twice =
        std::any_of(sets.begin(), sets.end(), [&](const auto& s) { return s.first == name; });
    if (!listed_twice) sets.emplace_back(name, find_detector(name).detect(query, detect_options(options)));
  }
  for (const RecordedAnswer& r : query.answers) sets.emplace_back(r.detector + " (saved)", r.contacts);
  return sets;
}

nlohmann::json optional_number(const std::optional<double>& x) {
  return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
}

nlohmann::json to_json(const ContactDiff& d, std::string_view reference) {
  return {{"points", {{std::string(kOwn), d.base_points}, {std::string(reference), d.other_points}}},
          {"normal_angle", optional_number(d.normal_angle)},
          {"depth_difference", optional_number(d.depth_difference)},
          {"hausdorff", optional_number(d.hausdorff)},
          {"hull_distance", optional_number(d.hull_distance)},
          {"smaller_inside_hull", d.inside_hull},
          {"tested", d.other_tested ? std::string(reference) : std::string(kOwn)}};
}

using ContactSets = std::vector<std::pair<std::string, Manifold>>;

const Manifold* own_set(const ContactSets& sets) {
  const auto own = std::find_if(sets.begin(), sets.end(), [](const auto& s) { return s.first == kOwn; });
  return own == sets.end() ? nullptr : &own->second;
}

void print_json(const ContactsOptions& options, const ContactQuery& query, const ContactSets& sets) {
  nlohmann::json engines = nlohmann::json::object();
  for (const auto& [name, m] : sets) engines[name] = answer_json(m);
  nlohmann::json doc = {{"query", options.query}, {"kind", query.b ? "box-box" : "box-plane"}, {"engines", engines}};
  if (const Manifold* own = own_set(sets)) {
    nlohmann::json diff = nlohmann::json::object();
    for (const auto& [name, m] : sets) {
      if (name != kOwn) diff[name] = to_json(diff_contacts(*own, m), name);
    }
    doc["diff"] = diff;
  }
  std::cout << doc.dump(2) << '\n';
}

std::string cell(const char* format, double x) {
  char text[64];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

std::string vec_cell(const Vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%9.5f, %9.5f, %9.5f)", v.x(), v.y(), v.z());
  return text;
}

std::string optional_cell(const std::optional<double>& x, const char* format) {
  return x ? cell(format, *x) : std::string("-");
}

void print_table(const ContactsOptions& options, const ContactQuery& query, const ContactSets& sets) {
  std::cout << options.query << ": " << (query.b ? "box-box" : "box-plane") << "\n";
  if (!query.note.empty()) std::cout << "note: " << query.note << "\n";
  std::cout << '\n';
  char line[256];
  std::snprintf(line, sizeof line, "%-22s %2s  %-33s %-33s %12s\n", "detector", "#", "position (m)", "normal",
                "depth (m)");
  std::cout << line;
  for (const auto& [name, m] : sets) {
    if (m.empty()) {
      std::snprintf(line, sizeof line, "%-22s  -  no contact\n", name.c_str());
      std::cout << line;
    }
    for (int i = 0; i < m.size(); ++i) {
      std::snprintf(line, sizeof line, "%-22s %2d  %-33s %-33s %12.3e\n", i == 0 ? name.c_str() : "", i,
                    vec_cell(m[i].position).c_str(), vec_cell(m[i].normal).c_str(), m[i].depth);
      std::cout << line;
    }
  }
  const Manifold* own = own_set(sets);
  if (!own) return;
  std::snprintf(line, sizeof line, "\n%-22s %7s %12s %12s %12s %12s\n", "against own", "points", "angle (rad)",
                "depth diff", "hausdorff", "outside hull");
  std::cout << line;
  for (const auto& [name, m] : sets) {
    if (name == kOwn) continue;
    const ContactDiff d = diff_contacts(*own, m);
    std::snprintf(line, sizeof line, "%-22s %3d/%-3d %12s %12s %12s %12s\n", name.c_str(), d.base_points,
                  d.other_points, optional_cell(d.normal_angle, "%.2e").c_str(),
                  optional_cell(d.depth_difference, "%.2e").c_str(), optional_cell(d.hausdorff, "%.2e").c_str(),
                  optional_cell(d.hull_distance, "%.2e").c_str());
    std::cout << line;
  }
}

// The line protocol: a query per input line, an answer per output line, flushed at once (the
// other side waits for it). Blank lines are skipped.
int serve(const ContactsOptions& options) {
  const DetectorInfo& detector = find_detector(detector_of(options.engine));
  std::string line;
  for (int n = 1; std::getline(std::cin, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const ContactQuery query = parse_query(line, "stdin line " + std::to_string(n));
    std::cout << answer_json(detector.detect(query, detect_options(options))).dump() << std::endl;
  }
  return kExitOk;
}

}  // namespace

void add_contacts_command(CLI::App& app, ContactsOptions& options) {
  CLI::App* cmd = app.add_subcommand("contacts", "Print the contact sets of a box-box or box-plane query "
                                                 "from our detector and the reference engines, with diffs");
  CLI::Option* query = cmd->add_option("query", options.query, "Query file (JSON): boxes a and b, or box a and a plane");
  cmd->add_flag("--reduce", options.reduce, "Reduce our box-box manifold to at most 4 points");
  cmd->add_option("--engines", options.engines,
                  "Comma-separated detectors to show (own-impulse and own-penalty are own: one detector; "
                  "default: own, ode, bullet, and bullet-multipoint for a box-plane query); each is compared "
                  "with own when own is shown")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(detector_name());
  cmd->add_option("--format", options.format, "Output: table (the default on a terminal) or json (when piped)")
      ->check(CLI::IsMember({kTable, kJson}));
  CLI::Option* serve_flag = cmd->add_flag(
      "--serve", options.serve, "Answer queries on stdin, one JSON line each, with one detector (docs/conform.md)");
  cmd->add_option("--engine", options.engine, "The detector that answers under --serve")
      ->check(detector_name())
      ->needs(serve_flag)
      ->capture_default_str();
  add_input_limit_option(*cmd, options.max_input_bytes);
  serve_flag->excludes(query);
  cmd->callback([&options, query]() {
    if (!options.serve && query->count() == 0) throw CLI::RequiredError("query (or --serve)");
  });
}

int run_contacts(const ContactsOptions& options) {
  if (options.serve) return serve(options);
  check_distinct(options.engines, "--engines");
  const ContactQuery query = load_query(options.query, options.max_input_bytes);
  const ContactSets sets = contact_sets(options, query);
  const bool table = options.format.empty() ? isatty(STDOUT_FILENO) == 1 : options.format == kTable;
  if (table) {
    print_table(options, query, sets);
  } else {
    print_json(options, query, sets);
  }
  return kExitOk;
}

}  // namespace boxpile::cli
