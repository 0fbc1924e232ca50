// boxpile's everyday API in one include: #include <boxpile/boxpile.hpp>, link boxpile::validation
// (find_package(boxpile) in CMake; docs/tutorial.md).
//
//   const boxpile::Scene scene = boxpile::load_scene("stack_5.json");
//   const auto engine = boxpile::make_engine("ode", scene);         // "own", "ode", "bullet"
//   engine->step();
//   std::vector<boxpile::BodyState> states;
//   engine->body_states(states);
//
//   boxpile::Manifold m = boxpile::ode_box_box(a, b);               // or collide_box_box, bullet_...
//   boxpile::ContactDiff d = boxpile::diff_contacts(ours, m);
//   boxpile::CheckResult r = boxpile::check_collider(my_collider);  // judge your own collider
#pragma once

// Scenes, bodies and the one Engine interface.
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/io/query_loader.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/scene.hpp"
// Contacts: the types, our detectors, ODE's and Bullet's, and the table of all of them by name.
#include "boxpile/reference/bullet/bullet_contacts.hpp"
#include "boxpile/reference/ode/ode_contacts.hpp"
#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/sim/collision/contact.hpp"
#include "boxpile/validation/contacts/detectors.hpp"
// Engines by name, comparing contact sets, and the judge of a collider.
#include "boxpile/validation/contacts/contact_diff.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/conform/judge/check_collider.hpp"
#include "boxpile/validation/conform/judge/judge.hpp"
