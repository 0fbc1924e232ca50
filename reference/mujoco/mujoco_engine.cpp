#include "boxpile/reference/mujoco/mujoco_engine.hpp"

#include <array>
#include <cmath>
#include <utility>

#include <mujoco/mujoco.h>

#include "boxpile/reference/body_states.hpp"
#include "boxpile/reference/convention.hpp"
#include "boxpile/reference/mujoco/mujoco_model.hpp"
#include "boxpile/sim/body.hpp"

namespace boxpile {

using namespace reference_detail;

namespace {

// How a scene body is held in MuJoCo's model.
enum class Mount { Fixed, Free, Wire };

struct BodyMap {
  Mount mount = Mount::Free;
  int id = 0;        // MuJoCo body id
  int qvel = 0;      // first dof: the free joint's, or the wire's slide joint's
  int ball_qvel = 0; // a wire's ball joint's first dof
};

// Which scene body and which of its boxes a MuJoCo geom stands for.
struct GeomTag {
  int body = kGround;
  int shape = 0;
};

// MuJoCo's warnings that leave a run wrong: the state was reset (a bad number), contacts or
// constraints were dropped (a full list), or the inertia was singular.
constexpr std::array<std::pair<int, const char*>, 6> kFatalWarnings = {{
    {mjWARN_INERTIA, "a (near) singular inertia matrix"},
    {mjWARN_CONTACTFULL, "the contact list is full"},
    {mjWARN_CNSTRFULL, "the constraint list is full"},
    {mjWARN_BADQPOS, "a bad number in qpos (MuJoCo reset the state)"},
    {mjWARN_BADQVEL, "a bad number in qvel (MuJoCo reset the state)"},
    {mjWARN_BADQACC, "a bad number in qacc (MuJoCo reset the state)"},
}};

Mat3 mat3(const mjtNum* p) {
  Mat3 r;
  r << p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8];  // row-major
  return r;
}

// Air damping as a force held over the step: with MuJoCo's semi-implicit Euler v <- v + a dt,
// the acceleration -v (1 - exp(-c dt)) / dt gives v <- v exp(-c dt), the scene's law
// dv/dt = -c v over one step exactly (as ODE's and Bullet's mappings do).
double damping_per_second(double rate, double dt) { return (1.0 - std::exp(-rate * dt)) / dt; }

}  // namespace

struct MujocoEngine::World {
  World(const Scene& scene, const MujocoSettings& settings);

  void map_model();
  void set_start_velocities();
  // Kinematics and velocities of the present qpos and qvel: mj_step leaves them at the start of
  // the step it took.
  void refresh();
  // The per-step forces the scene's effects ask for and MuJoCo has no switch for.
  void apply_effects();
  void check_warnings() const;
  void read_contacts();
  OrientedBox box_of_geom(int geom) const;
  // Angular velocity (world) and velocity of the centre of mass of MuJoCo body `id`.
  std::pair<Vec3, Vec3> velocities(int id) const;

  Scene scene;
  MujocoSettings settings;
  std::vector<RigidBody> bodies;
  ModelPtr model;
  DataPtr data;
  std::vector<BodyMap> map;      // scene order
  std::vector<GeomTag> tags;     // by MuJoCo geom id
  std::vector<BodyContact> contacts;
  bool per_step_forces = false;  // damping or the gyroscopic term cancelled
  std::uint64_t steps = 0;
  std::uint64_t messages_at_start = 0;
};

MujocoEngine::World::World(const Scene& s, const MujocoSettings& st)
    : scene(s), settings(st), bodies(make_bodies(s)) {
  ensure_mujoco_handlers();
  // MuJoCo always integrates the gyroscopic term; boxpile cancels it with a torque held over the
  // step, exact only when the step evaluates its forces once (Euler).
  if (!scene.effects.gyroscopic && settings.integrator != MujocoIntegrator::Euler) {
    throw MujocoError(
        "mujoco: integrator \"" + std::string(settings.integrator == MujocoIntegrator::RK4 ? "rk4" : "implicit") +
        "\" needs the scene's gyroscopic effect on: MuJoCo always has the gyroscopic term, and boxpile "
        "cancels it exactly only under \"euler\"");
  }
  messages_at_start = mujoco_messages().count;
  model = load_mjcf(mujoco_mjcf(scene, bodies, settings));
  data.reset(mj_makeData(model.get()));
  if (!data) throw MujocoError("mujoco: mj_makeData failed");
  map_model();
  set_start_velocities();
  refresh();
  per_step_forces = scene.effects.damping || !scene.effects.gyroscopic;
  contacts.reserve(static_cast<std::size_t>(model->nconmax));
}

void MujocoEngine::World::map_model() {
  const mjModel* m = model.get();
  const auto id_of = [&](int type, const std::string& name) {
    const int id = mj_name2id(m, type, name.c_str());
    if (id < 0) throw MujocoError("mujoco: the compiled model has no \"" + name + "\"");
    return id;
  };
  tags.assign(static_cast<std::size_t>(m->ngeom), GeomTag{});
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    const RigidBody& rb = bodies[static_cast<std::size_t>(i)];
    BodyMap b;
    b.id = id_of(mjOBJ_BODY, mujoco_body_name(i));
    if (rb.fixed) {
      b.mount = Mount::Fixed;
    } else if (scene.bodies[static_cast<std::size_t>(i)].wire) {
      b.mount = Mount::Wire;
      b.qvel = m->jnt_dofadr[id_of(mjOBJ_JOINT, mujoco_body_name(i) + "_slide")];
      b.ball_qvel = m->jnt_dofadr[id_of(mjOBJ_JOINT, mujoco_body_name(i) + "_ball")];
    } else {
      b.qvel = m->jnt_dofadr[id_of(mjOBJ_JOINT, mujoco_body_name(i) + "_free")];
    }
    map.push_back(b);
    for (int k = 0; k < static_cast<int>(rb.shapes.size()); ++k) {
      tags[static_cast<std::size_t>(id_of(mjOBJ_GEOM, mujoco_geom_name(i, k)))] = {i, k};
    }
  }
}

// A free joint's velocity is the body frame origin's (world axes) and the angular velocity in body
// axes; a wire's slide joint takes the anchor's speed along the wire, its ball joint the angular
// velocity in body axes (the velocity across the wire is the wire's to cancel, as in ODE).
void MujocoEngine::World::set_start_velocities() {
  mjtNum* qvel = data->qvel;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const RigidBody& rb = bodies[i];
    const BodyMap& b = map[i];
    const Vec3 omega_body = rb.q.conjugate() * rb.omega;
    if (b.mount == Mount::Free) {
      const Vec3 v_origin = rb.velocity_at(rb.frame_pose().position);
      for (int k = 0; k < 3; ++k) {
        qvel[b.qvel + k] = v_origin[k];
        qvel[b.qvel + 3 + k] = omega_body[k];
      }
    } else if (b.mount == Mount::Wire) {
      const BodyDesc& desc = scene.bodies[i];
      const Vec3 axis = (desc.wire->to - desc.wire->from).normalized();
      qvel[b.qvel] = axis.dot(rb.velocity_at(desc.frame.apply(desc.wire->anchor)));
      for (int k = 0; k < 3; ++k) qvel[b.ball_qvel + k] = omega_body[k];
    }
  }
}

void MujocoEngine::World::refresh() {
  mj_kinematics(model.get(), data.get());
  mj_comPos(model.get(), data.get());
  mj_comVel(model.get(), data.get());
}

std::pair<Vec3, Vec3> MujocoEngine::World::velocities(int id) const {
  mjtNum v[6];
  // mjOBJ_BODY: at the body's centre of mass (xipos); flg_local 0: world axes; [angular, linear].
  mj_objectVelocity(model.get(), data.get(), mjOBJ_BODY, id, v, 0);
  return {Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5])};
}

// Forces at the centre of mass, world axes (xfrc_applied), from the state the step starts at:
//  - air damping, F = -m v c' and T = -I w c' with c' from damping_per_second;
//  - the gyroscopic term cancelled when the scene leaves it out: MuJoCo's equations of motion
//    have I dw/dt + w x I w = T, so the torque w x I w held over an Euler step removes it.
void MujocoEngine::World::apply_effects() {
  const double dt = scene.time.dt;
  const Effects& fx = scene.effects;
  const double c_lin = fx.damping ? damping_per_second(scene.damping.linear, dt) : 0.0;
  const double c_ang = fx.damping ? damping_per_second(scene.damping.angular, dt) : 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyMap& b = map[i];
    if (b.mount == Mount::Fixed) continue;
    const RigidBody& rb = bodies[i];
    const auto [omega, v] = velocities(b.id);
    const Mat3 r = mat3(data->xmat + 9 * b.id);  // MuJoCo's body frame is the scene's
    const Vec3 l = r * (rb.inertia_body * (r.transpose() * omega));
    Vec3 force = -c_lin * rb.mass * v;
    Vec3 torque = -c_ang * l;
    if (!fx.gyroscopic) torque += omega.cross(l);
    mjtNum* f = data->xfrc_applied + 6 * b.id;
    for (int k = 0; k < 3; ++k) {
      f[k] = force[k];
      f[3 + k] = torque[k];
    }
  }
}

void MujocoEngine::World::check_warnings() const {
  for (const auto& [warning, what] : kFatalWarnings) {
    if (data->warning[warning].number > 0) {
      throw MujocoError("mujoco: at step " + std::to_string(steps + 1) + ", " + what + " (MuJoCo's info " +
                        std::to_string(data->warning[warning].lastinfo) + ")");
    }
  }
}

OrientedBox MujocoEngine::World::box_of_geom(int geom) const {
  OrientedBox box;
  box.center = vec3(data->geom_xpos + 3 * geom);
  box.axes = mat3(data->geom_xmat + 9 * geom);
  box.half = vec3(model->geom_size + 3 * geom);
  return box;
}

// d->contact holds the contacts the step used, found at the poses it started from, which
// geom_xpos and geom_xmat still hold. MuJoCo's normal (frame[0..2]) points from geom1 to geom2
// and dist < 0 is a penetration; `pos` is the midpoint already. Ours points from B toward A: A
// is geom1 (normal negated) unless geom1 is the ground, which is always B.
void MujocoEngine::World::read_contacts() {
  contacts.clear();
  for (int i = 0; i < data->ncon; ++i) {
    const mjContact& c = data->contact[i];
    const bool ground_first = tags[static_cast<std::size_t>(c.geom1)].body == kGround;
    const int ga = ground_first ? c.geom2 : c.geom1;
    const int gb = ground_first ? c.geom1 : c.geom2;
    const GeomTag& ta = tags[static_cast<std::size_t>(ga)];
    const GeomTag& tb = tags[static_cast<std::size_t>(gb)];
    const Vec3 frame_normal = vec3(c.frame);
    const Vec3 n = ground_first ? frame_normal : Vec3(-frame_normal);
    const FeatureKind kind =
        tb.body == kGround ? FeatureKind::Plane : box_box_kind(box_of_geom(ga), box_of_geom(gb), n);
    contacts.push_back({Contact{vec3(c.pos), n, -c.dist, kind_only(kind)}, ta.body, tb.body, ta.shape, tb.shape});
  }
}

MujocoEngine::MujocoEngine(const Scene& scene, const MujocoSettings& settings)
    : world_(std::make_unique<World>(scene, settings)) {}

MujocoEngine::~MujocoEngine() = default;

void MujocoEngine::step() {
  World& w = *world_;
  if (w.per_step_forces) w.apply_effects();
  mj_step(w.model.get(), w.data.get());
  w.check_warnings();
  w.read_contacts();
  w.refresh();
  ++w.steps;
}

double MujocoEngine::time() const { return static_cast<double>(world_->steps) * world_->scene.time.dt; }

void MujocoEngine::body_states(std::vector<BodyState>& out) const {
  const World& w = *world_;
  reference_detail::collect_body_states(w.bodies, out, [&](std::size_t i, BodyState& s) {
    if (w.map[i].mount == Mount::Fixed) return reference_detail::set_fixed_state(w.bodies[i], s);
    const int id = w.map[i].id;
    const mjtNum* q = w.data->xquat + 4 * id;
    s.position = vec3(w.data->xpos + 3 * id);
    s.orientation = Quat(q[0], q[1], q[2], q[3]).normalized();
    std::tie(s.angular_velocity, s.velocity) = w.velocities(id);
  });
}

void MujocoEngine::contacts(std::vector<BodyContact>& out) const { out = world_->contacts; }

std::uint64_t MujocoEngine::messages() const { return mujoco_messages().count - world_->messages_at_start; }

std::string MujocoEngine::last_message() const { return messages() > 0 ? mujoco_messages().last : std::string(); }

}  // namespace boxpile
