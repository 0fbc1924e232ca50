#include "boxpile/validation/stacks.hpp"

#include <algorithm>
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
  for (int i = 0; i < n; ++i) {
    if (!member[static_cast<std::size_t>(i)]) continue;
    for (int j = i + 1; j < n; ++j) {
      const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      if (!member[uj] || !boxes[ui].overlaps(boxes[uj])) continue;
      if (body_pair_depth(bodies[ui], bodies[uj]) < -tolerance) continue;
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
      r.error = s.height - start.height;
    }
    reports.push_back(std::move(r));
  }
  return reports;
}

}  // namespace boxpile
