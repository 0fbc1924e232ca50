#include "boxpile/reference/mujoco/mujoco_contacts.hpp"

#include <algorithm>
#include <array>

#include <mujoco/mujoco.h>

#include "boxpile/reference/convention.hpp"
#include "boxpile/reference/mujoco/mujoco_messages.hpp"
#include "boxpile/reference/mujoco/mujoco_model.hpp"

namespace boxpile {

using namespace reference_detail;

namespace {

// Three geoms in the world body: a plane (0) and two boxes (1, 2). A query writes the boxes'
// sizes into the model and their poses into the data, then calls the table's function directly:
// no kinematics, no broadphase.
constexpr const char* kQueryModel = R"(<mujoco model="boxpile_query">
  <worldbody>
    <geom name="plane" type="plane" size="0 0 1"/>
    <geom name="a" type="box" size="0.5 0.5 0.5"/>
    <geom name="b" type="box" size="0.5 0.5 0.5"/>
  </worldbody>
</mujoco>
)";
constexpr int kPlane = 0, kBoxA = 1, kBoxB = 2;

// One model per thread: queries write into it.
struct QueryModel {
  QueryModel() : model(load_mjcf(kQueryModel)), data(mj_makeData(model.get())) {}
  ModelPtr model;
  DataPtr data;
  std::array<mjContact, mjMAXCONPAIR> found{};

  void place(int geom, const OrientedBox& box) {
    for (int k = 0; k < 3; ++k) {
      data->geom_xpos[3 * geom + k] = box.center[k];
      model->geom_size[3 * geom + k] = box.half[k];
      for (int j = 0; j < 3; ++j) data->geom_xmat[9 * geom + 3 * k + j] = box.axes(k, j);  // row-major
    }
    model->geom_rbound[geom] = box.half.norm();
  }
  // A plane keeps its infinite extent: its pose only.
  void place_plane(const Vec3& point, const Mat3& axes) {
    for (int k = 0; k < 3; ++k) {
      data->geom_xpos[3 * kPlane + k] = point[k];
      for (int j = 0; j < 3; ++j) data->geom_xmat[9 * kPlane + 3 * k + j] = axes(k, j);
    }
  }

  int collide(int g1, int g2) {
    const int t1 = model->geom_type[g1], t2 = model->geom_type[g2];
    return mjCOLLISIONFUNC[t1][t2](model.get(), data.get(), found.data(), g1, g2, 0.0);
  }
};

QueryModel& query_model() {
  thread_local QueryModel q;
  return q;
}


// The deepest kMaxManifoldPoints of MuJoCo's points, each in our convention.
template <class Convert>
Manifold keep(const std::array<mjContact, mjMAXCONPAIR>& found, int n, Convert convert) {
  std::array<int, mjMAXCONPAIR> order{};
  for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
  std::stable_sort(order.begin(), order.begin() + n, [&](int x, int y) {
    return found[static_cast<std::size_t>(x)].dist < found[static_cast<std::size_t>(y)].dist;
  });
  Manifold m;
  for (int i = 0; i < std::min(n, kMaxManifoldPoints); ++i) m.push_back(convert(found[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])]));
  return m;
}

}  // namespace

// geom1 = A, geom2 = B: MuJoCo's normal points from A to B, ours from B toward A.
Manifold mujoco_box_box(const OrientedBox& a, const OrientedBox& b) {
  QueryModel& q = query_model();
  q.place(kBoxA, a);
  q.place(kBoxB, b);
  const int n = q.collide(kBoxA, kBoxB);
  return keep(q.found, n, [&](const mjContact& c) {
    const Vec3 normal = -vec3(c.frame);
    return Contact{vec3(c.pos), normal, -c.dist, kind_only(box_box_kind(a, b, normal))};
  });
}

// geom1 = the plane (B), geom2 = the box (A): MuJoCo's normal, from the plane to the box, is ours.
Manifold mujoco_box_plane(const OrientedBox& a, const HalfSpace& plane) {
  QueryModel& q = query_model();
  const Mat3 axes = Quat::FromTwoVectors(Vec3::UnitZ(), plane.normal).toRotationMatrix();
  q.place_plane(plane.offset * plane.normal, axes);
  q.place(kBoxA, a);
  const int n = q.collide(kPlane, kBoxA);
  return keep(q.found, n, [](const mjContact& c) {
    return Contact{vec3(c.pos), vec3(c.frame), -c.dist, kind_only(FeatureKind::Plane)};
  });
}

}  // namespace boxpile
