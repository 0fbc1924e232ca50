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

TEST_CASE("the sweep by cells gives the plain sweep's pairs in the plain sweep's order", "[broadphase]") {
  // A lattice of unit boxes touching face to face (bounds on whole metres, where cell edges can
  // fall), random boxes of 0.05-0.6 m among and above it, a few boxes of 5-15 m spanning many
  // cells, some fixed; moved at random between calls. The plain sweep's pairs are checked
  // against every pair tested, and the cells' must be the same list.
  std::mt19937_64 rng(test_seed(7));
  std::vector<Aabb> boxes;
  std::vector<char> fixed;
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 6; ++z) {
        boxes.push_back({Vec3(x, y, z), Vec3(x + 1, y + 1, z + 1)});
        fixed.push_back(z == 0 ? 1 : 0);
      }
  std::uniform_real_distribution<double> pos(-2.0, 14.0), size(0.05, 0.6), large(5.0, 15.0), unit(0.0, 1.0);
  for (int k = 0; k < 900; ++k) {
    const Vec3 lo(pos(rng), pos(rng), pos(rng) * 0.6);
    const bool huge = k % 150 == 0;
    const Vec3 extent = huge ? Vec3(size(rng), large(rng), large(rng)) : Vec3(size(rng), size(rng), size(rng));
    boxes.push_back({lo, lo + extent});
    fixed.push_back(unit(rng) < 0.05 ? 1 : 0);
  }
  const int n = static_cast<int>(boxes.size());
  REQUIRE(n >= SweepAndPrune::kCellsFrom);
  SweepAndPrune plain(SweepAndPrune::Search::sweep), by_cells(SweepAndPrune::Search::cells), automatic;
  std::normal_distribution<double> step(0.0, 0.05);
  for (int round = 0; round < 8; ++round) {
    std::set<std::pair<int, int>> expected;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (!(fixed[i] && fixed[j]) && boxes[i].overlaps(boxes[j])) expected.insert({i, j});
    const std::vector<std::pair<int, int>> swept = plain.find_pairs(boxes, fixed);
    CHECK(plain.cells() == 1);
    CHECK(std::set<std::pair<int, int>>(swept.begin(), swept.end()) == expected);
    CHECK(swept.size() == expected.size());
    CHECK(by_cells.find_pairs(boxes, fixed) == swept);  // the same pairs in the same order
    CHECK(by_cells.cells() > 16);
    CHECK(automatic.find_pairs(boxes, fixed) == swept);
    CHECK(automatic.cells() == by_cells.cells());
    for (int i = 0; i < n; ++i) {
      if (fixed[i]) continue;
      // The lattice's boxes keep their whole-metre bounds in every other round.
      if (i < 8 * 8 * 6 && round % 2 == 1) continue;
      const Vec3 move(step(rng), step(rng), step(rng));
      boxes[i].lo += move;
      boxes[i].hi += move;
    }
  }
}

TEST_CASE("the sweep by cells stops above the cap on pairs as the plain sweep does", "[broadphase]") {
  // 400 coincident boxes make 79,800 pairs; with a cap of 1,000 both searches return 1,001 and
  // stop, and below the cap both return every pair.
  std::vector<Aabb> boxes;
  for (int k = 0; k < 400; ++k) {
    const Vec3 lo(0.01 * (k % 7), 0.01 * (k % 5), 0.01 * (k % 3));
    boxes.push_back({lo, lo + Vec3::Constant(1.0)});
  }
  // Far boxes so that the grid has more than one cell.
  for (int k = 0; k < 100; ++k) {
    const Vec3 lo(3.0 * (k + 1), 3.0 * (k % 10), 3.0 * (k % 4));
    boxes.push_back({lo, lo + Vec3::Constant(0.5)});
  }
  const std::vector<char> fixed(boxes.size(), 0);
  SweepAndPrune plain(SweepAndPrune::Search::sweep), by_cells(SweepAndPrune::Search::cells);
  CHECK(plain.find_pairs(boxes, fixed, 1000).size() == 1001);
  CHECK(by_cells.find_pairs(boxes, fixed, 1000).size() == 1001);
  CHECK(by_cells.cells() > 1);
  const std::size_t all = 400 * 399 / 2;
  CHECK(plain.find_pairs(boxes, fixed, all).size() == all);
  CHECK(by_cells.find_pairs(boxes, fixed, all) == plain.find_pairs(boxes, fixed, all));
}
