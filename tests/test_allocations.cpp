// No heap allocation inside a step: a counting global operator new, in a test binary of its own
// (replacing operator new in the main test binary would count Catch2's own allocations too).
// Every step's storage is sized when the world is built, so stepping allocates nothing; the
// penalty method sizes its anchors' storage in its first steps. Catch2's runner and main() come
// from Catch2::Catch2WithMain, as in the other test programs.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/world.hpp"

namespace {
std::atomic<long> g_allocations{0};
// Where the first test's buffer escapes to, so that the compiler cannot drop its allocation.
std::vector<int>* volatile g_escape = nullptr;
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  ++g_allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace boxpile;

TEST_CASE("the counter sees allocations", "[allocations]") {
  const long before = g_allocations;
  std::vector<int> v(100);
  g_escape = &v;
  CHECK(g_allocations - before == 1);  // the vector's buffer
  g_escape = nullptr;
}

TEST_CASE("1,000 steps of pile_100 allocate nothing, on one thread and on two", "[allocations]") {
  Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/pile_100.json");
  const int threads = GENERATE(1, 2);
  scene.solver.threads = threads;
  World world(scene);
  REQUIRE(world.threads() == threads);
  constexpr int kSteps = 1000;
  const long before = g_allocations;
  for (int k = 0; k < kSteps; ++k) world.step();
  const long allocations = g_allocations - before;
  std::vector<BodyContact> contacts;
  world.contacts(contacts);
  INFO("contact points in the last step: " << contacts.size() << ", collision events " << world.events().size());
  CHECK(allocations == 0);
}

TEST_CASE("a penalty step allocates nothing once the first steps have sized the storage", "[allocations][penalty]") {
  Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/pyramid.json");
  scene.solver.method = "penalty";
  World world(scene);
  // Half a second sizes the anchors' and springs' storage; the next half second reuses it.
  const int half_second = static_cast<int>(std::lround(0.5 / scene.time.dt));
  for (int k = 0; k < half_second; ++k) world.step();
  const long before = g_allocations;
  for (int k = 0; k < half_second; ++k) world.step();
  CHECK(g_allocations - before == 0);
}

TEST_CASE("a 385-box pyramid, swept cell by cell, allocates nothing in its steps, on one thread and on two",
          "[allocations]") {
  // From SweepAndPrune::kCellsFrom bodies on, the broadphase sweeps a y-z grid: its cells and
  // their entries are sized when the world is built, like the rest of the step's storage.
  Scene scene = load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/hard/pyramid_10.json");
  REQUIRE(scene.bodies.size() >= 256);
  const int threads = GENERATE(1, 2);
  scene.solver.threads = threads;
  World world(scene);
  REQUIRE(world.threads() == threads);
  const long before = g_allocations;
  for (int k = 0; k < 240; ++k) world.step();
  CHECK(g_allocations - before == 0);
}
