// Grouping a phase's contacts by the moving bodies they share (sim/solver/body_groups.hpp), which
// shock propagation and penetration recovery both use, and their stall rule.
#include <catch2/catch.hpp>

#include <vector>

#include "boxpile/sim/solver/body_groups.hpp"

using namespace boxpile;

namespace {

// A contact of the test: an id to follow it, and its moving bodies.
struct Item {
  int id = 0;
  MovingBodies bodies;
};

std::vector<std::vector<int>> sorted_ids(BodyGroups& groups, const std::vector<Item>& items, std::size_t bodies) {
  std::vector<Item> grouped;
  groups.sort(std::span<const Item>(items), bodies, [](const Item& i) { return i.bodies; }, grouped);
  std::vector<std::vector<int>> ids;
  for (int g = 0; g < groups.count(); ++g) {
    ids.emplace_back();
    for (const Item& i : groups.group(grouped, g)) ids.back().push_back(i.id);
  }
  return ids;
}

}  // namespace

TEST_CASE("contacts are grouped by shared moving bodies, groups in order of their first contact", "[solver][groups]") {
  BodyGroups groups;
  // Bodies 0-5. Contacts 0, 3 touch body 4 alone; 1 links 2 and 0; 2 touches body 1; 4 links 1
  // and 3; 5 touches body 0; 6 touches body 5. Groups: {4}, {0, 2}, {1, 3}, {5}.
  const std::vector<Item> items = {{0, {4, -1}}, {1, {2, 0}}, {2, {1, -1}}, {3, {4, -1}},
                                   {4, {3, 1}},  {5, {0, -1}}, {6, {5, -1}}};
  const auto ids = sorted_ids(groups, items, 6);
  CHECK(ids == std::vector<std::vector<int>>{{0, 3}, {1, 5}, {2, 4}, {6}});
}

TEST_CASE("a chain of links joins its bodies into one group whatever the order of the links", "[solver][groups]") {
  BodyGroups groups;
  // 3-2, then 0-1, then 1-2: all four bodies end in one group, numbered at contact 0.
  const std::vector<Item> items = {{0, {3, 2}}, {1, {0, 1}}, {2, {2, -1}}, {3, {1, 2}}, {4, {0, -1}}};
  CHECK(sorted_ids(groups, items, 4) == std::vector<std::vector<int>>{{0, 1, 2, 3, 4}});
}

TEST_CASE("a BodyGroups sorts again with other bodies and other counts", "[solver][groups]") {
  BodyGroups groups;
  const std::vector<Item> first = {{0, {0, 1}}, {1, {2, -1}}};
  CHECK(sorted_ids(groups, first, 3) == std::vector<std::vector<int>>{{0}, {1}});
  // The same bodies in other groups: nothing of the first sort stays behind.
  const std::vector<Item> second = {{0, {2, -1}}, {1, {1, 2}}, {2, {0, -1}}};
  CHECK(sorted_ids(groups, second, 3) == std::vector<std::vector<int>>{{0, 1}, {2}});
  // More bodies than before, and an empty phase.
  const std::vector<Item> third = {{0, {7, -1}}, {1, {6, -1}}, {2, {7, 6}}};
  CHECK(sorted_ids(groups, third, 8) == std::vector<std::vector<int>>{{0, 1, 2}});
  CHECK(sorted_ids(groups, {}, 8).empty());
}

TEST_CASE("passes stall after `patience` passes without a new low by `factor`", "[solver][groups]") {
  PassProgress progress(0.9, 3);
  CHECK(progress.made(1.0));    // the first pass is progress
  CHECK(progress.made(0.5));    // below 0.9 of 1.0
  CHECK(progress.made(0.46));   // not below 0.45: one pass without progress
  CHECK(progress.made(0.47));   // two
  CHECK(progress.made(0.44));   // below 0.45: progress again, the count starts over
  CHECK(progress.made(0.44));   // one
  CHECK(progress.made(0.40));   // two (0.40 is not below 0.396)
  CHECK_FALSE(progress.made(0.399));  // three in a row: stalled
}
