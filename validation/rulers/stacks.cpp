#include "boxpile/validation/rulers/stacks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "boxpile/sim/collision/box.hpp"
#include "boxpile/sim/collision/box_plane.hpp"
#include "boxpile/sim/collision/broadphase.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/finite.hpp"

namespace boxpile {
namespace {

bool stacks_with_others(const Scene& scene, const RigidBody& body, std::size_t index) {
  return !body.fixed && !scene.bodies[index].wire;
}

// Union-find over body indices, with path halving.
int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    auto& p = parent[static_cast<std::size_t>(i)];
    p = parent[static_cast<std::size_t>(p)];
    i = p;
  }
  return i;
}

// The column height of a stack (Stack::column_height), its bodies lowest first: a connected group
// whose members touch at most two others and whose touching pairs number one fewer than its
// members is a path; it is a column when that path runs in the order of height from the one body
// on the ground.
std::optional<double> column_height(const std::vector<RigidBody>& bodies, const std::vector<int>& members,
                                    const std::vector<int>& degree, const std::vector<bool>& on_ground,
                                    const HalfSpace& ground, double tolerance) {
  int edges = 0;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const auto u = static_cast<std::size_t>(members[k]);
    if (bodies[u].shapes.size() != 1 || degree[u] > 2 || on_ground[u] != (k == 0)) return std::nullopt;
    edges += degree[u];
  }
  if (edges != 2 * (static_cast<int>(members.size()) - 1)) return std::nullopt;
  double sum = 0.0;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const RigidBody& body = bodies[static_cast<std::size_t>(members[k])];
    if (k > 0 && body_pair_depth(bodies[static_cast<std::size_t>(members[k - 1])], body) < -tolerance) {
      return std::nullopt;
    }
    const OrientedBox box = OrientedBox::from(body.shape_pose(0), body.shapes[0].half_extents);
    int up = 0;
    for (int a = 1; a < 3; ++a) {
      if (std::abs(box.axes.col(a).dot(ground.normal)) > std::abs(box.axes.col(up).dot(ground.normal))) up = a;
    }
    sum += 2.0 * box.half[up];
  }
  return sum;
}

}  // namespace

double top_height(const RigidBody& body, const HalfSpace& ground) {
  double top = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < static_cast<int>(body.shapes.size()); ++k) {
    const OrientedBox box =
        OrientedBox::from(body.shape_pose(k), body.shapes[static_cast<std::size_t>(k)].half_extents);
    // The highest vertex: the centre plus the box's half extent along the normal.
    top = std::max(top, ground.normal.dot(box.center) + box.radius_along(ground.normal) - ground.offset);
  }
  return top;
}

std::vector<Stack> find_stacks(const std::vector<RigidBody>& bodies, const Scene& scene, double tolerance) {
  if (!scene.ground) return {};
  const HalfSpace& ground = *scene.ground;
  const int n = static_cast<int>(bodies.size());
  std::vector<bool> member(bodies.size()), on_ground(bodies.size());
  std::vector<Aabb> boxes(bodies.size());
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    member[ui] = stacks_with_others(scene, bodies[ui], ui) && finite_magnitude(bodies[ui].x);
    if (!member[ui]) continue;
    boxes[ui] = body_aabb(bodies[ui], tolerance);
    for (int k = 0; k < static_cast<int>(bodies[ui].shapes.size()) && !on_ground[ui]; ++k) {
      const OrientedBox box = OrientedBox::from(bodies[ui].shape_pose(k),
                                                bodies[ui].shapes[static_cast<std::size_t>(k)].half_extents);
      on_ground[ui] = box_plane_depth(box, ground) >= -tolerance;
    }
  }

  std::vector<int> parent(bodies.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int> degree(bodies.size(), 0);  // touching members
  for (int i = 0; i < n; ++i) {
    if (!member[static_cast<std::size_t>(i)]) continue;
    for (int j = i + 1; j < n; ++j) {
      const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      if (!member[uj] || !boxes[ui].overlaps(boxes[uj])) continue;
      if (body_pair_depth(bodies[ui], bodies[uj]) < -tolerance) continue;
      ++degree[ui];
      ++degree[uj];
      parent[static_cast<std::size_t>(find_root(parent, i))] = find_root(parent, j);
    }
  }

  // Groups by root, kept only when some member touches the ground.
  std::vector<int> group_of(bodies.size(), -1);
  std::vector<Stack> stacks;
  std::vector<bool> grounded;
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (!member[ui]) continue;
    const auto root = static_cast<std::size_t>(find_root(parent, i));
    if (group_of[root] < 0) {
      group_of[root] = static_cast<int>(stacks.size());
      stacks.emplace_back();
      grounded.push_back(false);
    }
    const auto g = static_cast<std::size_t>(group_of[root]);
    stacks[g].bodies.push_back(i);
    grounded[g] = grounded[g] || on_ground[ui];
  }

  std::vector<Stack> result;
  for (std::size_t g = 0; g < stacks.size(); ++g) {
    if (!grounded[g]) continue;
    Stack s = std::move(stacks[g]);
    s.height = -std::numeric_limits<double>::infinity();
    for (int i : s.bodies) s.height = std::max(s.height, top_height(bodies[static_cast<std::size_t>(i)], ground));
    std::stable_sort(s.bodies.begin(), s.bodies.end(), [&](int a, int b) {
      return ground.normal.dot(bodies[static_cast<std::size_t>(a)].x) <
             ground.normal.dot(bodies[static_cast<std::size_t>(b)].x);
    });
    s.column_height = column_height(bodies, s.bodies, degree, on_ground, ground, tolerance);
    result.push_back(std::move(s));
  }
  return result;
}

std::vector<StackReport> report_stacks(const std::vector<Stack>& final_stacks,
                                       const std::vector<Stack>& start_stacks,
                                       const std::vector<RigidBody>& bodies) {
  auto sorted = [](std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  std::vector<StackReport> reports;
  for (const Stack& s : final_stacks) {
    StackReport r;
    for (int i : s.bodies) r.bodies.push_back(bodies[static_cast<std::size_t>(i)].name);
    r.height = s.height;
    const std::vector<int> members = sorted(s.bodies);
    for (const Stack& start : start_stacks) {
      if (sorted(start.bodies) != members) continue;
      r.ideal = start.height;
    }
    if (!r.ideal) r.ideal = s.column_height;
    if (r.ideal) r.error = s.height - *r.ideal;
    reports.push_back(std::move(r));
  }
  return reports;
}

}  // namespace boxpile
