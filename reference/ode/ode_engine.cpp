#include "boxpile/reference/ode/ode_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "boxpile/reference/body_states.hpp"
#include "boxpile/reference/ode/ode_support.hpp"
#include "boxpile/sim/world.hpp"

namespace boxpile {

using namespace reference_detail;

namespace {

// A wire's ends, enforced on the body itself (see add_wire).
struct WireStop {
  dBodyID body = nullptr;
  Vec3 from, axis;       // world; axis a unit vector from `from` toward `to`
  double length = 0.0;   // m
  Vec3 anchor_local;     // the anchor about the centre of mass, body axes
};

// Which scene body and which of its boxes a geom stands for (dGeomSetData points here).
struct GeomTag {
  int body = kGround;
  int shape = 0;
};

// Air damping per step as ODE applies it, v <- (1 - s) v, matching the scene's continuous law
// dv/dt = -c v over one step exactly: 1 - s = exp(-c dt).
double damping_scale(double rate, double dt) { return 1.0 - std::exp(-rate * dt); }

}  // namespace

struct OdeEngine::World {
  World(const Scene& scene, const OdeSettings& settings);
  ~World();

  void build_world();
  void add_body(int index);
  void add_ground(const HalfSpace& ground);
  void add_wire(int index);
  void add_wire_stops();
  static void near_callback(void* data, dGeomID o1, dGeomID o2);
  void collide_pair(dGeomID o1, dGeomID o2);
  const Material& material_of(int body) const {
    return body == kGround ? scene.material : bodies[static_cast<std::size_t>(body)].material;
  }

  Scene scene;
  OdeSettings settings;
  std::vector<RigidBody> bodies;  // mass properties, shapes about the centre of mass, frame offsets

  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contact_joints = nullptr;
  std::vector<dBodyID> ode_bodies;  // scene order; null for fixed bodies
  std::vector<WireStop> wire_stops;
  std::vector<GeomTag> tags;        // sized once: geoms point into it
  std::vector<dContactGeom> scratch;
  std::vector<BodyContact> contacts;
  std::uint64_t steps = 0;
  std::uint64_t messages_at_start = 0;
  bool failed = false;  // an OdeError left ODE's state undefined
};

OdeEngine::World::World(const Scene& s, const OdeSettings& st)
    : scene(s), settings(st), bodies(make_bodies(s)) {
  ensure_ode_initialised();
  messages_at_start = ode_messages().count;
  // QuickStep shuffles its constraints with ODE's one global generator: the same seed for every
  // build makes runs repeatable (as long as two ODE worlds do not step interleaved).
  dRandSetSeed(settings.seed);
  build_world();
}

OdeEngine::World::~World() {
  if (contact_joints) dJointGroupDestroy(contact_joints);
  if (space) dSpaceDestroy(space);  // destroys its geoms too (cleanup mode is on by default)
  if (world) dWorldDestroy(world);
}

void OdeEngine::World::build_world() {
  world = dWorldCreate();
  const Vec3 g = scene.effects.gravity ? scene.gravity : Vec3::Zero();
  dWorldSetGravity(world, g.x(), g.y(), g.z());
  dWorldSetERP(world, settings.erp);
  dWorldSetCFM(world, settings.cfm);
  dWorldSetQuickStepNumIterations(world, settings.quickstep_iterations);
  dWorldSetQuickStepW(world, settings.quickstep_sor);
  dWorldSetContactSurfaceLayer(world, settings.surface_layer);
  if (std::isfinite(settings.max_correcting_velocity)) {
    dWorldSetContactMaxCorrectingVel(world, settings.max_correcting_velocity);
  }
  // Bodies created after this inherit the world's sleeping rules (dBodyCreate copies them).
  dWorldSetAutoDisableFlag(world, settings.auto_disable ? 1 : 0);
  dWorldSetAutoDisableLinearThreshold(world, settings.auto_disable_linear_threshold);
  dWorldSetAutoDisableAngularThreshold(world, settings.auto_disable_angular_threshold);
  dWorldSetAutoDisableSteps(world, settings.auto_disable_steps);
  dWorldSetAutoDisableTime(world, 0);  // the steps alone decide

  // A simple space tests every pair of bounding boxes in a fixed order: deterministic, and for
  // the hundred bodies of our largest scene cheaper than building a hash. It is all-pairs, though
  // (0.59 s a step at 10,000 bodies): above kOdeHashSpaceAbove bodies a multi-resolution hash
  // space (deterministic for the same scene, its pair order another) with cells from the smallest
  // to the largest box's size.
  constexpr std::size_t kOdeHashSpaceAbove = 1'000;
  if (bodies.size() > kOdeHashSpaceAbove) {
    double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
    for (const RigidBody& b : bodies) {
      for (const BoxShape& shape : b.shapes) {
        smallest = std::min(smallest, 2.0 * shape.half_extents.minCoeff());
        largest = std::max(largest, 2.0 * shape.half_extents.norm());
      }
    }
    space = dHashSpaceCreate(nullptr);
    dHashSpaceSetLevels(space, static_cast<int>(std::floor(std::log2(smallest))),
                        static_cast<int>(std::ceil(std::log2(largest))));
  } else {
    space = dSimpleSpaceCreate(nullptr);
  }
  contact_joints = dJointGroupCreate(0);

  std::size_t geom_count = scene.ground ? 1 : 0;
  for (const RigidBody& b : bodies) geom_count += b.shapes.size();
  tags.reserve(geom_count);
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) add_body(i);
  if (scene.ground) add_ground(*scene.ground);
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    if (scene.bodies[static_cast<std::size_t>(i)].wire) add_wire(i);
  }

  scratch.resize(static_cast<std::size_t>(std::max(1, settings.max_contacts)));
  contacts.reserve(static_cast<std::size_t>(settings.max_contacts) * geom_count);
}

void OdeEngine::World::add_body(int index) {
  const RigidBody& rb = bodies[static_cast<std::size_t>(index)];
  dBodyID body = nullptr;
  if (!rb.fixed) {
    body = dBodyCreate(world);
    // ODE wants the centre of mass at the body origin; our body frame is already there.
    dMass mass;
    const Mat3& I = rb.inertia_body;
    dMassSetParameters(&mass, rb.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
    dBodySetMass(body, &mass);
    dBodySetPosition(body, rb.x.x(), rb.x.y(), rb.x.z());
    dQuaternion q;
    quat_to_ode(rb.q, q);
    dBodySetQuaternion(body, q);
    dBodySetLinearVel(body, rb.v.x(), rb.v.y(), rb.v.z());
    dBodySetAngularVel(body, rb.omega.x(), rb.omega.y(), rb.omega.z());
    dBodySetGyroscopicMode(body, scene.effects.gyroscopic ? 1 : 0);
    if (scene.effects.damping) {
      const double dt = scene.time.dt;
      dBodySetLinearDamping(body, damping_scale(scene.damping.linear, dt));
      dBodySetAngularDamping(body, damping_scale(scene.damping.angular, dt));
      // ODE skips damping below a speed threshold (0.01 by default): damp at every speed.
      dBodySetLinearDampingThreshold(body, 0.0);
      dBodySetAngularDampingThreshold(body, 0.0);
    }
  }
  ode_bodies.push_back(body);

  for (int k = 0; k < static_cast<int>(rb.shapes.size()); ++k) {
    const BoxShape& shape = rb.shapes[static_cast<std::size_t>(k)];
    const Vec3 size = 2.0 * shape.half_extents;
    dGeomID geom = dCreateBox(space, size.x(), size.y(), size.z());
    tags.push_back({index, k});
    dGeomSetData(geom, &tags.back());
    dQuaternion q;
    if (body) {
      dGeomSetBody(geom, body);
      dGeomSetOffsetPosition(geom, shape.offset.x(), shape.offset.y(), shape.offset.z());
      quat_to_ode(shape.orientation, q);
      dGeomSetOffsetQuaternion(geom, q);
    } else {
      // A fixed body is a set of static geoms placed once.
      const Pose pose = rb.shape_pose(k);
      dGeomSetPosition(geom, pose.position.x(), pose.position.y(), pose.position.z());
      quat_to_ode(pose.orientation, q);
      dGeomSetQuaternion(geom, q);
    }
  }
}

void OdeEngine::World::add_ground(const HalfSpace& ground) {
  // dCreatePlane(a, b, c, d) is the plane a x + b y + c z = d, solid on the side the normal
  // points away from: our half-space n . x < offset.
  dGeomID plane = dCreatePlane(space, ground.normal.x(), ground.normal.y(), ground.normal.z(),
                               ground.offset);
  tags.push_back({kGround, 0});
  dGeomSetData(plane, &tags.back());
}

// The wire: ODE has no joint that keeps a point of one body on a line while leaving all three
// rotations free, so a carriage carries the anchor. A slider joint to the world keeps the
// carriage on the wire's line without turning; a ball joint ties the body to the carriage at the
// anchor. The carriage has no geom (it touches nothing). Its mass is a small fraction of the
// body's (a lighter one makes QuickStep's joint rows converge worse), and it has weight like any
// body, so that body and carriage together slide at g sin(theta), as a body on a massless anchor
// does. Both joints belong to the world and go with it.
//
// The ends are not the slider's stops: a stop acts on the light carriage, and QuickStep then
// stops the heavy body through the ball joint only partly (measured: a cube hitting the end at
// 4.4 m/s passed it by 4.7 cm and bounced back at 1.3 m/s). Instead each step that would carry
// the anchor past an end gets a frictionless contact joint between the body and the world at the
// anchor, its normal along the wire back from that end (add_wire_stops).
void OdeEngine::World::add_wire(int index) {
  const BodyDesc& desc = scene.bodies[static_cast<std::size_t>(index)];
  const Wire& wire = *desc.wire;
  const RigidBody& rb = bodies[static_cast<std::size_t>(index)];
  const Vec3 along = wire.to - wire.from;
  const double length = along.norm();
  const Vec3 axis = along / length;
  const Vec3 anchor = desc.frame.apply(wire.anchor);

  dBodyID carriage = dBodyCreate(world);
  // The body's mass and inertia scaled down: rotation is locked by the slider, so the inertia
  // only sets the conditioning of the joint rows.
  const double f = settings.wire_carriage_mass_fraction;
  const Mat3 I = f * rb.inertia_body;
  dMass mass;
  dMassSetParameters(&mass, f * rb.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
  dBodySetMass(carriage, &mass);
  dBodySetPosition(carriage, anchor.x(), anchor.y(), anchor.z());
  const Vec3 v = axis * axis.dot(rb.velocity_at(anchor));
  dBodySetLinearVel(carriage, v.x(), v.y(), v.z());

  dJointID slider = dJointCreateSlider(world, nullptr);
  dJointAttach(slider, carriage, nullptr);
  dJointSetSliderAxis(slider, axis.x(), axis.y(), axis.z());

  const dBodyID body = ode_bodies[static_cast<std::size_t>(index)];
  dJointID ball = dJointCreateBall(world, nullptr);
  dJointAttach(ball, carriage, body);
  dJointSetBallAnchor(ball, anchor.x(), anchor.y(), anchor.z());

  wire_stops.push_back({body, wire.from, axis, length, rb.frame_offset + wire.anchor});
}

// A contact joint at each end the anchor would pass in this step at its present velocity and
// gravity (or has passed): a one-sided constraint on the body's anchor velocity along the wire,
// with the distance past the end as its depth for ODE's error reduction. Rebuilt every step with
// the contacts.
void OdeEngine::World::add_wire_stops() {
  const double dt = scene.time.dt;
  const Vec3 g = scene.effects.gravity ? scene.gravity : Vec3::Zero();
  for (const WireStop& w : wire_stops) {
    const Vec3 x = from_ode(dBodyGetPosition(w.body));
    const Vec3 anchor = x + quat_from_ode(dBodyGetQuaternion(w.body)) * w.anchor_local;
    dVector3 v;
    dBodyGetPointVel(w.body, anchor.x(), anchor.y(), anchor.z(), v);
    const double s = (anchor - w.from).dot(w.axis);
    const double s_next = s + w.axis.dot(from_ode(v) + g * dt) * dt;
    for (const bool far_end : {false, true}) {
      const double past = far_end ? std::max(s, s_next) - w.length : -std::min(s, s_next);
      if (past <= 0.0) continue;
      const Vec3 normal = far_end ? Vec3(-w.axis) : w.axis;  // pushes the body back onto the wire
      dContact joint{};
      joint.surface.mode = 0;
      joint.surface.mu = 0.0;  // the wire has no friction
      joint.geom.pos[0] = anchor.x();
      joint.geom.pos[1] = anchor.y();
      joint.geom.pos[2] = anchor.z();
      joint.geom.normal[0] = normal.x();
      joint.geom.normal[1] = normal.y();
      joint.geom.normal[2] = normal.z();
      joint.geom.depth = std::max(0.0, far_end ? s - w.length : -s);
      dJointID j = dJointCreateContact(world, contact_joints, &joint);
      dJointAttach(j, w.body, nullptr);
    }
  }
}

void OdeEngine::World::near_callback(void* data, dGeomID o1, dGeomID o2) {
  static_cast<World*>(data)->collide_pair(o1, o2);
}

void OdeEngine::World::collide_pair(dGeomID o1, dGeomID o2) {
  const dBodyID b1 = dGeomGetBody(o1);
  const dBodyID b2 = dGeomGetBody(o2);
  if (!b1 && !b2) return;        // fixed bodies and the ground never move against each other
  if (b1 && b1 == b2) return;    // two boxes of one compound
  // The ground is always B, so that the normal (toward o1) points from the ground to the body.
  if (dGeomGetClass(o1) == dPlaneClass) std::swap(o1, o2);
  const GeomTag& ta = *static_cast<const GeomTag*>(dGeomGetData(o1));
  const GeomTag& tb = *static_cast<const GeomTag*>(dGeomGetData(o2));
  const bool with_ground = tb.body == kGround;

  const int n = dCollide(o1, o2, static_cast<int>(scratch.size()), scratch.data(), sizeof(dContactGeom));
  if (n <= 0) return;

  const Material m = combine_materials(material_of(ta.body), material_of(tb.body));
  const Effects& fx = scene.effects;
  OrientedBox box_a, box_b;
  if (!with_ground) {
    box_a = box_of_geom(o1);
    box_b = box_of_geom(o2);
  }
  for (int i = 0; i < n; ++i) {
    const dContactGeom& g = scratch[static_cast<std::size_t>(i)];
    dContact joint{};
    joint.geom = g;
    // Approx1: mu is a friction coefficient (the force limit follows the normal force), not a
    // force in newtons.
    joint.surface.mode = dContactApprox1;
    joint.surface.mu = fx.friction ? m.friction : 0.0;
    if (fx.restitution && m.restitution > 0.0) {
      joint.surface.mode |= dContactBounce;
      joint.surface.bounce = m.restitution;
      joint.surface.bounce_vel = settings.restitution_threshold;
    }
    dJointID j = dJointCreateContact(world, contact_joints, &joint);
    dJointAttach(j, dGeomGetBody(o1), dGeomGetBody(o2));

    const Contact c = with_ground ? ode_box_plane_contact(g) : ode_box_box_contact(box_a, box_b, g);
    contacts.push_back({c, ta.body, tb.body, ta.shape, tb.shape});
  }
}

OdeEngine::OdeEngine(const Scene& scene, const OdeSettings& settings)
    : world_(std::make_unique<World>(scene, settings)) {}

// After an ODE error its world may be half-way through a step (its arena in use, joints attached):
// tearing it down could assert again while the error unwinds. Such a world is never destroyed: it
// is kept until the process ends (still reachable, so that a leak checker does not report it).
OdeEngine::~OdeEngine() {
  if (world_ && world_->failed) {
    static auto* failed_worlds = new std::vector<std::unique_ptr<World>>;  // never destroyed
    failed_worlds->push_back(std::move(world_));
  }
}

void OdeEngine::step() {
  try {
    step_world();
  } catch (const OdeError&) {
    world_->failed = true;
    throw;
  }
}

void OdeEngine::step_world() {
  World& w = *world_;
  w.contacts.clear();
  dSpaceCollide(w.space, &w, &World::near_callback);
  w.add_wire_stops();
  if (w.settings.method == OdeStepMethod::Step) {
    dWorldStep(w.world, w.scene.time.dt);
  } else {
    dWorldQuickStep(w.world, w.scene.time.dt);
  }
  dJointGroupEmpty(w.contact_joints);
  ++w.steps;
}

double OdeEngine::time() const { return static_cast<double>(world_->steps) * world_->scene.time.dt; }

void OdeEngine::body_states(std::vector<BodyState>& out) const {
  const World& w = *world_;
  reference_detail::collect_body_states(w.bodies, out, [&](std::size_t i, BodyState& s) {
    const dBodyID body = w.ode_bodies[i];
    if (!body) return reference_detail::set_fixed_state(w.bodies[i], s);
    s.orientation = quat_from_ode(dBodyGetQuaternion(body));
    s.position = from_ode(dBodyGetPosition(body)) + s.orientation * w.bodies[i].frame_offset;
    s.velocity = from_ode(dBodyGetLinearVel(body));
    s.angular_velocity = from_ode(dBodyGetAngularVel(body));
  });
}

void OdeEngine::contacts(std::vector<BodyContact>& out) const { out = world_->contacts; }

std::uint64_t OdeEngine::messages() const { return ode_messages().count - world_->messages_at_start; }

std::string OdeEngine::last_message() const { return messages() > 0 ? ode_messages().last : std::string(); }

}  // namespace boxpile
