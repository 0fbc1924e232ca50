// Time per box-box query on the same fixed set of random touching pairs (tests/support/
// geometry.hpp, seed 1): our separating-axis test and clipping, ODE's dCollide (dBoxBox), and
// Bullet's btBoxBoxDetector, each called directly on shapes placed beforehand; then the full
// adapters of reference/ode/ode_contacts.hpp and reference/bullet/bullet_contacts.hpp (conversion to our convention, and for Bullet the
// dispatcher's algorithm and persistent manifold) for the cost of a `boxpile contacts` query.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <btBulletCollisionCommon.h>
#include <ode/ode.h>

#include "boxpile/reference/bullet/bullet_contacts.hpp"
#include "boxpile/reference/ode/ode_contacts.hpp"
#include "boxpile/sim/collision/box_box.hpp"
#include "boxpile/tests/support/geometry.hpp"

namespace boxpile {
namespace {

constexpr int kPairs = 1024;
constexpr std::uint64_t kSeed = 1;

// The index of the next pair, cycling through the set. A power-of-two set size makes the wrap a
// mask: a 64-bit division per query (i % n) would add some 10 ns to every detector alike.
static_assert((kPairs & (kPairs - 1)) == 0);
inline std::size_t next_pair(std::size_t& i) { return i++ & (kPairs - 1); }

const std::vector<BoxPair>& pairs() {
  static const std::vector<BoxPair> set = [] {
    std::mt19937_64 rng(kSeed);
    std::vector<BoxPair> v;
    for (int i = 0; i < kPairs; ++i) v.push_back(random_touching_pair(rng));
    return v;
  }();
  return set;
}

void BM_BoxBox_Own(benchmark::State& state) {
  CollisionSettings settings;
  settings.reduce_to_four = state.range(0) != 0;
  const auto& set = pairs();
  Manifold m;
  std::size_t i = 0;
  for (auto _ : state) {
    const BoxPair& p = set[next_pair(i)];
    collide_box_box(p.a, p.b, settings, m);
    benchmark::DoNotOptimize(m);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BoxBox_Own)->Arg(0)->Arg(1)->ArgName("reduce_to_four");

// The separating-axis test alone (no contact points): how the cost of a query divides.
void BM_BoxBox_OwnSatOnly(benchmark::State& state) {
  const auto& set = pairs();
  std::size_t i = 0;
  for (auto _ : state) {
    const BoxPair& p = set[next_pair(i)];
    benchmark::DoNotOptimize(box_box_sat(p.a, p.b));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BoxBox_OwnSatOnly);

// ODE: two box geoms per pair, created and placed once; each query is one dCollide.
void BM_BoxBox_OdeCollide(benchmark::State& state) {
  dInitODE2(0);
  const auto& set = pairs();
  std::vector<dGeomID> a, b;
  auto make = [](const OrientedBox& box) {
    const Vec3 s = 2.0 * box.half;
    dGeomID g = dCreateBox(nullptr, s.x(), s.y(), s.z());
    dGeomSetPosition(g, box.center.x(), box.center.y(), box.center.z());
    dMatrix3 R;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) R[4 * r + c] = box.axes(r, c);
      R[4 * r + 3] = 0;
    }
    dGeomSetRotation(g, R);
    return g;
  };
  for (const auto& p : set) {
    a.push_back(make(p.a));
    b.push_back(make(p.b));
  }
  dContactGeom contacts[8];
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = next_pair(i);
    benchmark::DoNotOptimize(dCollide(a[k], b[k], 8, contacts, sizeof(dContactGeom)));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  for (std::size_t k = 0; k < a.size(); ++k) {
    dGeomDestroy(a[k]);
    dGeomDestroy(b[k]);
  }
}
BENCHMARK(BM_BoxBox_OdeCollide);

// Collects btBoxBoxDetector's points as they come, with no manifold behind them.
struct CollectPoints : btDiscreteCollisionDetectorInterface::Result {
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3& normal, const btVector3& point, btScalar depth) override {
    if (count < 4) points[count++] = {normal, point, depth};
  }
  struct Point {
    btVector3 normal, point;
    btScalar depth;
  };
  Point points[4];
  int count = 0;
};

// Bullet: two btBoxShapes and their transforms per pair, made once; each query runs the
// detector its box-box algorithm uses (at most 4 points).
void BM_BoxBox_BulletDetector(benchmark::State& state) {
  const auto& set = pairs();
  std::vector<std::unique_ptr<btBoxShape>> shapes;
  std::vector<btDiscreteCollisionDetectorInterface::ClosestPointInput> inputs(set.size());
  auto transform = [](const OrientedBox& box) {
    const Mat3& m = box.axes;
    return btTransform(btMatrix3x3(m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2)),
                       btVector3(box.center.x(), box.center.y(), box.center.z()));
  };
  for (std::size_t k = 0; k < set.size(); ++k) {
    shapes.push_back(std::make_unique<btBoxShape>(btVector3(set[k].a.half.x(), set[k].a.half.y(), set[k].a.half.z())));
    shapes.push_back(std::make_unique<btBoxShape>(btVector3(set[k].b.half.x(), set[k].b.half.y(), set[k].b.half.z())));
    inputs[k].m_transformA = transform(set[k].a);
    inputs[k].m_transformB = transform(set[k].b);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = next_pair(i);
    btBoxBoxDetector detector(shapes[2 * k].get(), shapes[2 * k + 1].get());
    CollectPoints out;
    detector.getClosestPoints(inputs[k], out, nullptr);
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BoxBox_BulletDetector);

// The adapters behind `boxpile contacts`, in our convention.
void BM_BoxBox_OdeAdapter(benchmark::State& state) {
  const auto& set = pairs();
  std::size_t i = 0;
  for (auto _ : state) {
    const BoxPair& p = set[next_pair(i)];
    benchmark::DoNotOptimize(ode_box_box(p.a, p.b));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BoxBox_OdeAdapter);

void BM_BoxBox_BulletAdapter(benchmark::State& state) {
  const auto& set = pairs();
  std::size_t i = 0;
  for (auto _ : state) {
    const BoxPair& p = set[next_pair(i)];
    benchmark::DoNotOptimize(bullet_box_box(p.a, p.b));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BoxBox_BulletAdapter);

}  // namespace
}  // namespace boxpile
