#include <iostream>

#include "sim/collision/box_box.hpp"
#include "sim/collision/box_plane.hpp"
#include "sim/io/query_loader.hpp"
#include "validation/cli/commands.hpp"
#include "validation/cli/json_output.hpp"

namespace boxpile::cli {

void add_contacts_command(CLI::App& app, ContactsOptions& options) {
  CLI::App* cmd = app.add_subcommand("contacts", "Print the contact set of a box-box or box-plane query");
  cmd->add_option("query", options.query, "Query file (JSON): boxes a and b, or box a and a plane")
      ->required();
  cmd->add_flag("--reduce", options.reduce, "Reduce each box-box manifold to at most 4 points");
}

int run_contacts(const ContactsOptions& options) {
  const ContactQuery query = load_query(options.query);
  const OrientedBox a = OrientedBox::from(query.a.pose, query.a.half_extents);
  CollisionSettings settings;
  settings.reduce_to_four = options.reduce;

  Manifold m;
  if (query.b) {
    collide_box_box(a, OrientedBox::from(query.b->pose, query.b->half_extents), settings, m);
  } else {
    collide_box_plane(a, *query.plane, settings.margin, m);
  }

  nlohmann::json contacts = nlohmann::json::array();
  for (const Contact& c : m) contacts.push_back(to_json(c));
  const nlohmann::json doc = {{"engines", {{"own", {{"contacts", contacts}}}}}};
  std::cout << doc.dump(2) << '\n';
  return kExitOk;
}

}  // namespace boxpile::cli
