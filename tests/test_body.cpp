// Rigid-body mass properties and state against analytic values: one box, compounds, rotated
// boxes (also checked against a direct volume integral), and the velocity / momentum round trip.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>
#include <vector>

#include <Eigen/Eigenvalues>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/scene.hpp"

using namespace boxpile;

namespace {

// Rounding in a handful of 3x3 products: far below any modelling error we could make.
constexpr double kTight = 1e-12;

Quat axis_angle(const Vec3& axis, double angle) {
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

std::string show(const Mat3& m) {
  std::ostringstream os;
  os << '\n' << m << '\n';
  return os.str();
}

void check_mat(const Mat3& actual, const Mat3& expected, double tol) {
  INFO("actual:" << show(actual) << "expected:" << show(expected));
  CHECK((actual - expected).cwiseAbs().maxCoeff() <= tol);
}

void check_vec(const Vec3& actual, const Vec3& expected, double tol) {
  INFO("actual: " << actual.transpose() << "  expected: " << expected.transpose());
  CHECK((actual - expected).cwiseAbs().maxCoeff() <= tol);
}

// Same rotation (q and -q are the same rotation).
void check_same_rotation(const Quat& actual, const Quat& expected, double tol) {
  INFO("actual: " << actual.coeffs().transpose()
                   << "  expected: " << expected.coeffs().transpose());
  CHECK(std::abs(std::abs(actual.dot(expected)) - 1.0) <= tol);
}

// m/12 (b^2 + c^2) etc. with full edge lengths a, b, c: the textbook solid cuboid.
Mat3 cuboid_inertia(double m, double a, double b, double c) {
  return (m / 12.0 * Vec3(b * b + c * c, a * a + c * c, a * a + b * b)).asDiagonal();
}

// The inertia tensor about `center` as a volume integral, I = integral rho (|r|^2 E - r r^T) dV,
// by 2-point Gauss-Legendre quadrature per axis on an n^3 grid of cells over every box. The
// integrand is quadratic in each box coordinate, which that rule integrates exactly: the result is
// independent of the closed forms under test and differs from them by rounding only.
Mat3 integrate_inertia(const std::vector<BoxShape>& boxes, double density, const Vec3& center,
                       int n = 4) {
  const double gauss = 0.5 / std::sqrt(3.0);  // nodes at the cell centre +- h / (2 sqrt 3)
  Mat3 inertia = Mat3::Zero();
  for (const BoxShape& box : boxes) {
    const Vec3 cell = 2.0 * box.half_extents / n;
    const double dm = density * cell.prod() / 8.0;  // eight nodes per cell, equal weights
    const Mat3 rot = box.orientation.toRotationMatrix();
    for (int i = 0; i < 2 * n; ++i) {
      for (int j = 0; j < 2 * n; ++j) {
        for (int k = 0; k < 2 * n; ++k) {
          const Vec3 node(i / 2 + 0.5 + (i % 2 ? gauss : -gauss),
                          j / 2 + 0.5 + (j % 2 ? gauss : -gauss),
                          k / 2 + 0.5 + (k % 2 ? gauss : -gauss));
          const Vec3 r = box.offset + rot * (-box.half_extents + cell.cwiseProduct(node)) - center;
          inertia += dm * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
        }
      }
    }
  }
  return inertia;
}

// An L of two boxes: a 2 x 1 x 1 bar and a unit cube on top of its +x end.
std::vector<BoxShape> l_shape() {
  return {BoxShape{Vec3(1.0, 0.5, 0.5), Vec3(0.0, 0.0, 0.0), Quat::Identity()},
          BoxShape{Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0.0, 1.0), Quat::Identity()}};
}

}  // namespace

TEST_CASE("a single box: mass, centre and the cuboid inertia", "[body]") {
  const BoxShape box{Vec3(0.5, 1.0, 1.5), Vec3(0.3, -0.2, 0.1), Quat::Identity()};
  const MassProperties p = compute_mass_properties({box}, 2.0);
  CHECK(p.mass == 2.0);
  check_vec(p.center_of_mass, box.offset, kTight);
  check_mat(p.inertia, cuboid_inertia(2.0, 1.0, 2.0, 3.0), kTight);
}

TEST_CASE("two equal cubes side by side have the inertia of one box twice as long", "[body]") {
  const std::vector<BoxShape> pair = {
      BoxShape{Vec3::Constant(0.5), Vec3(-0.5, 0.0, 0.0), Quat::Identity()},
      BoxShape{Vec3::Constant(0.5), Vec3(0.5, 0.0, 0.0), Quat::Identity()}};
  const MassProperties p = compute_mass_properties(pair, 3.0);
  check_vec(p.center_of_mass, Vec3::Zero(), kTight);
  check_mat(p.inertia, cuboid_inertia(3.0, 2.0, 1.0, 1.0), kTight);
}

TEST_CASE("an asymmetric compound: centre of mass by volume, parallel-axis inertia", "[body]") {
  // A 2 x 1 x 1 bar (volume 2) at the origin and a unit cube (volume 1) at (2, 1, 0), 3 kg:
  // 2 kg and 1 kg, centre of mass (2/3, 1/3, 0).
  const std::vector<BoxShape> boxes = {
      BoxShape{Vec3(1.0, 0.5, 0.5), Vec3::Zero(), Quat::Identity()},
      BoxShape{Vec3::Constant(0.5), Vec3(2.0, 1.0, 0.0), Quat::Identity()}};
  const MassProperties p = compute_mass_properties(boxes, 3.0);
  const Vec3 c(2.0 / 3.0, 1.0 / 3.0, 0.0);
  check_vec(p.center_of_mass, c, kTight);

  // Worked by hand: d_bar = -c, d_cube = (4/3, 2/3, 0);
  // Ixx = bar 2/12 (1 + 1) + cube 1/12 (1 + 1) + 2 (1/9) + 1 (4/9) = 1/3 + 1/6 + 2/3 = 7/6
  // Iyy = 2/12 (4 + 1) + 1/6 + 2 (4/9) + 1 (16/9) = 5/6 + 1/6 + 24/9 = 11/3
  // Izz = 2/12 (4 + 1) + 1/6 + 2 (5/9) + 1 (20/9) = 1 + 30/9 = 13/3
  // Ixy = -(2 (2/3)(1/3) + 1 (4/3)(2/3)) = -4/3, Ixz = Iyz = 0.
  Mat3 expected;
  expected << 7.0 / 6.0, -4.0 / 3.0, 0.0,
              -4.0 / 3.0, 11.0 / 3.0, 0.0,
              0.0, 0.0, 13.0 / 3.0;
  check_mat(p.inertia, expected, kTight);

  // The same from the volume integral (density 3 kg / 3 m^3).
  check_mat(p.inertia, integrate_inertia(boxes, 1.0, c), 1e-10);
}

TEST_CASE("a rotated box has the inertia R I R^T", "[body]") {
  const Quat q = axis_angle(Vec3(1.0, 2.0, 3.0), 0.7);
  const BoxShape box{Vec3(0.5, 1.0, 1.5), Vec3(1.0, 2.0, 3.0), q};
  const MassProperties p = compute_mass_properties({box}, 6.0);
  const Mat3 r = q.toRotationMatrix();
  check_vec(p.center_of_mass, box.offset, kTight);
  check_mat(p.inertia, r * cuboid_inertia(6.0, 1.0, 2.0, 3.0) * r.transpose(), kTight);
  check_mat(p.inertia, integrate_inertia({box}, 1.0, box.offset), 1e-10);
}

TEST_CASE("a compound of rotated, offset boxes matches the volume integral", "[body]") {
  const std::vector<BoxShape> boxes = {
      BoxShape{Vec3(0.2, 0.4, 0.1), Vec3(0.1, -0.3, 0.2), axis_angle(Vec3(0.0, 1.0, 1.0), 0.4)},
      BoxShape{Vec3(0.3, 0.1, 0.25), Vec3(-0.4, 0.2, 0.5), axis_angle(Vec3(1.0, 0.0, -1.0), 1.1)},
      BoxShape{Vec3(0.15, 0.15, 0.15), Vec3(0.6, 0.6, -0.2), Quat::Identity()}};
  double volume = 0.0;
  Vec3 moment = Vec3::Zero();
  for (const BoxShape& b : boxes) {
    volume += 8.0 * b.half_extents.prod();
    moment += 8.0 * b.half_extents.prod() * b.offset;
  }
  const double mass = 2.5;
  const MassProperties p = compute_mass_properties(boxes, mass);
  check_vec(p.center_of_mass, moment / volume, kTight);
  check_mat(p.inertia, integrate_inertia(boxes, mass / volume, moment / volume), 1e-10);
  // An inertia tensor is symmetric, and each principal moment at most the sum of the other two.
  check_mat(p.inertia, p.inertia.transpose(), kTight);
  const Vec3 principal = Eigen::SelfAdjointEigenSolver<Mat3>(p.inertia).eigenvalues();
  CHECK(principal.minCoeff() > 0.0);
  CHECK(principal[2] <= principal[0] + principal[1] + kTight);
}

TEST_CASE("set_velocity and update_derived round trip through the momenta", "[body]") {
  const Pose frame{Vec3(1.0, -2.0, 3.0), axis_angle(Vec3(0.3, -1.0, 0.5), 1.2)};
  const Vec3 v(0.5, -1.5, 2.0);
  const Vec3 w(-0.7, 0.2, 1.3);
  RigidBody body = make_body("l", l_shape(), 4.0, frame, v, w, Material{}, false);

  check_vec(body.v, v, kTight);
  check_vec(body.omega, w, kTight);
  // P = m v, L = R I_body R^T omega.
  check_vec(body.P, 4.0 * v, kTight);
  check_vec(body.L, body.R * body.inertia_body * body.R.transpose() * w, kTight);
  check_mat(body.inv_inertia_world * (body.R * body.inertia_body * body.R.transpose()),
             Mat3::Identity(), kTight);

  // Only the momenta are state: recomputing the derived quantities gives the same velocities.
  body.v.setZero();
  body.omega.setZero();
  body.update_derived();
  check_vec(body.v, v, kTight);
  check_vec(body.omega, w, kTight);

  // A new orientation changes the world inertia, so the same L means a different omega.
  body.q = axis_angle(Vec3::UnitX(), 0.5) * body.q;
  body.update_derived();
  check_vec(body.omega, body.inv_inertia_world * body.L, kTight);
  check_mat(body.R * body.R.transpose(), Mat3::Identity(), kTight);
  // The material velocity of the centre of mass is v.
  check_vec(body.velocity_at(body.x), body.v, kTight);
}

TEST_CASE("update_derived renormalises a drifted quaternion", "[body]") {
  RigidBody body = make_body("b", {BoxShape{}}, 1.0, Pose{}, Vec3::Zero(), Vec3::Zero(),
                             Material{}, false);
  body.q = Quat(1.1, 0.0, 0.0, 0.2);
  body.update_derived();
  CHECK(std::abs(body.q.norm() - 1.0) <= kTight);
  check_mat(body.R * body.R.transpose(), Mat3::Identity(), kTight);
}

TEST_CASE("a compound's frame_pose reproduces the scene frame; shapes sit where written",
          "[body]") {
  const Pose frame{Vec3(5.0, -1.0, 0.5), axis_angle(Vec3(0.0, 0.0, 1.0), 0.9)};
  const std::vector<BoxShape> boxes = l_shape();
  const RigidBody body = make_body("l", boxes, 2.0, frame, Vec3::Zero(), Vec3::Zero(),
                                   Material{}, false);

  // Centre of mass of the L in its frame: the bar (volume 2) at the origin, the cube (volume 1)
  // at (0.5, 0, 1): c = (0.5, 0, 1) / 3. The state x is that point in the world.
  const Vec3 c(1.0 / 6.0, 0.0, 1.0 / 3.0);
  check_vec(body.x, frame.apply(c), kTight);
  check_vec(body.frame_offset, -c, kTight);
  check_same_rotation(body.q, frame.orientation, kTight);

  const Pose back = body.frame_pose();
  check_vec(back.position, frame.position, kTight);
  check_same_rotation(back.orientation, frame.orientation, kTight);

  for (int k = 0; k < 2; ++k) {
    const BoxShape& b = boxes[static_cast<std::size_t>(k)];
    const Pose s = body.shape_pose(k);
    check_vec(s.position, frame.apply(b.offset), kTight);
    check_same_rotation(s.orientation, frame.orientation * b.orientation, kTight);
  }
  // The body inertia is about the centre of mass in the frame's axes.
  check_mat(body.inertia_body, compute_mass_properties(boxes, 2.0).inertia, kTight);
}

TEST_CASE("a fixed body has infinite mass and does not move", "[body]") {
  const RigidBody body = make_body("floor", {BoxShape{Vec3(5.0, 5.0, 0.5)}}, 0.0,
                                   Pose{Vec3(0.0, 0.0, -0.5), Quat::Identity()},
                                   Vec3(1.0, 0.0, 0.0), Vec3(0.0, 0.0, 1.0), Material{}, true);
  CHECK(body.inv_mass == 0.0);
  CHECK(body.inv_inertia_body.isZero(0.0));
  CHECK(body.inv_inertia_world.isZero(0.0));
  CHECK(body.mass == 0.0);
  CHECK(body.v.isZero(0.0));
  CHECK(body.omega.isZero(0.0));
  CHECK(body.P.isZero(0.0));
  CHECK(body.L.isZero(0.0));

  // A fixed body given a mass keeps it for reports, still immovable.
  const RigidBody heavy = make_body("slab", {BoxShape{}}, 7.0, Pose{}, Vec3::Zero(), Vec3::Zero(),
                                    Material{}, true);
  CHECK(heavy.mass == 7.0);
  CHECK(heavy.inv_mass == 0.0);
}

TEST_CASE("make_bodies builds every body in order, materials falling back to the scene's",
          "[body]") {
  const auto cube = [](const char* name, double z) {
    BodyDesc d;
    d.name = name;
    d.boxes = {BoxShape{}};
    d.frame.position = Vec3(0.0, 0.0, z);
    return d;
  };
  Scene scene;
  scene.material = Material{0.8, 0.1, std::nullopt};
  scene.bodies = {cube("a", 0.5), cube("b", 1.5)};
  scene.bodies[1].material = Material{0.2, 0.0, std::nullopt};
  scene.bodies[1].mass = 3.0;

  const std::vector<RigidBody> bodies = make_bodies(scene);
  REQUIRE(bodies.size() == 2);
  CHECK(bodies[0].name == "a");
  CHECK(bodies[0].material.friction == 0.8);
  CHECK(bodies[0].material.restitution == 0.1);
  CHECK(bodies[1].name == "b");
  CHECK(bodies[1].material.friction == 0.2);
  CHECK(bodies[1].mass == 3.0);
  check_vec(bodies[1].x, Vec3(0.0, 0.0, 1.5), kTight);
}
