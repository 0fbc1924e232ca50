// The broadphase: bounding boxes from placed boxes equal those from the bodies, and the
// incremental sweep-and-prune finds exactly the overlapping pairs, step after step, as the bodies
// move and its kept sort order goes stale.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "boxpile/sim/collision/broadphase.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/tests/support/geometry.hpp"

using namespace boxpile;
using namespace boxpile::test;

namespace {

// n bodies at random poses in a 4 m cube; every third a compound of two boxes, one fixed.
std::vector<RigidBody> random_bodies(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> pos(-2.0, 2.0), size(0.05, 0.5);
  Scene s;
  for (int i = 0; i < n; ++i) {
    BodyDesc b;
    b.name = std::string("b").append(std::to_string(i));
    b.boxes = {BoxShape{Vec3(size(rng), size(rng), size(rng)), Vec3::Zero(), Quat::Identity()}};
    if (i % 3 == 0) b.boxes.push_back(BoxShape{Vec3(size(rng), 0.1, 0.1), Vec3(0.4, 0, 0), Quat::UnitRandom()});
    b.frame = {Vec3(pos(rng), pos(rng), pos(rng)), Quat::UnitRandom()};
    b.fixed = i == 1;
    s.bodies.push_back(b);
  }
  return make_bodies(s);
}

// Every overlapping pair by testing all of them.
std::set<std::pair<int, int>> all_pairs(const std::vector<RigidBody>& bodies, double margin) {
  std::set<std::pair<int, int>> out;
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(bodies.size()); ++j)
      if (body_aabb(bodies[i], margin).overlaps(body_aabb(bodies[j], margin))) out.insert({i, j});
  return out;
}

}  // namespace

TEST_CASE("bounding boxes of placed boxes are the bodies' own, to the bit", "[broadphase]") {
  std::mt19937_64 rng(test_seed(3));
  const std::vector<RigidBody> bodies = random_bodies(60, rng);
  PlacedBoxes placed(bodies);
  placed.place(bodies);
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    const Aabb from_body = body_aabb(bodies[i], 0.01);
    const Aabb from_placed = boxes_aabb(placed.of(i), 0.01);
    CHECK(from_body.lo == from_placed.lo);
    CHECK(from_body.hi == from_placed.hi);
  }
}

TEST_CASE("the incremental sweep finds exactly the overlapping pairs as bodies move", "[broadphase]") {
  std::mt19937_64 rng(test_seed(5));
  std::vector<RigidBody> bodies = random_bodies(80, rng);
  const std::vector<double> margins(bodies.size(), 0.02);
  std::vector<char> fixed;
  for (const RigidBody& b : bodies) fixed.push_back(b.fixed);
  SweepAndPrune from_bodies, from_boxes;
  std::normal_distribution<double> step(0.0, 0.15);  // large moves: the kept order goes stale
  for (int k = 0; k < 20; ++k) {
    std::set<std::pair<int, int>> expected = all_pairs(bodies, 0.02);
    std::erase_if(expected, [&](const auto& p) { return bodies[p.first].fixed && bodies[p.second].fixed; });
    const auto& found = from_bodies.find_pairs(bodies, margins);
    CHECK(std::set<std::pair<int, int>>(found.begin(), found.end()) == expected);
    CHECK(found.size() == expected.size());  // no pair twice

    std::vector<Aabb> boxes;
    for (std::size_t i = 0; i < bodies.size(); ++i) boxes.push_back(body_aabb(bodies[i], margins[i]));
    const auto& same = from_boxes.find_pairs(boxes, fixed);
    CHECK(same == found);  // the same pairs in the same order: the contact order depends on it

    for (RigidBody& b : bodies)
      if (!b.fixed) b.x += Vec3(step(rng), step(rng), step(rng));
  }
}

TEST_CASE("bodies whose bounds differ by less than the sweep's grain keep their order, and no overlap is missed",
          "[broadphase]") {
  // Columns of unit boxes with equal lower x (a stack, a tower; each box 1 um into the one below),
  // neighbouring columns overlapping along x by a third of the grain, and a row whose neighbours
  // are apart by as little: step after step,
  // each x moved by rounding-size noise, the sweep must give the same pairs in the same order (the
  // order exact bounds would swap at random), and exactly the overlapping ones.
  const double overlap = SweepAndPrune::kOrderGrain / 3.0;
  Scene s;
  auto add = [&](const Vec3& centre) {
    BodyDesc b;
    b.name = std::string("b").append(std::to_string(s.bodies.size()));
    b.boxes = {BoxShape{Vec3::Constant(0.5), Vec3::Zero(), Quat::Identity()}};
    b.frame = {centre, Quat::Identity()};
    s.bodies.push_back(b);
  };
  for (int column = 0; column < 3; ++column)
    for (int level = 0; level < 4; ++level) add(Vec3(column * (1.0 - overlap), 0.0, 0.5 + level * (1.0 - 1e-6)));
  for (int k = 0; k < 4; ++k) add(Vec3(k * (1.0 + overlap), 5.0, 0.5));  // apart by a third of a grain
  std::vector<RigidBody> bodies = make_bodies(s);
  const std::vector<RigidBody> start = bodies;
  const std::vector<double> margins(bodies.size(), 0.0);

  SweepAndPrune sweep;
  std::mt19937_64 rng(test_seed(6));
  std::uniform_real_distribution<double> noise(-1e-15, 1e-15);
  std::vector<std::pair<int, int>> first;
  for (int k = 0; k < 50; ++k) {
    for (std::size_t i = 0; i < bodies.size(); ++i) bodies[i].x = start[i].x + Vec3::Constant(noise(rng));
    const auto& found = sweep.find_pairs(bodies, margins);
    const std::set<std::pair<int, int>> expected = all_pairs(bodies, 0.0);
    CHECK(std::set<std::pair<int, int>>(found.begin(), found.end()) == expected);
    if (k == 0) {
      first = found;
      // Each column: 3 pairs up the column, and each box touches the neighbouring columns' boxes
      // at its level and the levels beside it (overlapping by a third of a grain along x); the
      // row's boxes are apart.
      CHECK(expected.size() == 3 * 3 + 2 * (4 + 2 * 3));
    }
    CHECK(found == first);
  }
}
