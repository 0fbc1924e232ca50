#include "boxpile/reference/mujoco/mujoco_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>

#include <mujoco/mujoco.h>

#include "boxpile/reference/mujoco/mujoco_messages.hpp"
#include "boxpile/sim/collision/collide.hpp"

namespace boxpile::reference_detail {
namespace {

// MuJoCo's defaults for what boxpile does not model: torsional and rolling friction (unused at
// condim 3), and solimp's midpoint and power.
constexpr const char* kTorsionalRolling = "0.005 0.0001";
constexpr const char* kTorsionalRollingPair = "0.005 0.0001 0.0001";
constexpr const char* kSolimpShape = "0.5 2";
// Contact room per box: a box-box pair gives up to 8 points (mjc_BoxBox), a box rests on a few
// neighbours at once. Rows per contact: 2 condim - 2 for a pyramidal cone of condim 3 (4), plus
// the limit rows of the wires. MuJoCo warns (an error here) when either fills.
constexpr int kContactsPerGeom = 16;
constexpr int kContactsSpare = 16;
constexpr int kRowsPerContact = 4;
constexpr int kRowsPerWire = 2;
// MuJoCo 2.2 sizes its stack from njmax (about 7 njmax^2 numbers when nstack is left to it) in an
// int: above some 12,000 rows the model cannot be made ("could not create mjData", measured on the
// 210-box pyramid_2d_20 at 13,568 rows; 12,000 loads). The rows are capped there, and a scene that
// needs more contacts than that leaves makes MuJoCo's contact list full: an error that names it.
constexpr int kMostRows = 12000;
// The document's name inside the virtual file system.
constexpr const char* kDocumentName = "boxpile_scene.xml";

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string vec(const Vec3& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }
// MJCF quaternions are w x y z.
std::string quat(const Quat& q) { return num(q.w()) + " " + num(q.x()) + " " + num(q.y()) + " " + num(q.z()); }

// Where the attributes go: a geom's friction has three values (sliding, torsional, rolling), an
// explicit pair's five (two sliding, torsional, two rolling).
enum class Holder { Geom, Pair };

// The contact attributes of a geom (or a pair) with material m under the scene's effects: the
// friction coefficient (condim 1, frictionless, when friction is off or zero: MuJoCo clamps a
// zero coefficient to mjMINMU), and the softness. Restitution has no MuJoCo counterpart: a pair
// with e > 0 gets solref's direct form (-stiffness, -damping) with the stiffness of the default
// spring at full impedance (1 / timeconst^2) and the damping ratio whose half oscillation keeps
// e of the approach speed.
std::string contact_attributes(const Material& m, const Effects& fx, const MujocoSettings& s, Holder holder) {
  const bool frictional = fx.friction && m.friction > 0.0;
  const std::string mu = num(frictional ? m.friction : 0.0);
  std::string a = " condim=\"" + std::string(frictional ? "3" : "1") + "\"";
  a += " friction=\"" + (holder == Holder::Pair ? mu + " " + mu + " " + kTorsionalRollingPair
                                                : mu + " " + kTorsionalRolling) + "\"";
  if (fx.restitution && m.restitution > 0.0) {
    const double stiffness = 1.0 / (s.solref_timeconst * s.solref_timeconst);
    const double zeta = damping_ratio_for_restitution(m.restitution);
    a += " solref=\"" + num(-stiffness) + " " + num(-2.0 * zeta * std::sqrt(stiffness)) + "\"";
  } else {
    a += " solref=\"" + num(s.solref_timeconst) + " " + num(s.solref_dampratio) + "\"";
  }
  a += " solimp=\"" + num(s.solimp_dmin) + " " + num(s.solimp_dmax) + " " + num(s.solimp_width) + " " +
       kSolimpShape + "\"";
  return a;
}

const char* integrator_name(MujocoIntegrator i) {
  switch (i) {
    case MujocoIntegrator::Euler: return "Euler";
    case MujocoIntegrator::RK4: return "RK4";
    case MujocoIntegrator::Implicit: return "implicit";
  }
  return "Euler";
}

const char* solver_name(MujocoSolver s) {
  switch (s) {
    case MujocoSolver::PGS: return "PGS";
    case MujocoSolver::CG: return "CG";
    case MujocoSolver::Newton: return "Newton";
  }
  return "Newton";
}

std::string option_element(const Scene& scene, const MujocoSettings& s) {
  const Vec3 g = scene.effects.gravity ? scene.gravity : Vec3::Zero();
  return "  <option timestep=\"" + num(scene.time.dt) + "\" gravity=\"" + vec(g) + "\" integrator=\"" +
         integrator_name(s.integrator) + "\" solver=\"" + solver_name(s.solver) + "\" iterations=\"" +
         std::to_string(s.iterations) + "\" tolerance=\"" + num(s.tolerance) + "\" cone=\"" +
         (s.cone == MujocoCone::Elliptic ? "elliptic" : "pyramidal") + "\" noslip_iterations=\"" +
         std::to_string(s.noslip_iterations) + "\" impratio=\"" + num(s.impratio) + "\"/>\n";
}

// The ground n . x < d: a plane geom (solid below its local z) at d n, its z turned onto n.
std::string ground_element(const HalfSpace& h, const std::string& contact) {
  const Quat q = Quat::FromTwoVectors(Vec3::UnitZ(), h.normal);
  return "    <geom name=\"" + std::string(kMujocoGround) + "\" type=\"plane\" size=\"0 0 1\" pos=\"" +
         vec(h.offset * h.normal) + "\" quat=\"" + quat(q) + "\"" + contact + "/>\n";
}

// A body on a wire: a slide joint along the wire (its range the wire's ends, measured from the
// start position) and then a ball joint at the anchor, both in MuJoCo's body frame (the scene's).
// The ends are the slide's limits, soft constraints like every MuJoCo constraint: their time
// constant is the shortest MuJoCo keeps (kLimitSteps steps; it raises shorter ones to that), so
// that a body hitting an end passes it as little as MuJoCo allows.
constexpr double kLimitSteps = 2.0;
std::string wire_joints(int index, const BodyDesc& desc, double dt) {
  const Wire& w = *desc.wire;
  const Vec3 along = w.to - w.from;
  const double length = along.norm();
  const Vec3 axis = along / length;
  const double s0 = (desc.frame.apply(w.anchor) - w.from).dot(axis);
  const std::string name = mujoco_body_name(index);
  return "      <joint name=\"" + name + "_slide\" type=\"slide\" pos=\"" + vec(w.anchor) + "\" axis=\"" +
         vec(desc.frame.orientation.conjugate() * axis) + "\" limited=\"true\" range=\"" + num(-s0) + " " +
         num(length - s0) + "\" solreflimit=\"" + num(kLimitSteps * dt) + " 1\"/>\n" + "      <joint name=\"" + name + "_ball\" type=\"ball\" pos=\"" +
         vec(w.anchor) + "\"/>\n";
}

std::string body_element(int index, const BodyDesc& desc, const RigidBody& rb, const std::string& contact,
                         double dt) {
  const std::string name = mujoco_body_name(index);
  std::string x = "    <body name=\"" + name + "\" pos=\"" + vec(desc.frame.position) + "\" quat=\"" +
                  quat(desc.frame.orientation) + "\">\n";
  if (!rb.fixed) {
    if (desc.wire) {
      x += wire_joints(index, desc, dt);
    } else {
      x += "      <freejoint name=\"" + name + "_free\"/>\n";
    }
    // The centre of mass in the scene's body frame is -frame_offset (same axes).
    const Mat3& I = rb.inertia_body;
    x += "      <inertial pos=\"" + vec(-rb.frame_offset) + "\" mass=\"" + num(rb.mass) + "\" fullinertia=\"" +
         num(I(0, 0)) + " " + num(I(1, 1)) + " " + num(I(2, 2)) + " " + num(I(0, 1)) + " " + num(I(0, 2)) + " " +
         num(I(1, 2)) + "\"/>\n";
  }
  for (std::size_t k = 0; k < desc.boxes.size(); ++k) {
    const BoxShape& b = desc.boxes[k];
    x += "      <geom name=\"" + mujoco_geom_name(index, static_cast<int>(k)) + "\" type=\"box\" size=\"" +
         vec(b.half_extents) + "\" pos=\"" + vec(b.offset) + "\" quat=\"" + quat(b.orientation) + "\"" + contact +
         "/>\n";
  }
  return x + "    </body>\n";
}

}  // namespace

// Appended rather than `"b" + std::to_string(body)`, on which GCC 12 at -O3 warns falsely
// (-Wrestrict inside basic_string::replace).
std::string mujoco_body_name(int body) { return std::string("b").append(std::to_string(body)); }
std::string mujoco_geom_name(int body, int shape) { return mujoco_body_name(body) + "_" + std::to_string(shape); }

double damping_ratio_for_restitution(double e) {
  const double l = std::log(e);
  return -l / std::sqrt(M_PI * M_PI + l * l);
}

std::string mujoco_mjcf(const Scene& scene, const std::vector<RigidBody>& bodies, const MujocoSettings& s) {
  const Effects& fx = scene.effects;
  const int n = static_cast<int>(bodies.size());
  std::vector<std::string> contact(static_cast<std::size_t>(n));
  int geoms = scene.ground ? 1 : 0, wires = 0;
  for (int i = 0; i < n; ++i) {
    contact[static_cast<std::size_t>(i)] = contact_attributes(bodies[static_cast<std::size_t>(i)].material, fx, s, Holder::Geom);
    geoms += static_cast<int>(bodies[static_cast<std::size_t>(i)].shapes.size());
    if (scene.bodies[static_cast<std::size_t>(i)].wire) ++wires;
  }
  const std::string ground_contact = contact_attributes(scene.material, fx, s, Holder::Geom);

  // MuJoCo combines two geoms' frictions by the larger and their solrefs by the mean; boxpile
  // combines materials by combine_materials (sqrt(mu_a mu_b), max(e_a, e_b)). The two agree when
  // both geoms carry the same attributes; every other geom pair that can touch gets an explicit
  // <pair> with the combined material (MuJoCo then skips its own contacts between those bodies).
  std::string pairs;
  const auto add_pairs = [&](int a, int b) {
    const Material& ma = bodies[static_cast<std::size_t>(a)].material;
    const Material& mb = b == kGround ? scene.material : bodies[static_cast<std::size_t>(b)].material;
    const std::string attributes = contact_attributes(combine_materials(ma, mb), fx, s, Holder::Pair);
    const int nb = b == kGround ? 1 : static_cast<int>(bodies[static_cast<std::size_t>(b)].shapes.size());
    for (std::size_t ka = 0; ka < bodies[static_cast<std::size_t>(a)].shapes.size(); ++ka) {
      for (int kb = 0; kb < nb; ++kb) {
        const std::string gb = b == kGround ? std::string(kMujocoGround) : mujoco_geom_name(b, kb);
        pairs += "    <pair geom1=\"" + mujoco_geom_name(a, static_cast<int>(ka)) + "\" geom2=\"" + gb + "\"" +
                 attributes + "/>\n";
      }
    }
  };
  for (int a = 0; a < n; ++a) {
    const bool a_fixed = bodies[static_cast<std::size_t>(a)].fixed;
    if (scene.ground && !a_fixed && contact[static_cast<std::size_t>(a)] != ground_contact) add_pairs(a, kGround);
    for (int b = a + 1; b < n; ++b) {
      if (a_fixed && bodies[static_cast<std::size_t>(b)].fixed) continue;
      if (contact[static_cast<std::size_t>(a)] != contact[static_cast<std::size_t>(b)]) add_pairs(a, b);
    }
  }

  const int nconmax =
      std::min(kContactsPerGeom * geoms + kContactsSpare, (kMostRows - kRowsPerWire * wires) / kRowsPerContact);
  std::string x = "<mujoco model=\"" + std::string("boxpile") + "\">\n";
  x += "  <compiler angle=\"radian\"/>\n";
  x += option_element(scene, s);
  x += "  <size nconmax=\"" + std::to_string(nconmax) + "\" njmax=\"" +
       std::to_string(kRowsPerContact * nconmax + kRowsPerWire * wires) + "\"/>\n";
  x += "  <worldbody>\n";
  if (scene.ground) x += ground_element(*scene.ground, ground_contact);
  for (int i = 0; i < n; ++i) {
    x += body_element(i, scene.bodies[static_cast<std::size_t>(i)], bodies[static_cast<std::size_t>(i)],
                      contact[static_cast<std::size_t>(i)], scene.time.dt);
  }
  x += "  </worldbody>\n";
  if (!pairs.empty()) x += "  <contact>\n" + pairs + "  </contact>\n";
  return x + "</mujoco>\n";
}

void ModelDeleter::operator()(mjModel_* m) const { mj_deleteModel(m); }
void DataDeleter::operator()(mjData_* d) const { mj_deleteData(d); }

ModelPtr load_mjcf(const std::string& xml) {
  ensure_mujoco_handlers();
  // mj_loadXML keeps the last parsed document in one global: one load at a time.
  static std::mutex load_mutex;
  const std::lock_guard<std::mutex> lock(load_mutex);
  // mjVFS holds 2,000 file names of 1,000 characters: on the heap.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), kDocumentName, static_cast<int>(xml.size())) != 0) {
    throw MujocoError("mujoco: could not make the scene's document in MuJoCo's virtual file system");
  }
  const int file = mj_findFileVFS(vfs.get(), kDocumentName);
  std::memcpy(vfs->filedata[file], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML(kDocumentName, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!m) throw MujocoError(std::string("mujoco: the scene's model was refused: ") + error);
  return ModelPtr(m);
}

}  // namespace boxpile::reference_detail
