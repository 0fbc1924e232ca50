#include <algorithm>
#include <iostream>
#include <string_view>
#include <vector>

#include "reference/reference_contacts.hpp"
#include "sim/collision/box_box.hpp"
#include "sim/collision/box_plane.hpp"
#include "sim/io/query_loader.hpp"
#include "validation/cli/commands.hpp"
#include "validation/cli/json_output.hpp"
#include "validation/contact_diff.hpp"

namespace boxpile::cli {
namespace {

// The detectors `contacts` can show. "bullet_multipoint" is Bullet with
// setPlaneConvexMultipointIterations(3, 3): it differs from "bullet" on box-plane queries only.
constexpr std::string_view kOwn = "own";
// own-impulse and own-penalty name our engine with a forced contact method; the contact set is the
// same for both, so they are "own" here.
const std::vector<std::string> kDetectors = {"own", "own-impulse", "own-penalty", "ode", "bullet",
                                             "bullet_multipoint"};

std::string detector_of(const std::string& name) {
  return name == "own-impulse" || name == "own-penalty" ? std::string(kOwn) : name;
}

Manifold detect(std::string_view name, const ContactQuery& query, bool reduce) {
  const OrientedBox a = OrientedBox::from(query.a.pose, query.a.half_extents);
  Manifold m;
  if (query.b) {
    const OrientedBox b = OrientedBox::from(query.b->pose, query.b->half_extents);
    if (name == kOwn) {
      CollisionSettings settings;
      settings.reduce_to_four = reduce;
      collide_box_box(a, b, settings, m);
    } else if (name == "ode") {
      m = ode_box_box(a, b);
    } else {
      m = bullet_box_box(a, b);
    }
  } else {
    const HalfSpace& plane = *query.plane;
    if (name == kOwn) {
      collide_box_plane(a, plane, 0.0, m);
    } else if (name == "ode") {
      m = ode_box_plane(a, plane);
    } else if (name == "bullet") {
      m = bullet_box_plane(a, plane);
    } else {
      m = bullet_box_plane(a, plane, kBulletMultipoint);
    }
  }
  return m;
}

nlohmann::json optional_number(const std::optional<double>& x) {
  return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
}

nlohmann::json to_json(const ContactDiff& d, std::string_view reference) {
  return {{"points", {{std::string(kOwn), d.own_points}, {std::string(reference), d.reference_points}}},
          {"normal_angle", optional_number(d.normal_angle)},
          {"depth_difference", optional_number(d.depth_difference)},
          {"hausdorff", optional_number(d.hausdorff)},
          {"hull_distance", optional_number(d.hull_distance)},
          {"smaller_inside_hull", d.inside_hull},
          {"tested", d.reference_tested ? std::string(reference) : std::string(kOwn)}};
}

}  // namespace

void add_contacts_command(CLI::App& app, ContactsOptions& options) {
  CLI::App* cmd = app.add_subcommand("contacts", "Print the contact sets of a box-box or box-plane query "
                                                 "from our detector and the reference engines, with diffs");
  cmd->add_option("query", options.query, "Query file (JSON): boxes a and b, or box a and a plane")
      ->required();
  cmd->add_flag("--reduce", options.reduce, "Reduce our box-box manifold to at most 4 points");
  cmd->add_option("--engines", options.engines,
                  "Comma-separated detectors to show: own (own-impulse and own-penalty are the same "
                  "detector), ode, bullet, bullet_multipoint (default: own, "
                  "ode, bullet, and bullet_multipoint for a box-plane query). \"diff\" compares each "
                  "reference with own when own is shown.")
      ->delimiter(',')
      ->check(CLI::IsMember(kDetectors));
}

int run_contacts(const ContactsOptions& options) {
  check_distinct(options.engines, "--engines");
  const ContactQuery query = load_query(options.query);
  std::vector<std::string> names = options.engines;
  if (names.empty()) {
    names = {"own", "ode", "bullet"};
    if (query.plane) names.emplace_back("bullet_multipoint");
  }

  nlohmann::json engines = nlohmann::json::object();
  std::vector<std::pair<std::string, Manifold>> results;
  for (const std::string& listed : names) {
    const std::string name = detector_of(listed);
    if (engines.contains(name)) continue;  // listed twice
    const Manifold m = detect(name, query, options.reduce);
    nlohmann::json contacts = nlohmann::json::array();
    for (const Contact& c : m) contacts.push_back(to_json(c));
    engines[name] = {{"contacts", contacts}};
    results.emplace_back(name, m);
  }

  nlohmann::json doc = {{"query", options.query},
                        {"kind", query.b ? "box-box" : "box-plane"},
                        {"engines", engines}};
  const auto own = std::find_if(results.begin(), results.end(), [](const auto& r) { return r.first == kOwn; });
  if (own != results.end()) {
    nlohmann::json diff = nlohmann::json::object();
    for (const auto& [name, m] : results) {
      if (name != kOwn) diff[name] = to_json(diff_contacts(own->second, m), name);
    }
    doc["diff"] = diff;
  }
  std::cout << doc.dump(2) << '\n';
  return kExitOk;
}

}  // namespace boxpile::cli
