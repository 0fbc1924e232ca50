// The impulse method on several threads: islands of touching bodies are solved independently, so
// the bodies' states after every step are the same to the bit whatever `solver.threads` is. Compared
// on scenes in motion, where islands form, merge and split from step to step: pile_100 falling
// onto the ground and the bone sliding into its pile. And the pool's rule for when a run is shared.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/thread_pool.hpp"
#include "boxpile/sim/world.hpp"

using namespace boxpile;

namespace {

Scene scene_with_threads(const std::string& name, int threads) {
  Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + name + ".json");
  scene.solver.threads = threads;
  return scene;
}

// Whether two doubles are the same bits (so that -0 and +0, or two NaNs, are told apart as well).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The first step and body whose state (position, orientation, momenta) differs between the worlds,
// as text; empty when every step agrees to the bit.
std::string first_difference(World& one, World& other, int steps) {
  for (int k = 1; k <= steps; ++k) {
    one.step();
    other.step();
    const std::vector<RigidBody>& a = one.bodies();
    const std::vector<RigidBody>& b = other.bodies();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const RigidBody& p = a[i];
      const RigidBody& q = b[i];
      const double pa[] = {p.x.x(), p.x.y(), p.x.z(), p.q.w(), p.q.x(), p.q.y(), p.q.z(),
                           p.P.x(), p.P.y(), p.P.z(), p.L.x(), p.L.y(), p.L.z()};
      const double qa[] = {q.x.x(), q.x.y(), q.x.z(), q.q.w(), q.q.x(), q.q.y(), q.q.z(),
                           q.P.x(), q.P.y(), q.P.z(), q.L.x(), q.L.y(), q.L.z()};
      for (std::size_t c = 0; c < std::size(pa); ++c)
        if (!same_bits(pa[c], qa[c]))
          return "step " + std::to_string(k) + ", body " + p.name + ", state component " + std::to_string(c);
    }
  }
  return "";
}

}  // namespace

TEST_CASE("pile_100 in motion: one thread and two give the same states to the bit", "[threads]") {
  // 2 s at 240 Hz: the pile falls, lands, tumbles and settles; islands change at every step.
  World one(scene_with_threads("pile_100", 1));
  World two(scene_with_threads("pile_100", 2));
  CHECK(one.threads() == 1);
  CHECK(two.threads() == 2);
  CHECK(first_difference(one, two, 480) == "");
  CHECK(one.events().size() == two.events().size());
}

TEST_CASE("the bone hitting its pile: one thread and three give the same states to the bit", "[threads]") {
  // More workers than cores: which worker takes which island changes, the result does not.
  World one(scene_with_threads("bone_hits_pile", 1));
  World three(scene_with_threads("bone_hits_pile", 3));
  CHECK(first_difference(one, three, 600) == "");
}

TEST_CASE("solver.threads 0 takes every core of the machine", "[threads]") {
  World world(scene_with_threads("stack_5", 0));
  CHECK(world.threads() == resolve_threads(0));
  CHECK(world.threads() >= 1);
}

TEST_CASE("the pool shares a run only when the other threads could take enough of it", "[threads]") {
  ThreadPool pool(2);
  CHECK(pool.size() == 2);
  CHECK_FALSE(pool.shares(0.0));
  CHECK_FALSE(pool.shares(ThreadPool::kMinSharedSeconds * 0.99));
  CHECK(pool.shares(ThreadPool::kMinSharedSeconds));
  CHECK_FALSE(ThreadPool(1).shares(1.0));  // no worker to share with

  // Too little to share: the items run in order on the caller's thread, as worker 0.
  std::vector<int> order, workers;
  pool.run(5, [&](int item, int worker) {
    order.push_back(item);
    workers.push_back(worker);
  }, 0.0);
  CHECK(order == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(workers == std::vector<int>(5, 0));

  // Shared: every item runs once, each on one of the pool's workers, and item 0 on the caller's.
  constexpr int kItems = 1000;
  std::vector<int> runs(kItems, 0), by(kItems, -1);
  pool.run(kItems, [&](int item, int worker) {
    ++runs[static_cast<std::size_t>(item)];
    by[static_cast<std::size_t>(item)] = worker;
  }, 1.0);
  CHECK(std::count(runs.begin(), runs.end(), 1) == kItems);
  CHECK(by[0] == 0);
  CHECK(std::all_of(by.begin(), by.end(), [](int w) { return w == 0 || w == 1; }));
}
