// Contacts of bodies at rest kept from one step to the next (sim/collision/contact_reuse.hpp):
// copied only while both bodies stay within the tolerance of the poses they were found at, at the
// same margin and about the same place in the search, and a run that keeps them is the run that finds
// them again, to far below anything a contact can tell.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "boxpile/sim/collision/contact_reuse.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/sim/solver/impulse_method.hpp"
#include "boxpile/sim/world.hpp"

using namespace boxpile;

namespace {

constexpr double kTolerance = ContactReuse::kPoseTolerance;

RigidBody unit_box(const Vec3& centre) {
  return make_body("box", {BoxShape{Vec3::Constant(0.5), Vec3::Zero(), Quat::Identity()}}, 1.0,
                   Pose{centre, Quat::Identity()}, Vec3::Zero(), Vec3::Zero(), Material{}, false);
}

// A contact told apart by its depth: the step it was found at.
BodyContact contact(int a, int b, double found_at) {
  BodyContact c;
  c.body_a = a;
  c.body_b = b;
  c.contact.depth = found_at;
  return c;
}

// One step's search over `pairs` (body, body or kGround), each finding `points[k]` contacts
// stamped with `step`; returns the set.
struct Search {
  ContactReuse reuse;
  std::vector<BodyContact> contacts;
  int finds = 0;

  void step(const std::vector<RigidBody>& bodies, const std::vector<std::pair<int, int>>& pairs,
            const std::vector<int>& points, double step_no, double margin = 0.01) {
    reuse.begin(bodies, contacts);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const int a = pairs[k].first, b = pairs[k].second;
      reuse.pair(a, b, margin, contacts, [&] {
        ++finds;
        for (int p = 0; p < points[k]; ++p) contacts.push_back(contact(a, b, step_no));
      });
    }
  }
};

Scene scene_file(const std::string& path) { return load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/" + path); }

// The largest distance between the same body's centres in two worlds, m.
double largest_distance(const World& a, const World& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.bodies().size(); ++i) d = std::max(d, (a.bodies()[i].x - b.bodies()[i].x).norm());
  return d;
}

}  // namespace

TEST_CASE("a pair's contacts are copied only while both bodies stay within the tolerance", "[contacts][reuse]") {
  std::vector<RigidBody> bodies = {unit_box(Vec3(0, 0, 0.5)), unit_box(Vec3(0, 0, 1.5))};
  const std::vector<std::pair<int, int>> pairs = {{0, kGround}, {0, 1}};
  Search s;
  s.reuse.reserve(bodies.size(), 16, 4, true);

  s.step(bodies, pairs, {4, 4}, 1.0);
  CHECK(s.finds == 2);  // nothing to copy from yet
  CHECK(s.reuse.found_pairs() == 2);

  // Moved by rounding (half the tolerance): both pairs copied, with last step's contacts.
  bodies[1].x.z() += 0.5 * kTolerance;
  s.step(bodies, pairs, {4, 4}, 2.0);
  CHECK(s.finds == 2);
  CHECK(s.reuse.reused_pairs() == 2);
  REQUIRE(s.contacts.size() == 8);
  for (const BodyContact& c : s.contacts) CHECK(c.contact.depth == 1.0);
  CHECK(std::count(s.reuse.same_as_last_step().begin(), s.reuse.same_as_last_step().end(), 1) == 8);

  // Body 1 moves beyond the tolerance (measured from the pose its contacts were found at, so a
  // second half-tolerance step counts): only its pair is found again.
  bodies[1].x.z() += 0.6 * kTolerance;
  s.step(bodies, pairs, {4, 4}, 3.0);
  CHECK(s.finds == 3);
  CHECK(s.contacts[0].contact.depth == 1.0);
  CHECK(s.contacts[4].contact.depth == 3.0);

  // A turn beyond the tolerance counts as a move as well.
  bodies[0].q = Quat(Eigen::AngleAxisd(4.0 * kTolerance, Vec3::UnitX()));
  s.step(bodies, pairs, {4, 4}, 4.0);
  CHECK(s.finds == 5);

  // At rest again: a changed margin finds the pair again, the same margin copies it.
  s.step(bodies, pairs, {4, 4}, 5.0, 0.01 + 2.0 * kTolerance);
  CHECK(s.finds == 7);
  s.step(bodies, pairs, {4, 4}, 6.0, 0.01 + 2.0 * kTolerance);
  CHECK(s.finds == 7);
}

TEST_CASE("a copied contact is the same as last step's only where it keeps its index", "[contacts][reuse]") {
  std::vector<RigidBody> bodies = {unit_box(Vec3(0, 0, 0.5)), unit_box(Vec3(3, 0, 0.5)), unit_box(Vec3(0, 0, 1.5))};
  Search s;
  s.reuse.reserve(bodies.size(), 16, 4, true);
  s.step(bodies, {{0, kGround}, {1, kGround}, {0, 2}}, {4, 4, 4}, 1.0);

  // Body 1 moves and its pair now finds 3 points: the pair after it is still copied (its bodies
  // have not moved) but lands one index earlier, so the solver must not take it for last step's.
  bodies[1].x.x() += 1e-3;
  s.step(bodies, {{0, kGround}, {1, kGround}, {0, 2}}, {4, 3, 4}, 2.0);
  CHECK(s.reuse.reused_pairs() == 2);
  const std::vector<char>& same = s.reuse.same_as_last_step();
  REQUIRE(same.size() == 11);
  CHECK(std::count(same.begin(), same.begin() + 4, 1) == 4);
  CHECK(std::count(same.begin() + 4, same.end(), 1) == 0);

  // The same pairs asked in another order: each is still copied (last step's search had it a few
  // places away), but none lands at its index of last step.
  s.step(bodies, {{0, 2}, {0, kGround}, {1, kGround}}, {4, 4, 3}, 3.0);
  CHECK(s.reuse.reused_pairs() == 3);
  CHECK(std::count(s.reuse.same_as_last_step().begin(), s.reuse.same_as_last_step().end(), 1) == 0);
}

TEST_CASE("a pair is looked for within 16 places of where last step's search had it", "[contacts][reuse]") {
  std::vector<RigidBody> bodies;
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < 20; ++i) {
    bodies.push_back(unit_box(Vec3(2.0 * i, 0, 0.5)));
    pairs.emplace_back(i, kGround);
  }
  Search s;
  s.reuse.reserve(bodies.size(), 64, 32, true);
  s.step(bodies, pairs, std::vector<int>(20, 1), 1.0);
  // In reverse order, pair k moves |19 - 2k| places: the four that move 17 or 19 are found again.
  std::reverse(pairs.begin(), pairs.end());
  s.step(bodies, pairs, std::vector<int>(20, 1), 2.0);
  CHECK(s.reuse.found_pairs() == 4);
  CHECK(s.reuse.reused_pairs() == 16);
}

TEST_CASE("a run that keeps contacts at rest is the run that finds them at every step", "[contacts][reuse]") {
  // Scenes at rest (every pair copied once settled) and one that keeps moving, 2 s each. The two
  // runs differ by rounding-size offsets of the contacts kept: measured 0 (stack_10), 4e-18 m (the
  // pyramid) and 8.5e-13 m (the Jenga tower), gated at 1e-10 m, far below the 1e-4 m penetration
  // slop.
  const auto path = GENERATE(as<std::string>{}, "scenes/stack_10.json", "scenes/pyramid.json", "hard/jenga.json",
                             "scenes/incline_slide.json");
  Scene s = scene_file(path);
  s.time.duration = std::min(s.time.duration, 2.0);
  World kept(s);
  s.collision.reuse_contacts = false;
  World found(s);
  const auto steps = step_count(s.time.dt, s.time.duration);
  for (long k = 0; k < steps; ++k) {
    kept.step();
    found.step();
  }
  INFO(path);
  CHECK(largest_distance(kept, found) < 1e-10);
  CHECK(found.counters().pairs_reused == 0);
  CHECK(found.method_as<ImpulseMethod>()->counters().same_contact_sets == 0);
  if (path == "scenes/incline_slide.json") {
    CHECK(kept.counters().pairs_reused == 0);  // the sliding box moves at every step
  } else {
    // Over the last second every pair copied, and every step's contact set the last step's (shock
    // propagation keeps its levels and groups).
    const auto reused_before = kept.counters().pairs_reused;
    const auto found_before = kept.counters().pairs_found;
    const auto sets_before = kept.method_as<ImpulseMethod>()->counters().same_contact_sets;
    const long last_second = step_count(s.time.dt, 1.0);
    for (long k = 0; k < last_second; ++k) kept.step();
    const auto found_pairs = kept.counters().pairs_found - found_before;
    const auto reused = kept.counters().pairs_reused - reused_before;
    const auto same_sets = kept.method_as<ImpulseMethod>()->counters().same_contact_sets - sets_before;
    if (path == "hard/jenga.json") {
      // The tower's upper layers creep together by some 2e-15 m a step: every few hundred steps
      // they pass the tolerance and their pairs (a fifth of the tower's) are found again.
      CHECK(found_pairs * 100 <= found_pairs + reused);
      CHECK(same_sets * 100 >= 95 * static_cast<std::uint64_t>(last_second));
    } else {
      CHECK(found_pairs == 0);
      CHECK(same_sets == static_cast<std::uint64_t>(last_second));
    }
    CHECK(reused > 0);
  }
}

TEST_CASE("the penalty method tests every pair at every step", "[contacts][reuse]") {
  // Its springs read each contact's depth: a copy would leave it up to the tolerance stale, and a
  // box at rest on its springs would ring at 1e-10 m/s instead of resting to rounding.
  Scene s = scene_file("scenes/stack_5.json");
  s.solver.method = "penalty";
  World w(s);
  for (int k = 0; k < 240; ++k) w.step();
  CHECK(w.counters().pairs_reused == 0);
  CHECK(w.counters().pairs_found > 0);
}
