#include "boxpile/reference/bullet/bullet_engine.hpp"

#include <cmath>
#include <cstdint>
#include <utility>

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h>
#include <Eigen/Eigenvalues>

#include "boxpile/reference/body_states.hpp"
#include "boxpile/reference/bullet/bullet_support.hpp"
#include "boxpile/reference/convention.hpp"
#include "boxpile/sim/world.hpp"

namespace boxpile {

using namespace reference_detail;

namespace {

// What a collision object's user pointer carries for the material callbacks.
struct MaterialTag {
  Material material;
  const Effects* effects = nullptr;
};

// Bullet combines materials per contact through two global callbacks that see only the two
// collision objects; ours read the tags and apply the scene's rule (combine_materials) and its
// effects. Objects without a tag (not built by BulletEngine) keep Bullet's product rule.
btScalar combined_friction(const btCollisionObject* a, const btCollisionObject* b) {
  const auto* ta = static_cast<const MaterialTag*>(a->getUserPointer());
  const auto* tb = static_cast<const MaterialTag*>(b->getUserPointer());
  if (!ta || !tb) return a->getFriction() * b->getFriction();
  if (!ta->effects->friction) return 0.0;
  return combine_materials(ta->material, tb->material).friction;
}

btScalar combined_restitution(const btCollisionObject* a, const btCollisionObject* b) {
  const auto* ta = static_cast<const MaterialTag*>(a->getUserPointer());
  const auto* tb = static_cast<const MaterialTag*>(b->getUserPointer());
  if (!ta || !tb) return a->getRestitution() * b->getRestitution();
  if (!ta->effects->restitution) return 0.0;
  return combine_materials(ta->material, tb->material).restitution;
}

// Bullet damps as v <- v (1 - d)^dt each step; the scene's law dv/dt = -c v gives
// v <- v exp(-c dt), so d = 1 - exp(-c) matches it at every dt.
double damping_factor(double rate) { return 1.0 - std::exp(-rate); }

// Off-diagonal inertia below this fraction of the largest moment counts as diagonal: the body
// axes are then principal already and stay as they are.
constexpr double kDiagonalInertiaTolerance = 1e-12;

// Principal axes of an inertia tensor as a proper rotation V (I = V D V^T, det V = +1), and D.
std::pair<Mat3, Vec3> principal_axes(const Mat3& inertia) {
  const double largest = inertia.diagonal().cwiseAbs().maxCoeff();
  Mat3 off = inertia;
  off.diagonal().setZero();
  if (off.cwiseAbs().maxCoeff() <= kDiagonalInertiaTolerance * largest) {
    return {Mat3::Identity(), inertia.diagonal()};
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(inertia);
  Mat3 v = solver.eigenvectors();
  if (v.determinant() < 0.0) v.col(2) = -v.col(2);
  return {v, solver.eigenvalues()};
}

}  // namespace

struct BulletEngine::World {
  World(const Scene& scene, const BulletSettings& settings);
  ~World();

  void add_body(int index);
  void add_ground(const HalfSpace& ground);
  void add_wire(int index);
  void read_contacts();
  // Box `shape` of body `body` at the Bullet transform `t` of that body.
  OrientedBox box_at(int body, int shape, const btTransform& t) const;

  Scene scene;
  BulletSettings settings;
  std::vector<RigidBody> bodies;
  std::vector<Quat> principal;  // per body: Bullet's body axes in our body axes (V above)

  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};

  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> rigid;  // scene order
  std::unique_ptr<btRigidBody> ground;
  std::vector<std::unique_ptr<btTypedConstraint>> wires;
  std::vector<MaterialTag> tags;  // sized once: objects point into it
  std::vector<btTransform> before_step;  // body transforms the last step's contacts were found at
  std::vector<BodyContact> contacts;
  std::uint64_t steps = 0;
};

BulletEngine::World::World(const Scene& s, const BulletSettings& st)
    : scene(s), settings(st), bodies(make_bodies(s)) {
  gCalculateCombinedFrictionCallback = &combined_friction;
  gCalculateCombinedRestitutionCallback = &combined_restitution;
  if (settings.plane_iterations > 0) {
    config.setPlaneConvexMultipointIterations(settings.plane_iterations,
                                              settings.plane_min_points);
  }

  // Gravity first: addRigidBody gives each body the world's gravity (Bullet's own default is
  // (0, -10, 0)).
  const Vec3 g = scene.effects.gravity ? scene.gravity : Vec3::Zero();
  world.setGravity(to_bt(g));
  btContactSolverInfo& info = world.getSolverInfo();
  info.m_numIterations = settings.iterations;
  info.m_erp = settings.erp;
  info.m_erp2 = settings.split_erp;
  info.m_globalCfm = settings.cfm;
  info.m_splitImpulse = settings.split_impulse ? 1 : 0;
  info.m_splitImpulsePenetrationThreshold = settings.split_impulse_threshold;
  info.m_restitutionVelocityThreshold = settings.restitution_threshold;

  tags.reserve(bodies.size() + 1);
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) add_body(i);
  if (scene.ground) add_ground(*scene.ground);
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    if (scene.bodies[static_cast<std::size_t>(i)].wire) add_wire(i);
  }
  before_step.resize(bodies.size());
  std::size_t box_count = 0;
  for (const RigidBody& b : bodies) box_count += b.shapes.size();
  contacts.reserve(4 * (box_count + 1));
}

BulletEngine::World::~World() {
  for (auto& wire : wires) world.removeConstraint(wire.get());
  if (ground) world.removeRigidBody(ground.get());
  for (auto& body : rigid) world.removeRigidBody(body.get());
}

void BulletEngine::World::add_body(int index) {
  const RigidBody& rb = bodies[static_cast<std::size_t>(index)];
  const auto [v, moments] = principal_axes(rb.inertia_body);
  const Quat qv(v);
  principal.push_back(qv);

  // Shapes in the principal frame: x_principal = V^T x_body.
  btCollisionShape* shape = nullptr;
  const bool single_centred = rb.shapes.size() == 1 && rb.shapes[0].offset.isZero(0.0) &&
                              v.isIdentity(0.0) &&
                              rb.shapes[0].orientation.coeffs() == Quat::Identity().coeffs();
  if (single_centred) {
    shapes.push_back(std::make_unique<btBoxShape>(to_bt(rb.shapes[0].half_extents)));
    shape = shapes.back().get();
  } else {
    auto compound = std::make_unique<btCompoundShape>(/*enableDynamicAabbTree=*/false,
                                                      static_cast<int>(rb.shapes.size()));
    for (const BoxShape& s : rb.shapes) {
      shapes.push_back(std::make_unique<btBoxShape>(to_bt(s.half_extents)));
      const Pose child{v.transpose() * s.offset, (qv.conjugate() * s.orientation).normalized()};
      compound->addChildShape(to_bt(child), shapes.back().get());
    }
    shape = compound.get();
    shapes.push_back(std::move(compound));
  }

  const double mass = rb.fixed ? 0.0 : rb.mass;
  const btVector3 inertia = rb.fixed ? btVector3(0, 0, 0) : to_bt(moments);
  btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, shape, inertia);
  ci.m_startWorldTransform = to_bt(Pose{rb.x, (rb.q * qv).normalized()});
  ci.m_friction = rb.material.friction;        // reported only: the callbacks combine
  ci.m_restitution = rb.material.restitution;  // (see combined_friction)
  if (scene.effects.damping) {
    ci.m_linearDamping = damping_factor(scene.damping.linear);
    ci.m_angularDamping = damping_factor(scene.damping.angular);
  }
  auto body = std::make_unique<btRigidBody>(ci);
  tags.push_back({rb.material, &scene.effects});
  body->setUserPointer(&tags.back());
  body->setUserIndex(index);
  if (!rb.fixed) {
    if (settings.sleeping) {
      body->setSleepingThresholds(settings.linear_sleeping_threshold, settings.angular_sleeping_threshold);
    } else {
      body->setActivationState(DISABLE_DEACTIVATION);
    }
    body->setCcdMotionThreshold(settings.ccd_motion_threshold);
    body->setCcdSweptSphereRadius(settings.ccd_swept_sphere_radius);
    body->setLinearVelocity(to_bt(rb.v));
    body->setAngularVelocity(to_bt(rb.omega));
    int flags = body->getFlags();
    // Bullet integrates the gyroscopic term implicitly by default; the scene decides.
    if (!scene.effects.gyroscopic) flags &= ~BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY;
    body->setFlags(flags);
  }
  world.addRigidBody(body.get());
  rigid.push_back(std::move(body));
}

void BulletEngine::World::add_ground(const HalfSpace& half_space) {
  // btStaticPlaneShape: the plane n . x = constant, solid where n . x < constant.
  shapes.push_back(std::make_unique<btStaticPlaneShape>(to_bt(half_space.normal), half_space.offset));
  btRigidBody::btRigidBodyConstructionInfo ci(0.0, nullptr, shapes.back().get());
  ci.m_friction = scene.material.friction;
  ci.m_restitution = scene.material.restitution;
  ground = std::make_unique<btRigidBody>(ci);
  tags.push_back({scene.material, &scene.effects});
  ground->setUserPointer(&tags.back());
  ground->setUserIndex(kGround);
  world.addRigidBody(ground.get());
}

// The wire: one generic 6-dof constraint between the world and the body, with no carriage.
// Its frame A is fixed in the world at the wire's start, x along the wire; its frame B is the
// anchor in the body. The offset of B from A, measured along A's axes, is held at 0 across the
// wire (y and z locked) and between 0 and the wire's length along it (x limited); the three
// rotations are free (lower limit above upper). Errors are corrected as for contacts (Bullet's
// ERP 0.2, CFM 0).
void BulletEngine::World::add_wire(int index) {
  const BodyDesc& desc = scene.bodies[static_cast<std::size_t>(index)];
  const Wire& wire = *desc.wire;
  const RigidBody& rb = bodies[static_cast<std::size_t>(index)];
  const Vec3 along = wire.to - wire.from;
  const double length = along.norm();
  // Any right-handed frame with x along the wire.
  const Quat wire_frame = Quat::FromTwoVectors(Vec3::UnitX(), along / length);
  // The anchor in Bullet's body frame (centre of mass, principal axes), and the same world
  // orientation as frame A, so that the rotation between the frames starts at zero.
  const Quat body_to_world = rb.q * principal[static_cast<std::size_t>(index)];
  const Vec3 anchor = principal[static_cast<std::size_t>(index)].conjugate() * (rb.frame_offset + wire.anchor);
  const Pose frame_a{wire.from, wire_frame};
  const Pose frame_b{anchor, (body_to_world.conjugate() * wire_frame).normalized()};

  auto joint = std::make_unique<btGeneric6DofSpring2Constraint>(
      btTypedConstraint::getFixedBody(), *rigid[static_cast<std::size_t>(index)], to_bt(frame_a),
      to_bt(frame_b));
  joint->setLinearLowerLimit(btVector3(0, 0, 0));
  joint->setLinearUpperLimit(btVector3(length, 0, 0));
  joint->setAngularLowerLimit(btVector3(1, 1, 1));
  joint->setAngularUpperLimit(btVector3(-1, -1, -1));
  world.addConstraint(joint.get());
  wires.push_back(std::move(joint));
}

OrientedBox BulletEngine::World::box_at(int body, int shape, const btTransform& t) const {
  const RigidBody& rb = bodies[static_cast<std::size_t>(body)];
  const Quat q = from_bt(t.getRotation()) * principal[static_cast<std::size_t>(body)].conjugate();
  const BoxShape& s = rb.shapes[static_cast<std::size_t>(shape)];
  return OrientedBox::from(Pose{from_bt(t.getOrigin()), q} * Pose{s.offset, s.orientation}, s.half_extents);
}

void BulletEngine::World::read_contacts() {
  contacts.clear();
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold& pm = *dispatcher.getManifoldByIndexInternal(m);
    if (pm.getNumContacts() == 0) continue;
    // The ground is always B; otherwise A is Bullet's body 0.
    const bool a_is_body0 = pm.getBody0()->getUserIndex() != kGround;
    const btCollisionObject* oa = a_is_body0 ? pm.getBody0() : pm.getBody1();
    const btCollisionObject* ob = a_is_body0 ? pm.getBody1() : pm.getBody0();
    const int ia = oa->getUserIndex();
    const int ib = ob->getUserIndex();
    for (int i = 0; i < pm.getNumContacts(); ++i) {
      const btManifoldPoint& p = pm.getContactPoint(i);
      // Child indices of a compound; -1 for a body of one box.
      const int sa = std::max(0, a_is_body0 ? p.m_index0 : p.m_index1);
      const int sb = std::max(0, a_is_body0 ? p.m_index1 : p.m_index0);
      FeatureKind kind = FeatureKind::Plane;
      if (ib != kGround) {
        const Vec3 n = from_bt(a_is_body0 ? p.m_normalWorldOnB : -p.m_normalWorldOnB);
        kind = box_box_kind(box_at(ia, sa, before_step[static_cast<std::size_t>(ia)]),
                            box_at(ib, sb, before_step[static_cast<std::size_t>(ib)]), n);
      }
      contacts.push_back({contact_from_bullet(p, a_is_body0, kind), ia, ib, sa, sb});
    }
  }
}

BulletEngine::BulletEngine(const Scene& scene, const BulletSettings& settings)
    : world_(std::make_unique<World>(scene, settings)) {}

BulletEngine::~BulletEngine() = default;

void BulletEngine::step() {
  World& w = *world_;
  for (std::size_t i = 0; i < w.rigid.size(); ++i) w.before_step[i] = w.rigid[i]->getWorldTransform();
  // maxSubSteps = 0: exactly one internal step of dt (no fixed-step accumulator, no interpolation).
  w.world.stepSimulation(w.scene.time.dt, 0);
  w.read_contacts();
  ++w.steps;
}

double BulletEngine::time() const { return static_cast<double>(world_->steps) * world_->scene.time.dt; }

void BulletEngine::body_states(std::vector<BodyState>& out) const {
  const World& w = *world_;
  reference_detail::collect_body_states(w.bodies, out, [&](std::size_t i, BodyState& s) {
    const btRigidBody& body = *w.rigid[i];
    const btTransform& t = body.getWorldTransform();
    s.orientation = (from_bt(t.getRotation()) * w.principal[i].conjugate()).normalized();
    s.position = from_bt(t.getOrigin()) + s.orientation * w.bodies[i].frame_offset;
    s.velocity = from_bt(body.getLinearVelocity());
    s.angular_velocity = from_bt(body.getAngularVelocity());
  });
}

void BulletEngine::contacts(std::vector<BodyContact>& out) const { out = world_->contacts; }

}  // namespace boxpile
